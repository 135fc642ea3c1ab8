// SPDX-License-Identifier: BSD-3-Clause
// ToIndex (Core/Index.h): the one conversion of a count to a container index.
#include "Core/Index.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace
{
enum class Small : std::int8_t
{
  Three = 3
};
} // namespace

TEST(Index, ConvertsEveryIntegerKindItIsGiven)
{
  EXPECT_EQ(msynth::ToIndex(0), 0u);
  EXPECT_EQ(msynth::ToIndex(std::int64_t{ 1 } << 40), std::size_t{ 1 } << 40);
  EXPECT_EQ(msynth::ToIndex(std::numeric_limits<std::int32_t>::max()), 2147483647u);
  EXPECT_EQ(msynth::ToIndex(std::uint8_t{ 255 }), 255u);
  EXPECT_EQ(msynth::ToIndex(Small::Three), 3u);
  const __int128 wide = static_cast<__int128>(1) << 50;
  EXPECT_EQ(msynth::ToIndex(wide), std::size_t{ 1 } << 50);
  static_assert(msynth::ToIndex(7) == 7u, "usable in constant expressions");
}

TEST(Index, ANegativeIndexStopsDebugAndSanitizerBuilds)
{
  // Release builds convert (and wrap) as static_cast does; debug builds assert.
  volatile std::int64_t negative = -1;
  EXPECT_DEBUG_DEATH(
    {
      const std::size_t i = msynth::ToIndex(static_cast<std::int64_t>(negative));
      EXPECT_EQ(i, std::numeric_limits<std::size_t>::max());
    },
    "negative value used as an index");
}
