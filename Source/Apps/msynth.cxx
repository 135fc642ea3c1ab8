// SPDX-License-Identifier: BSD-3-Clause
// msynth: ModelSynth's command line. Each command is in its own file (Commands.h lists them)
// and drives the same VTK algorithms that Python and ParaView use.
//
//   msynth info EXAMPLE                  labels, counts and transition tables (Eq. 3.2)
//   msynth analyze EXAMPLE [--out DIR]   the analysis as CSV tables plus the example as .vdb
//   msynth synthesize EXAMPLE --size ... discrete or continuous model synthesis
//   msynth animate EXAMPLE... --size ... --frames N   time-varying synthesis
//   msynth check EXAMPLE MODEL           the independent check of a model
//   msynth batch SAMPLES.xml             every entry of a sample list, each output checked
//   msynth pattern EXEMPLAR --size ...   tile patterns with factor graphs; `quality` scores one
//   msynth CMD --help                    a command's options
//
// Exit status: 0 on success, 1 when the work fails (bad input, unwritable output) or a check
// finds problems, 2 on a usage error. Errors are one line on stderr naming the file and the
// problem; usage errors end with "see msynth CMD --help".
#include "Commands.h"
#include "Common.h"
#include "Examples.h"
#include "HelpText.h"

#include "vtkLogger.h"
#include "vtkOutputWindow.h"

#include "Core/Error.h"
#include "Core/OutputFolder.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <pthread.h>
#include <regex>
#include <thread>
#include <unistd.h>

namespace
{

const char* const Footer = R"(
EXAMPLE is a label grid (.vti with an integer array 'Label', the original program's .txt format,
or MagicaVoxel .vox), a simple-tiled tileset (.xml) or, for continuous synthesis, a polyhedral
example (.obj, .vtp, .ply, .stl). DIR, the --out folder, defaults to ./msynth-output (to
./msynth-batch for msynth batch).
)";

/// main()'s exit status once it is known (-1 before): a signal arriving after the work is
/// done ends the process with that status, silently, and discards nothing.
std::atomic<int> FinalStatus{ -1 };

/**
 * SIGINT and SIGTERM (and SIGHUP) are taken by one thread: it discards the staging folders of
 * the run, says so in one line and ends the process with 128 + the signal's number, whatever
 * stage the run is in. The signals are blocked in every other thread (they inherit the mask).
 */
void HandleInterruptions()
{
  static sigset_t signals;
  sigemptyset(&signals);
  for (int sig : { SIGINT, SIGTERM, SIGHUP })
  {
    sigaddset(&signals, sig);
  }
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread(
    []()
    {
      int sig = 0;
      while (sigwait(&signals, &sig) != 0)
      {
      }
      if (FinalStatus >= 0)
      {
        std::_Exit(FinalStatus);
      }
      // A folder with nothing to go on from (a stream before its first slab): moved away
      // first, so that no file appears in it while it is removed, and before the staging
      // folders, so that an output folder the run made is empty again and removed with them.
      const std::string discard = msynth::cli::InterruptDiscard();
      if (!discard.empty())
      {
        const std::string doomed = discard.substr(0, discard.rfind('/') + 1) + ".msynth-discard-" +
          std::to_string(::getpid()) + "-interrupted";
        msynth::RemoveTree(std::rename(discard.c_str(), doomed.c_str()) == 0 ? doomed : discard);
      }
      int published = 0;
      const std::string done = msynth::cli::InterruptDone(); // (a batch: more was to come)
      if (msynth::OutputFolder::DiscardAll(&published) == 0 && published > 0 && done.empty())
      {
        std::_Exit(0); // the run's outputs are complete: only its last words are lost
      }
      const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
      const std::string note = msynth::cli::InterruptNote();
      std::fprintf(stderr, "\nmsynth: interrupted (%s); %s%s%s\n", name,
        done.empty() ? "no outputs were written" : done.c_str(), note.empty() ? "" : "; ",
        note.c_str());
      std::fflush(stderr);
      std::_Exit(128 + sig);
    })
    .detach();
}

/// The subcommand the command line named ("" when none was recognized).
std::string CommandOf(const CLI::App& app)
{
  const auto parsed = app.get_subcommands();
  return parsed.empty() ? std::string() : parsed.front()->get_name();
}

/// The registered commands, as "info, analyze, ... or quality" (in the order of --help).
std::string CommandList(CLI::App& app)
{
  const auto commands = app.get_subcommands({});
  std::string list;
  for (std::size_t i = 0; i < commands.size(); ++i)
  {
    list += (i == 0 ? "" : i + 1 == commands.size() ? " or " : ", ") + commands[i]->get_name();
  }
  return list;
}

/**
 * What the command line held that no command or option took, as a usage message; "" when
 * everything was understood. CLI11 checks required options before it reports extras, so a
 * misspelt option would otherwise be reported as the option it was meant to be, missing.
 */
std::string NotUnderstood(CLI::App& app)
{
  // What was not understood, in the order given.
  const std::string command = CommandOf(app);
  auto extras = app.remaining(); // the command's own, and what fell through to msynth
  if (!command.empty())
  {
    const auto own = app.get_subcommand(command)->remaining();
    extras.insert(extras.begin(), own.begin(), own.end());
  }
  if (extras.empty())
  {
    return std::string();
  }
  const std::string& first = extras.front();
  if (command.empty() && !first.empty() && first[0] != '-')
  {
    std::vector<std::string> names;
    for (const CLI::App* c : app.get_subcommands({}))
      names.push_back(c->get_name());
    const std::string meant = msynth::cli::ClosestName(first, names);
    return "unknown command '" + first + "' (" +
      (meant.empty() ? CommandList(app) : "did you mean '" + meant + "'?") + ")";
  }
  for (const auto& extra : extras)
  {
    if (extra.size() > 1 && extra[0] == '-')
    {
      // The command's options and msynth's own (they fall through), by their long names.
      std::vector<std::string> names;
      for (const CLI::App* scope : { command.empty() ? &app : app.get_subcommand(command), &app })
        for (const CLI::Option* option : scope->get_options())
          for (const auto& name : option->get_lnames())
            names.push_back("--" + name);
      const std::string typed = extra.substr(0, extra.find('='));
      const std::string meant = msynth::cli::ClosestName(typed, names);
      return "unknown option '" + extra + "'" +
        (meant.empty() ? std::string() : " (did you mean " + meant + "?)");
    }
  }
  return "unexpected argument '" + first + "'";
}

/// `msynth check MODEL` with the example left out: the model msynth wrote names the example it
/// was made from, and the message the command to run ("" for anything else).
std::string MissingExample(CLI::App& app)
{
  if (CommandOf(app) != "check")
    return "";
  CLI::App* check = app.get_subcommand("check");
  const CLI::Option* example = check->get_option("EXAMPLE");
  if (example->count() != 1 || check->get_option("MODEL")->count() != 0)
    return "";
  const std::string given = example->results().front();
  std::string from;
  try
  {
    from = msynth::cli::WrittenExample(given);
  }
  catch (const std::exception&)
  {
  }
  return from.empty() ? ""
                      : "EXAMPLE is missing: '" + given + "' is a model msynth wrote from " + from +
      " (msynth check " + from + " " + given + ")";
}

/// "msynth[ CMD]: WHAT; see msynth[ CMD] --help" on stderr; exit status 2.
/// CLI11's count messages ("--size: At least 3 required but received 2") in the words of the
/// other messages ("--size takes 3 values, not 2"); others as they are.
std::string InOwnWords(const CLI::ParseError& e)
{
  static const std::regex count("(.*): At (?:least|Most) ([0-9]+) required but received ([0-9]+)");
  std::smatch m;
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) && std::regex_match(what, m, count))
    return m[1].str() + " takes " + m[2].str() + (m[2] == "1" ? " value" : " values") + ", not " +
      m[3].str();
  return what;
}

int UsageFailure(const std::string& command, const std::string& what)
{
  const std::string name = command.empty() ? "msynth" : "msynth " + command;
  std::cerr << name << ": " << msynth::Printable(what) << "; see " << name << " --help\n";
  return 2;
}

int Main(int argc, char* argv[])
{
  CLI::App app(
    "msynth: model synthesis from a small example (ModelSynth " MSYNTH_VERSION ")", "msynth");
  app.footer(Footer);
  app.formatter(msynth::cli::MakeHelpFormatter()); // before the commands: they inherit it
  app.option_defaults()->always_capture_default(); // --help shows each option's default
  app.require_subcommand(0, 1);
  bool version = false, verbose = false;
  app.add_flag("--version", version, "print the version");
  app.add_flag("--verbose", verbose, "show VTK's own diagnostics as well");
  std::map<std::string, msynth::cli::CommandRunner> commands;
  commands["info"] = msynth::cli::AddInfo(app);
  commands["analyze"] = msynth::cli::AddAnalyze(app);
  commands["synthesize"] = msynth::cli::AddSynthesize(app);
  commands["animate"] = msynth::cli::AddAnimate(app);
  commands["check"] = msynth::cli::AddCheck(app);
  commands["batch"] = msynth::cli::AddBatch(app);
  commands["pattern"] = msynth::cli::AddPattern(app);
  commands["quality"] = msynth::cli::AddQuality(app);
  for (CLI::App* command : app.get_subcommands({}))
  {
    command->fallthrough(); // --verbose after the command too
  }
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::CallForHelp&)
  {
    std::cout << app.help();
    return 0;
  }
  catch (const CLI::ParseError& e)
  {
    // An unknown command or option first: it explains the errors it causes.
    const std::string unknown = NotUnderstood(app);
    const std::string missing = unknown.empty() ? MissingExample(app) : "";
    return UsageFailure(CommandOf(app),
      !unknown.empty()     ? unknown
        : !missing.empty() ? missing
                           : InOwnWords(e));
  }
  if (version)
  {
    std::cout << "msynth " << MSYNTH_VERSION << "\n";
    return 0;
  }
  const std::string command = CommandOf(app);
  if (command.empty())
  {
    return UsageFailure("", "no command given (" + CommandList(app) + ")");
  }
  if (verbose)
  {
    vtkOutputWindow::GetInstance()->SetDisplayModeToDefault();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);
  }
  try
  {
    return commands.at(command)();
  }
  catch (const msynth::cli::UsageError& e)
  {
    return UsageFailure(command, e.What);
  }
}

/**
 * glibc gives the top of the heap back to the system whenever more than its trim threshold
 * (128 KB at first) is free there, and VTK's XML writer compresses each array with a zlib stream
 * of its own (about 270 KB allocated and freed): a small run's heap grew and shrank a hundred
 * times, a quarter of its page faults. Freeing one block above the mmap threshold raises that
 * threshold to the block's size and the trim threshold to twice it, as glibc's dynamic
 * adjustment does at the first large free of any run (mallopt(3), M_MMAP_THRESHOLD); the
 * adjustment stays on.
 */
void KeepTheHeapWarm()
{
  constexpr std::size_t block = std::size_t(1) << 20;
  void* first = std::malloc(block);
  if (first)
  {
    static_cast<volatile char*>(first)[0] = 0; // not optimized away
  }
  std::free(first);
}
} // namespace

int main(int argc, char* argv[])
{
  KeepTheHeapWarm();
  HandleInterruptions();
  // Our errors reach the user as one line each through observers; VTK's own pipeline chatter
  // ("algorithm returned failure") is shown only with --verbose.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  int status = 1;
  try
  {
    status = Main(argc, argv);
  }
  catch (const std::exception& e)
  {
    std::cerr << "msynth: error: " << msynth::Printable(e.what()) << "\n";
    status = 1;
  }
  std::cout.flush();
  FinalStatus = status;
  return status;
}
