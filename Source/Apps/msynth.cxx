// SPDX-License-Identifier: BSD-3-Clause
// msynth: ModelSynth's command line.
//
//   msynth info EXAMPLE                  labels, counts and transition tables (Eq. 3.2)
//   msynth analyze EXAMPLE [--out DIR]   the analysis as CSV tables plus the example as .vdb
//
// Exit status: 0 on success, 1 when the work fails (bad input, unwritable output), 2 on a
// usage error. Errors are one line on stderr naming the file and the problem.
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSTransitionTables.h"

#include "vtkAbstractArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkVariant.h"

#include "msynth/AtomicFile.h"

#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{

const char* const Usage = R"(usage:
  msynth info EXAMPLE                 print the example's labels and transition tables
  msynth analyze EXAMPLE [--out DIR]  write DIR/labels.csv, DIR/transitions.csv, DIR/example.vdb
  msynth --help | --version

Options: --verbose shows VTK's own diagnostics as well.

EXAMPLE is a label grid in VTK image data (.vti) with an integer array 'Label'.
DIR defaults to ./msynth-output.
)";

struct UsageError
{
  std::string What;
};

/// Runs @p algorithm, turning its VTK errors into one exception message.
void Run(vtkAlgorithm* algorithm)
{
  std::string messages;
  if (!vtkMSEngineBridge::Execute(algorithm, messages))
  {
    throw std::runtime_error(messages);
  }
}

struct Analysis
{
  vtkSmartPointer<vtkMSLabelGridReader> Reader;
  vtkSmartPointer<vtkMSTransitionTables> Tables;
};

Analysis Analyze(const std::string& example)
{
  Analysis a;
  a.Reader = vtkSmartPointer<vtkMSLabelGridReader>::New();
  a.Reader->SetFileName(example.c_str());
  Run(a.Reader);
  a.Tables = vtkSmartPointer<vtkMSTransitionTables>::New();
  a.Tables->SetInputConnection(a.Reader->GetOutputPort());
  Run(a.Tables);
  return a;
}

void WriteCSV(const std::string& path, vtkTable* table)
{
  msynth::WriteFileAtomically(path,
    [table](std::ostream& out)
    {
      for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
      {
        out << (c ? "," : "") << table->GetColumnName(c);
      }
      out << "\n";
      for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
      {
        for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
        {
          out << (c ? "," : "") << table->GetValue(r, c).ToString();
        }
        out << "\n";
      }
    });
}

int Info(const std::string& example)
{
  Analysis a = Analyze(example);
  vtkImageData* image = a.Reader->GetOutput();
  vtkTable* labels = a.Tables->GetOutput(1);
  vtkTable* transitions = a.Tables->GetOutput(0);
  int dims[3];
  image->GetDimensions(dims);
  std::cout << "example: " << example << "\n"
            << "size: " << dims[0] << " x " << dims[1] << " x " << dims[2] << "\n"
            << "labels: " << labels->GetNumberOfRows() << "\n";
  for (vtkIdType r = 0; r < labels->GetNumberOfRows(); ++r)
  {
    std::cout << "  label " << labels->GetValueByName(r, "Label").ToString() << ": "
              << labels->GetValueByName(r, "Count").ToString() << " sites\n";
  }
  const char* names[3] = { "+x", "+y", "+z" };
  for (int axis = 0; axis < 3; ++axis)
  {
    std::vector<std::string> pairs;
    for (vtkIdType r = 0; r < transitions->GetNumberOfRows(); ++r)
    {
      if (transitions->GetValueByName(r, "Axis").ToInt() == axis)
      {
        pairs.push_back(transitions->GetValueByName(r, "From").ToString() + "->" +
          transitions->GetValueByName(r, "To").ToString());
      }
    }
    std::cout << "transitions " << names[axis] << ": " << pairs.size() << "\n";
    for (const auto& p : pairs)
    {
      std::cout << "  " << p << "\n";
    }
  }
  return 0;
}

void MakeDirectory(const std::string& dir)
{
  struct stat info;
  if (::stat(dir.c_str(), &info) == 0)
  {
    if (!S_ISDIR(info.st_mode))
    {
      throw std::runtime_error("'" + dir + "': exists and is not a folder");
    }
    return;
  }
  if (::mkdir(dir.c_str(), 0777) != 0)
  {
    throw std::runtime_error("'" + dir + "': cannot create folder: " + std::strerror(errno));
  }
}

int AnalyzeToFolder(const std::string& example, const std::string& dir)
{
  Analysis a = Analyze(example);
  MakeDirectory(dir);
  WriteCSV(dir + "/labels.csv", a.Tables->GetOutput(1));
  WriteCSV(dir + "/transitions.csv", a.Tables->GetOutput(0));
  vtkNew<vtkMSOpenVDBWriter> writer;
  writer->SetInputConnection(a.Reader->GetOutputPort());
  writer->SetFileName((dir + "/example.vdb").c_str());
  writer->WriteFloatLabelsOn();
  writer->AddMetadata("msynth_command", "analyze");
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(writer);
  if (!writer->Write() || errors->HasErrors())
  {
    throw std::runtime_error(errors->GetMessages());
  }
  std::cout << "wrote " << dir << "/labels.csv, " << dir << "/transitions.csv, " << dir
            << "/example.vdb\n";
  return 0;
}

int Main(const std::vector<std::string>& args)
{
  if (args.empty())
  {
    throw UsageError{ "no command given" };
  }
  const std::string& command = args[0];
  if (command == "--help" || command == "-h" || command == "help")
  {
    std::cout << Usage;
    return 0;
  }
  if (command == "--version")
  {
    std::cout << "msynth " << MSYNTH_VERSION << "\n";
    return 0;
  }
  std::vector<std::string> positional;
  std::string out = "msynth-output";
  for (std::size_t i = 1; i < args.size(); ++i)
  {
    if (args[i] == "--verbose")
    {
      vtkOutputWindow::GetInstance()->SetDisplayModeToDefault();
      vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);
    }
    else if (args[i] == "--out")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ "--out needs a folder" };
      }
      out = args[++i];
    }
    else if (args[i].rfind("--", 0) == 0)
    {
      throw UsageError{ "unknown option '" + args[i] + "'" };
    }
    else
    {
      positional.push_back(args[i]);
    }
  }
  if (command == "info" || command == "analyze")
  {
    if (positional.size() != 1)
    {
      throw UsageError{ command + " takes exactly one EXAMPLE" };
    }
    return command == "info" ? Info(positional[0]) : AnalyzeToFolder(positional[0], out);
  }
  throw UsageError{ "unknown command '" + command + "'" };
}

} // namespace

int main(int argc, char* argv[])
{
  // Our errors reach the user as one line each through observers; VTK's own pipeline chatter
  // ("algorithm returned failure") is shown only with --verbose.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  try
  {
    return Main(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const UsageError& e)
  {
    std::cerr << "msynth: " << e.What << "\n" << Usage;
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "msynth: error: " << e.what() << "\n";
    return 1;
  }
}
