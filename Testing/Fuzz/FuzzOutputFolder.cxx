// SPDX-License-Identifier: BSD-3-Clause
// An output folder's manifest (.msynth-outputs, Core/OutputFolder.h) as a damaged or hostile file:
// a run into the folder either refuses it (msynth::Error) or publishes and removes only files
// of the folder that the manifest lists, never the folder itself, its other files or anything
// outside it.
#include "Core/AtomicFile.h"
#include "Core/OutputFolder.h"
#include "FuzzCommon.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
bool Exists(const std::string& path)
{
  struct stat info;
  return ::lstat(path.c_str(), &info) == 0;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const char* shm = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  const std::string top = std::string(shm) + "/msynth-fuzz-folder-" + std::to_string(::getpid());
  const std::string dir = top + "/out";
  msynth::RemoveTree(top);
  ::mkdir(top.c_str(), 0755);
  ::mkdir(dir.c_str(), 0755);
  std::ofstream(top + "/outside.txt") << "outside";          // beside the folder
  std::ofstream(dir + "/kept.txt") << "unlisted";            // the user's, in the folder
  std::ofstream(dir + "/labels.vti") << "an earlier output"; // what a manifest may list
  std::ofstream(dir + "/.msynth-outputs", std::ios::binary)
    .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  bool published = false;
  msynth_fuzz::Expect(
    [&]
    {
      msynth::OutputFolder folder(dir);
      msynth::WriteFileAtomically(
        folder.Stage() + "/mesh.vtp", [](std::ostream& out) { out << "new"; });
      folder.Publish();
      published = true;
    });
  const std::string manifest(reinterpret_cast<const char*>(data), size);
  const bool listsKept = ("\n" + manifest + "\n").find("\nkept.txt\n") != std::string::npos;
  if (!Exists(dir) || !Exists(top + "/outside.txt") || (!listsKept && !Exists(dir + "/kept.txt")) ||
    (published && !Exists(dir + "/mesh.vtp")))
    std::abort(); // the cleanup reached what is not the last run's
  msynth::RemoveTree(top);
  return 0;
}
