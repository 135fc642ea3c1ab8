// SPDX-License-Identifier: BSD-3-Clause
#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/OutputFolder.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace
{
std::string Slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool AnyTemporaryLeftIn(const std::string& dir, const std::string& stem)
{
  DIR* d = opendir(dir.c_str());
  bool found = false;
  while (dirent* e = readdir(d))
  {
    const std::string name = e->d_name;
    found |= name.rfind(stem + ".tmp-", 0) == 0;
  }
  closedir(d);
  return found;
}
} // namespace

TEST(AtomicFile, WritesAndReplaces)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/atomic.txt";
  msynth::WriteFileAtomically(path, [](std::ostream& out) { out << "first"; });
  EXPECT_EQ(Slurp(path), "first");
  msynth::WriteFileAtomically(path, [](std::ostream& out) { out << "second"; });
  EXPECT_EQ(Slurp(path), "second");
}

TEST(AtomicFile, FailureLeavesOldContentAndNoTemporary)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/atomic-fail.txt";
  msynth::WriteFileAtomically(path, [](std::ostream& out) { out << "kept"; });
  EXPECT_THROW(msynth::WriteFileAtomically(path,
                 [](std::ostream& out)
                 {
                   out << "half";
                   throw msynth::Error("interrupted");
                 }),
    msynth::Error);
  EXPECT_EQ(Slurp(path), "kept");
  EXPECT_FALSE(AnyTemporaryLeftIn(MSYNTH_TEST_TMP, "atomic-fail.txt"));
}

TEST(AtomicFile, MissingFolderIsAClearError)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/no/such/folder/x.txt";
  try
  {
    msynth::WriteFileAtomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "expected an error";
  }
  catch (const msynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, AFullDiskIsSeenAndLeavesNothing)
{
  // Files may not grow past 4 KB (writes past it fail as on a full disk): the failure is seen,
  // named with the system's reason, and nothing is left.
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/full-disk.txt";
  std::remove(path.c_str());
  std::string what;
  try
  {
    const msynth_test::FileSizeLimit limit(4096);
    msynth::WriteFileAtomically(path, [](std::ostream& out) { out << std::string(100000, 'x'); });
  }
  catch (const msynth::Error& e)
  {
    what = e.what();
  }
  EXPECT_NE(what.find("'" + path + "': could not be written: File too large"), std::string::npos)
    << what;
  EXPECT_FALSE(std::ifstream(path).good());
  EXPECT_FALSE(AnyTemporaryLeftIn(MSYNTH_TEST_TMP, "full-disk.txt"));
}

// A signal-handling thread discards the staging folders while the run still writes into them
// (msynth's interruption path): nothing of the stage may remain, however the two interleave.
TEST(OutputFolder, DiscardWhileAnotherThreadWritesLeavesNothing)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/discard-race";
  msynth::RemoveTree(dir);
  ::mkdir(dir.c_str(), 0755); // exists beforehand, so it stays and can be listed
  for (int round = 0; round < 50; ++round)
  {
    std::atomic<bool> stop{ false };
    auto folder = std::make_unique<msynth::OutputFolder>(dir);
    const std::string stage = folder->Stage();
    std::thread writer(
      [&]
      {
        for (int i = 0; !stop; ++i)
        {
          std::ofstream(stage + "/file" + std::to_string(i % 64) + ".tmp-1") << i;
          ::mkdir((stage + "/sub").c_str(), 0755);
          std::ofstream(stage + "/sub/x") << i;
        }
      });
    std::this_thread::sleep_for(std::chrono::microseconds(200 * (round % 5)));
    EXPECT_EQ(msynth::OutputFolder::DiscardAll(), 1);
    stop = true;
    writer.join();
    folder.reset();
    DIR* d = ::opendir(dir.c_str());
    ASSERT_NE(d, nullptr);
    std::vector<std::string> left;
    while (const dirent* e = ::readdir(d))
      if (std::string(e->d_name) != "." && std::string(e->d_name) != "..")
        left.push_back(e->d_name);
    ::closedir(d);
    EXPECT_TRUE(left.empty()) << left.front();
  }
  msynth::RemoveTree(dir);
}

TEST(OutputFolder, MissingParentsAreMadeAndRemovedWhenNothingIsPublished)
{
  // --out output/village in a fresh checkout: the parents are made as with mkdir -p; a run
  // that publishes nothing leaves no trace of them, one that publishes keeps them.
  const std::string top = std::string(MSYNTH_TEST_TMP) + "/parents-" + std::to_string(::getpid());
  const std::string dir = top + "/a/b";
  {
    msynth::OutputFolder folder(dir);
    struct stat info;
    EXPECT_EQ(::stat((top + "/a").c_str(), &info), 0);
  }
  struct stat info;
  EXPECT_NE(::stat(top.c_str(), &info), 0) << "unpublished: the parents are removed";
  {
    msynth::OutputFolder folder(dir);
    msynth::WriteFileAtomically(folder.Stage() + "/x.txt", [](std::ostream& out) { out << "x"; });
    folder.Publish();
  }
  EXPECT_EQ(Slurp(dir + "/x.txt"), "x");
  // Interrupted (DiscardAll, as the signal thread calls it, while the folder object lives on):
  // the folders made for the run go too, so an interrupted run leaves nothing either.
  const std::string other = top + "-interrupted";
  msynth::OutputFolder interrupted(other + "/c/d");
  EXPECT_EQ(::stat((other + "/c/d").c_str(), &info), 0);
  msynth::OutputFolder::DiscardAll();
  EXPECT_NE(::stat(other.c_str(), &info), 0) << "interrupted: the folders made are removed";
}

// A run killed with SIGKILL leaves its staging folder behind: the next run into the folder
// removes the stages of processes that no longer exist, and keeps those of live ones.
TEST(OutputFolder, StagesOfKilledRunsAreRemovedByTheNextRun)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/stale-" + std::to_string(::getpid());
  msynth::RemoveTree(dir);
  ::mkdir(dir.c_str(), 0755);
  const pid_t gone = ::fork(); // a process id that no longer runs
  if (gone == 0)
    ::_exit(0);
  ASSERT_GT(gone, 0);
  int status = 0;
  ::waitpid(gone, &status, 0);
  const std::string stale = dir + "/.msynth-stage-" + std::to_string(gone) + "-0";
  const std::string discarded = dir + "/.msynth-discard-" + std::to_string(gone) + "-3";
  const std::string live = dir + "/.msynth-stage-1-0"; // init always runs
  for (const auto& stage : { stale, discarded, live })
  {
    ::mkdir(stage.c_str(), 0755);
    std::ofstream(stage + "/labels.vti") << "partial";
  }
  std::ofstream(dir + "/.msynth-stage-notapid") << "kept";
  {
    msynth::OutputFolder folder(dir);
    msynth::WriteFileAtomically(folder.Stage() + "/x.txt", [](std::ostream& out) { out << "x"; });
    folder.Publish();
  }
  struct stat info;
  EXPECT_NE(::stat(stale.c_str(), &info), 0) << "the killed run's stage is removed";
  EXPECT_NE(::stat(discarded.c_str(), &info), 0);
  EXPECT_EQ(::stat(live.c_str(), &info), 0) << "a live process's stage is kept";
  EXPECT_EQ(::stat((dir + "/.msynth-stage-notapid").c_str(), &info), 0);
  EXPECT_EQ(Slurp(dir + "/x.txt"), "x");
  msynth::RemoveTree(dir);
}

TEST(OutputFolder, ADamagedManifestIsRefusedBeforeAnythingIsRemovedOrPublished)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/manifest-" + std::to_string(::getpid());
  msynth::RemoveTree(dir);
  ::mkdir(dir.c_str(), 0755);
  std::ofstream(dir + "/labels.vti") << "earlier run";
  std::ofstream(dir + "/notes.txt") << "the user's";
  {
    std::ofstream manifest(dir + "/.msynth-outputs", std::ios::binary);
    manifest << "labels.vti\n" << std::string(1, '\0') << "\nmesh.vtp\n";
  }
  // The NUL byte once stood for the folder itself: the cleanup recursed without end.
  try
  {
    msynth::OutputFolder folder(dir);
    FAIL() << "a damaged manifest must be refused";
  }
  catch (const msynth::Error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(".msynth-outputs"), std::string::npos) << what;
    EXPECT_NE(what.find("line 2"), std::string::npos) << what;
  }
  EXPECT_EQ(Slurp(dir + "/labels.vti"), "earlier run");
  EXPECT_EQ(Slurp(dir + "/notes.txt"), "the user's");

  // Damaged after the run started: Publish refuses before it renames anything.
  ::unlink((dir + "/.msynth-outputs").c_str());
  {
    msynth::OutputFolder folder(dir);
    msynth::WriteFileAtomically(
      folder.Stage() + "/labels.vti", [](std::ostream& out) { out << "new"; });
    std::ofstream(dir + "/.msynth-outputs", std::ios::binary) << "../../etc\n";
    EXPECT_THROW(folder.Publish(), msynth::Error);
  }
  EXPECT_EQ(Slurp(dir + "/labels.vti"), "earlier run");
  EXPECT_EQ(Slurp(dir + "/notes.txt"), "the user's");

  // A path with a NUL byte is never an ancestor for RemoveTree.
  msynth::RemoveTree(dir + "/" + std::string(1, '\0'));
  EXPECT_EQ(Slurp(dir + "/notes.txt"), "the user's");
  msynth::RemoveTree(dir);
}

TEST(AtomicFile, ADeviceOrAPipeIsNeverWrittenOver)
{
  const std::string fifo = std::string(MSYNTH_TEST_TMP) + "/fifo-" + std::to_string(::getpid());
  ::unlink(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& path : { fifo, std::string("/dev/null") })
  {
    try
    {
      msynth::WriteFileAtomically(path, [](std::ostream& out) { out << "x"; });
      FAIL() << path << " must be refused";
    }
    catch (const msynth::Error& e)
    {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
    struct stat info;
    ASSERT_EQ(::stat(path.c_str(), &info), 0);
    EXPECT_FALSE(S_ISREG(info.st_mode)) << path << " was replaced by a file";
  }
  EXPECT_FALSE(AnyTemporaryLeftIn(MSYNTH_TEST_TMP, fifo.substr(fifo.rfind('/') + 1)));
  ::unlink(fifo.c_str());
  EXPECT_THROW(msynth::CheckReplaceable(MSYNTH_TEST_TMP), msynth::Error) << "a folder";
}

// What a run replaces of an earlier one is named (the command prints it, issue 49): the names
// it wrote again (a folder with a slash) and the earlier run's files it did not write again.
// Files the earlier runs did not list (a user's) are neither replaced nor removed.
TEST(OutputFolder, ReplacedAndRemovedNameTheEarlierRunsFiles)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/replaced-" + std::to_string(::getpid());
  msynth::RemoveTree(dir);
  const auto publish = [&dir](const std::vector<std::string>& files, bool folder)
  {
    auto run = std::make_unique<msynth::OutputFolder>(dir);
    for (const auto& name : files)
      msynth::WriteFileAtomically(run->Stage() + "/" + name, [](std::ostream& out) { out << "x"; });
    if (folder)
    {
      ::mkdir((run->Stage() + "/labels").c_str(), 0755);
      msynth::WriteFileAtomically(
        run->Stage() + "/labels/a.vti", [](std::ostream& out) { out << "a"; });
    }
    run->Publish();
    return run;
  };
  auto first = publish({ "labels.vti", "mesh.glb" }, true);
  EXPECT_TRUE(first->Replaced().empty());
  EXPECT_TRUE(first->Removed().empty());
  msynth::WriteFileAtomically(dir + "/notes.txt", [](std::ostream& out) { out << "mine"; });
  auto second = publish({ "labels.vti", "statistics.json" }, true);
  EXPECT_EQ(second->Replaced(), (std::vector<std::string>{ "labels.vti", "labels/" }));
  EXPECT_EQ(second->Removed(), (std::vector<std::string>{ "mesh.glb" }));
  EXPECT_EQ(Slurp(dir + "/notes.txt"), "mine");
  msynth::RemoveTree(dir);
}
