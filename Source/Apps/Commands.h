// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Commands.h
 * @brief msynth's commands, one file each. Add<Command> adds the subcommand with its own typed,
 * validated options to the application and returns what runs it once the command line is
 * parsed (its exit status: 0 done, 1 failed or a check found problems).
 *
 *   info        InfoCommand.cxx        an example's labels and transitions (or neighbourhoods)
 *   analyze     AnalyzeCommand.cxx     the same as CSV tables plus the example as .vdb
 *   synthesize  SynthesizeCommand.cxx  discrete synthesis (label grids, tilesets, samples);
 *               ContinuousCommand.cxx  continuous synthesis (polyhedral examples)
 *   animate     AnimateCommand.cxx     time-varying synthesis
 *   check       CheckCommand.cxx       the independent checks of a model against its example
 *   batch       BatchCommand.cxx       every entry of a sample list (samples.xml), checked
 *   pattern     PatternCommand.cxx     factor-graph pattern synthesis (Yeh 2012, BLOCKSS)
 *   quality     PatternCommand.cxx     the KL divergence of a pattern to its exemplars
 */
#include <CLI/CLI.hpp>

#include <functional>

namespace msynth
{
namespace cli
{

using CommandRunner = std::function<int()>;

CommandRunner AddInfo(CLI::App& app);
CommandRunner AddAnalyze(CLI::App& app);
CommandRunner AddSynthesize(CLI::App& app);
CommandRunner AddAnimate(CLI::App& app);
CommandRunner AddCheck(CLI::App& app);
CommandRunner AddBatch(CLI::App& app);
CommandRunner AddPattern(CLI::App& app);
CommandRunner AddQuality(CLI::App& app);

} // namespace cli
} // namespace msynth
