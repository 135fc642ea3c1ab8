// SPDX-License-Identifier: BSD-3-Clause
// Example grids and helpers shared by the engine tests.
#pragma once
#include "Continuous/PolyhedralAnalysis.h"
#include "Core/LabelGrid.h"
#include "Formats/PolyhedralExample.h"

#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <mutex>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace msynth_test
{
/// A bundled polyhedral example (Data/Continuous/NAME), validated, and its analysis.
struct LoadedPolyhedra
{
  msynth::PolyhedralExample Example;
  msynth::PolyhedralAnalysis Analysis;
};

inline LoadedPolyhedra LoadPolyhedra(const std::string& name)
{
  LoadedPolyhedra l;
  l.Example = msynth::ReadOBJExample(std::string(MSYNTH_DATA) + "/Continuous/" + name);
  msynth::ValidateExample(l.Example);
  l.Analysis = msynth::PolyhedralAnalysis::Analyze(l.Example);
  return l;
}

/// A 2D grid from rows written top (largest y) first, as in the dissertation's figures.
inline msynth::LabelGrid Grid2D(const std::vector<std::vector<msynth::Label>>& rowsTopToBottom)
{
  const auto ny = static_cast<std::int64_t>(rowsTopToBottom.size());
  const auto nx = static_cast<std::int64_t>(rowsTopToBottom[0].size());
  msynth::LabelGrid g(nx, ny, 1);
  for (std::int64_t y = 0; y < ny; ++y)
    for (std::int64_t x = 0; x < nx; ++x)
      g.Set(x, y, 0,
        rowsTopToBottom[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)]);
  return g;
}

/// While alive, files may not grow past @p bytes (RLIMIT_FSIZE; SIGXFSZ ignored): writes past
/// it fail as they do on a full disk.
class FileSizeLimit
{
public:
  explicit FileSizeLimit(rlim_t bytes)
  {
    struct sigaction ignore = {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGXFSZ, &ignore, &this->OldAction);
    getrlimit(RLIMIT_FSIZE, &this->OldLimit);
    rlimit small = this->OldLimit;
    small.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &small);
  }
  ~FileSizeLimit()
  {
    setrlimit(RLIMIT_FSIZE, &this->OldLimit);
    sigaction(SIGXFSZ, &this->OldAction, nullptr);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
  struct sigaction OldAction = {};
  rlimit OldLimit{};
};
/// A small 3D village: ground (1), two-storey houses of walls (2) with roofs (3), empty (0).
inline msynth::LabelGrid Village()
{
  msynth::LabelGrid g(7, 7, 5, 0);
  for (std::int64_t y = 0; y < 7; ++y)
    for (std::int64_t x = 0; x < 7; ++x)
    {
      g.Set(x, y, 0, 1);
      if (x >= 2 && x <= 4 && y >= 2 && y <= 4)
      {
        g.Set(x, y, 1, 2);
        g.Set(x, y, 2, 2);
        g.Set(x, y, 3, 3);
      }
    }
  return g;
}

/// An all-gather among threads standing in for MPI ranks: each call blocks until every rank
/// has contributed, then returns all contributions in rank order.
class ThreadAllGather
{
public:
  explicit ThreadAllGather(int ranks)
    : Ranks(ranks)
    , Slots(static_cast<std::size_t>(ranks))
  {
  }
  std::vector<std::vector<char>> operator()(int rank, const std::vector<char>& mine)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    const std::int64_t generation = this->Generation;
    this->Slots[static_cast<std::size_t>(rank)] = mine;
    if (++this->Arrived == this->Ranks)
    {
      this->Result = this->Slots;
      this->Arrived = 0;
      ++this->Generation;
      this->Changed.notify_all();
    }
    else
      this->Changed.wait(lock, [&] { return this->Generation != generation; });
    return this->Result;
  }

private:
  int Ranks;
  int Arrived = 0;
  std::int64_t Generation = 0;
  std::vector<std::vector<char>> Slots, Result;
  std::mutex Mutex;
  std::condition_variable Changed;
};

} // namespace msynth_test
