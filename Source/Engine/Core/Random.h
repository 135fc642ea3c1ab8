// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Random.h
 * @brief A small, fully specified random generator (SplitMix64), so results are identical on
 * every platform and standard library for a given seed (std:: distributions are not).
 */
#include <cstdint>

namespace msynth
{

class Random
{
public:
  explicit Random(std::uint64_t seed)
    : State(seed)
  {
  }
  /// A generator for a sub-task (block, attempt) derived from a seed; independent of the
  /// order in which sub-tasks run.
  static Random Derived(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0)
  {
    Random r(seed);
    r.State ^= Mix(a + 0x632be59bd9b4e019ull);
    r.State = Mix(r.State);
    r.State ^= Mix(b + 0x9e3779b97f4a7c15ull);
    return r;
  }
  std::uint64_t Next() { return Mix(this->State += 0x9e3779b97f4a7c15ull); }
  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(this->Next() >> 11) * 0x1.0p-53; }
  /// Uniform in [0, n).
  std::uint64_t Below(std::uint64_t n) { return n ? this->Next() % n : 0; }

  static std::uint64_t Mix(std::uint64_t z)
  {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

private:
  std::uint64_t State;
};

} // namespace msynth
