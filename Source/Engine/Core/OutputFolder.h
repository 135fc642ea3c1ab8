// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file OutputFolder.h
 * @brief A run's outputs appear together or not at all.
 *
 * The files of a run are written into a staging folder inside the output folder
 * (`DIR/.msynth-stage-PID-N`), then published together: under a lock on the folder (so two
 * runs into one folder publish one after the other, never interleaved), each file is renamed
 * over its final name, and the files an earlier run listed in `DIR/.msynth-outputs` that this
 * run did not write (a longer snapshot sequence, a picture) are removed, so the folder holds
 * exactly one run's set. A run that fails or is interrupted discards its staging folder and
 * leaves the folder as it was.
 */
#include <string>
#include <vector>

namespace msynth
{

class OutputFolder
{
public:
  /// Creates @p dir when missing (and its missing parents, as mkdir -p) and a staging folder
  /// inside it. @throw Error naming @p dir when it is not a folder or not writable.
  explicit OutputFolder(const std::string& dir);
  /// Discards the staging folder unless Publish() succeeded (and the folder and its parents
  /// too, when this object created them and they are empty).
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Where the run writes its files.
  const std::string& Stage() const { return this->StagePath; }
  /// The output folder.
  const std::string& Final() const { return this->Dir; }
  /// Moves every staged file into the folder (see above). @throw Error on failure.
  void Publish();
  /// What Publish() replaced of an earlier run: the names already in the folder that this run
  /// wrote (a folder's with a slash: "labels/"), sorted.
  const std::vector<std::string>& Replaced() const { return this->ReplacedNames; }
  /// What Publish() removed: the earlier run's files that this run did not write again, sorted.
  const std::vector<std::string>& Removed() const { return this->RemovedNames; }

  /// Removes the staging folders of every OutputFolder not yet published, and the folders made
  /// for them when empty; for a signal-handling thread that then ends the process (not for
  /// signal handlers themselves). Returns how many
  /// it removed; @p published gets how many folders this process has published.
  static int DiscardAll(int* published = nullptr);

private:
  void RemoveCreated();

  std::string Dir;
  std::string StagePath;
  std::vector<std::string> ReplacedNames, RemovedNames;
  bool Published = false;
  bool Created = false; ///< the folder did not exist: removed again if nothing is published
  std::vector<std::string> CreatedParents; ///< missing parents made for it (outermost first)
};

/// Makes @p path and each of its missing ancestors, as `mkdir -p`; returns the folders it made,
/// outermost first. It stops at the first that cannot be made: a later mkdir of @p path says
/// why.
std::vector<std::string> MakeMissingFolders(const std::string& path);

/// The names in folder @p dir but "." and "..", sorted (none when it cannot be read).
std::vector<std::string> FolderEntries(const std::string& dir);

/// Removes @p path and, if it is a folder, everything in it. Errors are ignored.
void RemoveTree(const std::string& path);

} // namespace msynth
