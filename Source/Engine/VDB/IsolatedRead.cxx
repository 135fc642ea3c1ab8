// SPDX-License-Identifier: BSD-3-Clause
#include "VDB/IsolatedRead.h"
#include "VDB/VDBBackend.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "VDB/VDBLayout.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <new>
#include <poll.h>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tuple>
#include <unistd.h>

namespace msynth
{
namespace vdb
{
namespace detail
{

void PackHeader(Packer& p, const GridHeader& h)
{
  p.Str(h.Name);
  p.U64(static_cast<std::uint64_t>(h.Type));
  for (int a = 0; a < 3; ++a)
  {
    p.U64(static_cast<std::uint64_t>(static_cast<std::int64_t>(h.IndexMin[ToIndex(a)])));
    p.U64(static_cast<std::uint64_t>(h.Dims[ToIndex(a)]));
    p.F64(h.Origin[ToIndex(a)]);
    p.F64(h.Spacing[ToIndex(a)]);
  }
  p.F64(h.Background);
  p.Str(h.GridClass);
  p.Map(h.Metadata);
}

GridHeader UnpackHeader(Unpacker& u, std::int64_t maxVoxels)
{
  GridHeader h;
  h.Name = u.Str();
  h.Type = static_cast<ValueType>(u.U64(2));
  for (int a = 0; a < 3; ++a)
  {
    h.IndexMin[ToIndex(a)] = static_cast<std::int32_t>(static_cast<std::int64_t>(u.U64()));
    h.Dims[ToIndex(a)] = static_cast<std::int64_t>(u.U64(static_cast<std::uint64_t>(maxVoxels)));
    h.Origin[ToIndex(a)] = u.F64();
    h.Spacing[ToIndex(a)] = u.F64();
  }
  h.Background = u.F64();
  h.GridClass = u.Str();
  h.Metadata = u.Map();
  if (h.Dims[0] * h.Dims[1] > maxVoxels || h.NumberOfVoxels() > maxVoxels)
    throw Error::InFile(u.Path, "could not be read (a grid out of range from the reading process)");
  return h;
}

void WriteAll(int fd, const void* data, std::size_t n)
{
  const char* p = static_cast<const char*>(data);
  while (n > 0)
  {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR)
      continue;
    if (k <= 0)
      ::_exit(1); // the parent stopped listening
    p += k;
    n -= ToIndex(k);
  }
}

void SendBlock(int fd, const std::string& bytes)
{
  const std::uint64_t n = bytes.size();
  WriteAll(fd, "O", 1);
  WriteAll(fd, &n, 8);
  WriteAll(fd, bytes.data(), bytes.size());
}

namespace
{
/// The CPU time a reading child may use (a whole 2^28-voxel grid takes a few seconds).
constexpr rlim_t ChildSeconds = 60;

/// (state, CPU ticks, threads) of process @p pid from /proc/PID/stat; state 0 when unknown.
std::tuple<char, unsigned long long, long> ProcessState(pid_t pid)
{
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')'); // the command name may hold spaces
  if (close == std::string::npos)
    return { 0, 0, 0 };
  std::istringstream fields(text.substr(close + 2));
  char state = 0;
  std::string skip;
  unsigned long long user = 0, system = 0;
  long threads = 0;
  fields >> state;
  for (int i = 4; i <= 13; ++i) // fields 4-13
    fields >> skip;
  fields >> user >> system;
  for (int i = 16; i <= 19; ++i)
    fields >> skip;
  fields >> threads;
  return { fields ? state : '\0', user + system, threads };
}

/**
 * Waits until the child's first byte can be read. False when the child is deadlocked: forked
 * from a multithreaded process, it can inherit a lock another thread held (an allocator's, seen
 * with the sanitizers' allocator); one thread asleep without using the CPU for 2 s cannot wake.
 */
bool FirstByteComes(int fd, pid_t pid)
{
  unsigned long long lastTicks = ~0ull;
  int still = 0;
  for (;;)
  {
    pollfd p{ fd, POLLIN, 0 };
    const int ready = ::poll(&p, 1, 500);
    if (ready != 0)
      return true; // data, the end of the pipe, or an error: the reader sees which
    const auto [state, ticks, threads] = ProcessState(pid);
    if (state == 'S' && threads == 1 && ticks == lastTicks)
    {
      if (++still >= 4)
        return false;
    }
    else
      still = 0;
    lastTicks = ticks;
  }
}
/**
 * The reading child's limits: one TBB thread (the parent's workers do not exist here), an address
 * space that may grow by @p memoryBudget only (sizes a damaged file claims fail fast as
 * bad_alloc), bounded CPU time, and its output and errors sent nowhere.
 */
void PrepareChild(std::uint64_t memoryBudget)
{
  // Nothing the library or the C runtime prints in the child reaches the user (OpenVDB's
  // warnings, glibc's report of a heap a damaged file corrupted): the parent says what failed.
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null >= 0)
  {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
  }
  // A bounded time: a file that keeps the library busy longer is refused (SIGXCPU).
  rlimit cpu{ ChildSeconds, ChildSeconds + 1 };
  ::setrlimit(RLIMIT_CPU, &cpu);
  // One thread in the child: the parent's TBB workers do not exist here. Its address
  // space may grow by the budget only: sizes a damaged file claims fail fast as bad_alloc.
  LoadedBackend().LimitToOneThread();
  if (const std::uint64_t used = VirtualSize())
  {
    rlimit limit{};
    ::getrlimit(RLIMIT_AS, &limit);
    const std::uint64_t cap = used + memoryBudget;
    if (limit.rlim_cur == RLIM_INFINITY || cap < limit.rlim_cur)
    {
      limit.rlim_cur = static_cast<rlim_t>(cap);
      ::setrlimit(RLIMIT_AS, &limit);
    }
  }
}
} // namespace

void RunIsolated(const std::string& path, std::uint64_t memoryBudget,
  const std::function<void(int)>& child, const std::function<void(PipeReader&)>& parent)
{
  for (int attempt = 0; attempt < 5; ++attempt)
    if (RunIsolatedOnce(path, memoryBudget, child, parent))
      return;
  throw Error::InFile(path, "could not be read: the reading process deadlocked five times");
}

bool RunIsolatedOnce(const std::string& path, std::uint64_t memoryBudget,
  const std::function<void(int)>& child, const std::function<void(PipeReader&)>& parent)
{
  int fds[2];
  if (::pipe(fds) != 0)
    throw Error::InFile(path, std::string("could not be read: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error::InFile(path, std::string("could not be read: ") + std::strerror(errno));
  }
  if (pid == 0)
  {
    ::close(fds[0]);
    std::string message;
    try
    {
      PrepareChild(memoryBudget);
      child(fds[1]);
      ::_exit(0);
    }
    catch (const std::bad_alloc&)
    {
      message = Error::InFile(path, "needs more memory than is available").what();
    }
    catch (const std::exception& e)
    {
      message = e.what();
    }
    WriteAll(fds[1], "E", 1);
    WriteAll(fds[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(fds[1]);
  PipeReader reader(fds[0], path);
  const auto finish = [&](bool kill)
  {
    if (kill)
      ::kill(pid, SIGKILL);
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
    {
    }
    return status;
  };
  const auto crashed = [&](int status)
  {
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)
      return Error::InFile(path,
        "is corrupt or too large: reading it took more than " + std::to_string(ChildSeconds) +
          " s");
    return Error::InFile(path,
      WIFSIGNALED(status) ? "is corrupt: the OpenVDB library crashed reading it (signal " +
          std::to_string(WTERMSIG(status)) + ")"
                          : std::string("is corrupt: the OpenVDB library failed reading it"));
  };
  if (!FirstByteComes(fds[0], pid))
  {
    finish(true); // deadlocked at birth: try again
    return false;
  }
  char kind = 0;
  if (reader.Some(&kind, 1) != 1 || (kind != 'O' && kind != 'E'))
    throw crashed(finish(false));
  if (kind == 'E')
  {
    std::string message(4096, '\0');
    message.resize(reader.Some(&message[0], message.size()));
    finish(false);
    throw Error(message);
  }
  try
  {
    parent(reader);
    char extra = 0;
    const bool more = reader.Some(&extra, 1) != 0;
    const int status = finish(more);
    if (more || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw crashed(status);
  }
  catch (const Error&)
  {
    const int status = finish(true);
    if (WIFSIGNALED(status) && WTERMSIG(status) != SIGKILL)
      throw crashed(status);
    throw;
  }
  return true;
}

} // namespace detail

FileContents ReadFile(const std::string& path, const ReadOptions& options)
{
  detail::InitializeLibrary();
  // The dense grids, the tree they come from and OpenVDB's buffers.
  const std::uint64_t budget =
    static_cast<std::uint64_t>(options.MaxVoxels) * 36 + (std::uint64_t(1) << 30);
  FileContents contents;
  CheckLayout(path);
  detail::RunIsolated(
    path, budget,
    [&](int fd)
    {
      const FileContents read = detail::ReadFileHere(path, options);
      // The headers first (sizes included), then each grid's values as they are in memory.
      detail::Packer p;
      p.Map(read.Metadata);
      p.U64(read.Grids.size());
      for (const auto& g : read.Grids)
      {
        detail::PackHeader(p, g.Header);
        p.U64(g.Ints.size());
        p.U64(g.Floats.size());
      }
      detail::SendBlock(fd, p.Bytes);
      for (const auto& g : read.Grids)
      {
        detail::WriteAll(fd, g.Ints.data(), g.Ints.size() * sizeof(std::int32_t));
        detail::WriteAll(fd, g.Floats.data(), g.Floats.size() * sizeof(float));
      }
    },
    [&](detail::PipeReader& reader)
    {
      const std::string headers = reader.Block();
      detail::Unpacker u{ headers, path };
      contents.Metadata = u.Map();
      for (std::uint64_t count = u.U64(100000); count > 0; --count)
      {
        DenseGrid g;
        g.Header = detail::UnpackHeader(u, options.MaxVoxels);
        const auto voxels = static_cast<std::uint64_t>(g.Header.NumberOfVoxels());
        const std::uint64_t ints = u.U64(voxels), floats = u.U64(3 * voxels);
        const std::uint64_t expected =
          voxels * static_cast<std::uint64_t>(ComponentCount(g.Header.Type));
        if ((g.Header.Type == ValueType::Int32 ? ints : floats) != expected || (ints && floats))
          throw Error::InFile(path, "is corrupt: the OpenVDB library failed reading it");
        CheckMemory((ints + floats) * 4, "reading grid '" + g.Header.Name + "' of '" + path + "'");
        contents.Grids.push_back(std::move(g));
        ResizeOnHugePages(contents.Grids.back().Ints, ToIndex(ints));
        ResizeOnHugePages(contents.Grids.back().Floats, ToIndex(floats));
      }
      for (auto& g : contents.Grids)
      {
        reader.Exact(g.Ints.data(), g.Ints.size() * sizeof(std::int32_t));
        reader.Exact(g.Floats.data(), g.Floats.size() * sizeof(float));
      }
    });
  return contents;
}

std::vector<GridSummary> ListGrids(const std::string& path, MetadataMap* fileMetadata)
{
  detail::InitializeLibrary();
  std::string payload;
  CheckLayout(path);
  detail::RunIsolated(
    path, std::uint64_t(8) << 30,
    [&](int fd)
    {
      MetadataMap meta;
      const std::vector<GridSummary> grids = detail::ListGridsHere(path, &meta);
      detail::Packer p;
      p.Map(meta);
      p.U64(grids.size());
      for (const auto& g : grids)
      {
        p.Str(g.Name);
        p.Str(g.TypeName);
        p.Str(g.GridClass);
        p.Map(g.Metadata);
        p.U64(static_cast<std::uint64_t>(g.ActiveVoxelCount));
        for (std::size_t a = 0; a < 3; ++a)
        {
          p.U64(static_cast<std::uint64_t>(static_cast<std::uint32_t>(g.ActiveMin[a])));
          p.U64(static_cast<std::uint64_t>(static_cast<std::uint32_t>(g.ActiveMax[a])));
          p.F64(g.VoxelSize[a]);
        }
      }
      detail::SendBlock(fd, p.Bytes);
    },
    [&payload](detail::PipeReader& reader) { payload = reader.Block(); });
  detail::Unpacker u{ payload, path };
  MetadataMap meta = u.Map();
  if (fileMetadata)
    *fileMetadata = meta;
  std::vector<GridSummary> result;
  for (std::uint64_t n = u.U64(100000); n > 0; --n)
  {
    GridSummary g;
    g.Name = u.Str();
    g.TypeName = u.Str();
    g.GridClass = u.Str();
    g.Metadata = u.Map();
    g.ActiveVoxelCount = static_cast<std::int64_t>(u.U64());
    for (std::size_t a = 0; a < 3; ++a)
    {
      g.ActiveMin[a] = static_cast<std::int32_t>(static_cast<std::uint32_t>(u.U64(UINT32_MAX)));
      g.ActiveMax[a] = static_cast<std::int32_t>(static_cast<std::uint32_t>(u.U64(UINT32_MAX)));
      g.VoxelSize[a] = u.F64();
    }
    result.push_back(std::move(g));
  }
  return result;
}

} // namespace vdb
} // namespace msynth
