// SPDX-License-Identifier: BSD-3-Clause
#include "Core/OutputFolder.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/FileBytes.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <map>
#include <mutex>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace msynth
{
namespace
{
constexpr const char* ManifestName = ".msynth-outputs";
constexpr const char* LockName = ".msynth-lock";

/// The staging folders not yet published or discarded (for DiscardAll). Never destroyed: a
/// signal-handling thread may call DiscardAll while the process exits.
std::mutex& RegistryMutex()
{
  static std::mutex* m = new std::mutex;
  return *m;
}
/// Each staging folder, with the folders made for it (the output folder, its missing parents;
/// innermost first), which an interrupted run removes again when they are empty.
std::map<std::string, std::vector<std::string>>& Registry()
{
  static auto* r = new std::map<std::string, std::vector<std::string>>;
  return *r;
}
/// Folders published by this process (under RegistryMutex).
int& PublishedCount()
{
  static int n = 0;
  return n;
}

/// An exclusive lock on DIR/.msynth-lock for the duration of a publication.
class FolderLock
{
public:
  explicit FolderLock(const std::string& dir)
    : Fd(::open((dir + "/" + LockName).c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644))
  {
    if (this->Fd < 0)
      throw Error::InFile(
        dir, std::string("cannot be locked for writing: ") + std::strerror(errno));
    while (::flock(this->Fd, LOCK_EX) != 0 && errno == EINTR)
    {
    }
  }
  ~FolderLock() { ::close(this->Fd); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

private:
  int Fd;
};
/// A name the manifest may list: a file of the folder's own, not hidden, without control
/// characters.
bool IsListedName(const std::string& name)
{
  const bool control = std::any_of(name.begin(), name.end(),
    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  return !name.empty() && !control && name.find('/') == std::string::npos && name[0] != '.' &&
    name.size() <= 255;
}

/**
 * The names the last run published into @p dir (its manifest; none when there is none).
 * @throw Error naming the manifest when a line is not a plain file name (a NUL byte or another
 * control character, a slash, a leading dot, "..", more than 255 bytes): a damaged manifest
 * could make the cleanup remove the folder itself, so nothing is removed or published then.
 */
std::vector<std::string> ReadManifest(const std::string& dir)
{
  const std::string path = dir + "/" + ManifestName;
  struct stat info;
  if (::lstat(path.c_str(), &info) != 0)
    return {};
  const auto damaged = [&path](const std::string& problem)
  {
    return Error::InFile(path,
      "is damaged (" + problem +
        "); remove it to let this run replace the folder's files without cleaning up after the "
        "last run");
  };
  if (!S_ISREG(info.st_mode))
    throw damaged("not a regular file");
  const std::string text = ReadFileBytes(path, 1 << 20, "is larger than 1 MB");
  std::vector<std::string> names;
  std::size_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line)
  {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string name = text.substr(start, end - start);
    start = end + 1;
    if (name.empty())
      continue;
    if (!IsListedName(name))
      throw damaged("line " + std::to_string(line) + " is not a file name");
    names.push_back(std::move(name));
  }
  return names;
}

/// The process id in a staging folder's name (".msynth-stage-PID-N", ".msynth-discard-PID-N"),
/// or 0 when @p name is no such folder.
pid_t StagePid(const std::string& name)
{
  for (const char* prefix : { ".msynth-stage-", ".msynth-discard-" })
  {
    const std::size_t n = std::strlen(prefix);
    if (name.compare(0, n, prefix) != 0)
      continue;
    const std::size_t dash = name.find('-', n);
    const std::string digits = name.substr(n, dash == std::string::npos ? dash : dash - n);
    if (digits.empty() || digits.size() > 9 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
      return 0;
    return static_cast<pid_t>(std::stol(digits));
  }
  return 0;
}

/// Removes the staging folders in @p dir left by runs that were killed (SIGKILL, a power cut):
/// those whose process no longer exists. Live runs' stages, and this process's, are kept.
void RemoveStaleStages(const std::string& dir)
{
  for (const auto& name : FolderEntries(dir))
  {
    const pid_t pid = StagePid(name);
    if (pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH)
      RemoveTree(dir + "/" + name);
  }
}
} // namespace

std::vector<std::string> FolderEntries(const std::string& dir)
{
  std::vector<std::string> names;
  if (DIR* d = ::opendir(dir.c_str()))
  {
    while (const dirent* e = ::readdir(d))
    {
      const std::string name = e->d_name;
      if (name != "." && name != "..")
        names.push_back(name);
    }
    ::closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void RemoveTree(const std::string& path)
{
  struct stat info;
  // A name with a NUL byte would stand for a shorter path (an ancestor, the folder itself).
  if (path.find('\0') != std::string::npos || ::lstat(path.c_str(), &info) != 0)
    return;
  if (S_ISDIR(info.st_mode))
  {
    for (const auto& name : FolderEntries(path))
      RemoveTree(path + "/" + name);
    ::rmdir(path.c_str());
  }
  else
  {
    ::unlink(path.c_str());
  }
}

OutputFolder::OutputFolder(const std::string& dir)
  : Dir(dir.empty() ? std::string(".") : dir)
{
  struct stat info;
  if (::stat(this->Dir.c_str(), &info) == 0)
  {
    if (!S_ISDIR(info.st_mode))
      throw Error::InFile(this->Dir, "exists and is not a folder");
  }
  else
  {
    // Missing parents too, as mkdir -p (removed again when nothing is published).
    const auto slash = this->Dir.find_last_of('/');
    if (slash != std::string::npos && slash > 0)
      this->CreatedParents = MakeMissingFolders(this->Dir.substr(0, slash));
    if (::mkdir(this->Dir.c_str(), 0755) == 0)
      this->Created = true;
    else if (errno != EEXIST)
      throw Error::InFile(this->Dir, std::string("cannot create folder: ") + std::strerror(errno));
  }
  ReadManifest(this->Dir); // refused before the run, not after it (Publish reads it again)
  RemoveStaleStages(this->Dir);
  static std::atomic<unsigned> counter{ 0 };
  this->StagePath =
    this->Dir + "/.msynth-stage-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::lock_guard<std::mutex> lock(RegistryMutex());
  if (::mkdir(this->StagePath.c_str(), 0755) != 0)
  {
    const std::string reason = std::strerror(errno);
    this->RemoveCreated();
    throw Error::InFile(this->Dir, "cannot be written to: " + reason);
  }
  std::vector<std::string> made(this->CreatedParents.rbegin(), this->CreatedParents.rend());
  if (this->Created)
    made.insert(made.begin(), this->Dir);
  Registry().emplace(this->StagePath, std::move(made));
}

OutputFolder::~OutputFolder()
{
  std::lock_guard<std::mutex> lock(RegistryMutex());
  if (Registry().erase(this->StagePath))
    RemoveTree(this->StagePath);
  if (!this->Published)
    this->RemoveCreated();
}

std::vector<std::string> MakeMissingFolders(const std::string& path)
{
  std::vector<std::string> missing; // innermost first
  for (std::string folder = path;;)
  {
    struct stat info;
    if (folder.empty() || ::stat(folder.c_str(), &info) == 0)
      break;
    missing.push_back(folder);
    const auto slash = folder.find_last_of('/');
    if (slash == std::string::npos || slash == 0)
      break;
    folder.resize(slash);
  }
  std::vector<std::string> made;
  for (auto it = missing.rbegin(); it != missing.rend(); ++it)
  {
    if (::mkdir(it->c_str(), 0755) != 0 && errno != EEXIST)
      break;
    made.push_back(*it);
  }
  return made;
}

void OutputFolder::RemoveCreated()
{
  if (this->Created)
    ::rmdir(this->Dir.c_str()); // only if empty
  for (auto it = this->CreatedParents.rbegin(); it != this->CreatedParents.rend(); ++it)
    ::rmdir(it->c_str());
}

void OutputFolder::Publish()
{
  std::lock_guard<std::mutex> registryLock(RegistryMutex());
  if (!Registry().count(this->StagePath))
    throw Error::InFile(this->Dir, "was discarded before its outputs were published");
  FolderLock folderLock(this->Dir);
  const std::vector<std::string> written = FolderEntries(this->StagePath);
  // What the previous run published, less what this run replaces.
  std::vector<std::string> stale;
  for (auto& name : ReadManifest(this->Dir))
    if (!std::binary_search(written.begin(), written.end(), name))
      stale.push_back(std::move(name));
  std::vector<std::string> replaced;   // folders this run replaces, removed once it is published
  std::vector<std::string> said, gone; // what it replaces and removes, as Replaced() names them
  for (const auto& name : written)
  {
    const std::string target = this->Dir + "/" + name;
    struct stat info;
    const bool there = ::lstat(target.c_str(), &info) == 0;
    if (there && name[0] != '.')
      said.push_back(name + (S_ISDIR(info.st_mode) ? "/" : ""));
    if (there && S_ISDIR(info.st_mode))
    {
      replaced.push_back(this->Dir + "/.msynth-discard-" + std::to_string(::getpid()) + "-" +
        std::to_string(replaced.size()) + "-" + name);
      if (std::rename(target.c_str(), replaced.back().c_str()) != 0)
        throw Error::InFile(target, std::string("could not be replaced: ") + std::strerror(errno));
    }
    if (std::rename((this->StagePath + "/" + name).c_str(), target.c_str()) != 0)
      throw Error::InFile(target, std::string("could not be published: ") + std::strerror(errno));
  }
  for (const auto& name : stale)
  {
    struct stat info;
    const std::string path = this->Dir + "/" + name;
    if (::lstat(path.c_str(), &info) == 0)
      gone.push_back(name + (S_ISDIR(info.st_mode) ? "/" : ""));
    RemoveTree(path);
  }
  std::sort(said.begin(), said.end());
  std::sort(gone.begin(), gone.end());
  this->ReplacedNames = std::move(said);
  this->RemovedNames = std::move(gone);
  for (const auto& folder : replaced)
    RemoveTree(folder);
  WriteFileAtomically(this->Dir + "/" + ManifestName,
    [&](std::ostream& out)
    {
      for (const auto& name : written)
        if (IsListedName(name))
          out << name << "\n";
    });
  Registry().erase(this->StagePath);
  ::rmdir(this->StagePath.c_str());
  this->Published = true;
  ++PublishedCount();
}

int OutputFolder::DiscardAll(int* published)
{
  std::lock_guard<std::mutex> lock(RegistryMutex());
  const int discarded = static_cast<int>(Registry().size());
  static std::atomic<unsigned> counter{ 0 };
  for (const auto& [stage, made] : Registry())
  {
    // Other threads may still be writing into the stage: move it away first, so that no file
    // can appear in it after it is listed (their paths no longer resolve), then remove it.
    const std::string doomed = stage.substr(0, stage.rfind('/') + 1) + ".msynth-discard-" +
      std::to_string(::getpid()) + "-" + std::to_string(counter++);
    RemoveTree(std::rename(stage.c_str(), doomed.c_str()) == 0 ? doomed : stage);
    for (const auto& folder : made)
      ::rmdir(folder.c_str()); // only if empty: the folder was as it is now before the run
  }
  Registry().clear();
  if (published)
    *published = PublishedCount();
  return discarded;
}

} // namespace msynth
