// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How msynth's help reads for a newcomer: option values named as they are typed ("--size N N N",
// "--order scanline|random|entropy") with their defaults and "required" in words, instead of
// CLI11's types and validators ("FLOAT:NUMBER>=0=[] x 3 REQUIRED"); and the name a mistyped
// command or option was probably meant to be.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace msynth
{
namespace cli
{

/// The formatter every command's --help uses.
std::shared_ptr<CLI::Formatter> MakeHelpFormatter();

/// The name of @p names closest to @p typed (a mistyped option or command) when it is close
/// enough to be meant (at most a third of its letters changed, added or left out); "" if none.
std::string ClosestName(const std::string& typed, const std::vector<std::string>& names);

} // namespace cli
} // namespace msynth
