// SPDX-License-Identifier: BSD-3-Clause
// `msynth animate EXAMPLE... --size NX NY NZ --frames N`: time-varying synthesis (D§3.5.4)
// through vtkMSTimeVaryingSynthesis. One example file: its z slices are the frames; several:
// one frame each, given to the filter as time steps (as a file series in ParaView). Writes
// DIR/frame_0001.vti, ... (a series ParaView opens as time steps), DIR/model_0001.vdb, ... (the
// same number for the same frame, from 1 as renderers number sequences) and
// DIR/statistics.json, after checking the animation against the example frames (vtkMSCheckModel).
#include "Commands.h"
#include "Common.h"
#include "FrameSeries.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSCheckModel.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSTimeVaryingSynthesis.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"

#include <iomanip>
#include <iostream>
#include <memory>

namespace msynth
{
namespace cli
{
namespace
{
const std::vector<std::string> Orders{ "scanline", "random" };
const std::vector<std::string> Choices{ "uniform", "frequency" };

struct AnimateOptions
{
  std::vector<std::string> Examples;
  std::vector<int> Size;
  int Frames = 0;
  bool Loop = false;
  std::vector<int> Block{ 0, 0, 0 };
  std::vector<int> Overlap{ -1, -1, -1 };
  int OverlapFrames = -1;
  int BlockFrames = 0;
  std::int64_t Seed = 0;
  int Attempts = 10;
  std::string Order = "scanline";
  std::string Choice = "uniform";
  std::string Out = "msynth-output";
};

/// Frame @p t (from 0) of the synthesis written: frame_(t+1).vti and model_(t+1).vdb.
void WriteFrame(vtkMSTimeVaryingSynthesis* synthesis, int t, const std::string& dir)
{
  synthesis->UpdateTimeStep(t);
  vtkNew<vtkImageData> image;
  image->DeepCopy(synthesis->GetOutput());
  char name[32];
  std::snprintf(name, sizeof(name), "/frame_%04d.vti", t + 1);
  WriteXML<vtkXMLImageDataWriter>(dir + name, image.GetPointer());
  vtkNew<vtkMSOpenVDBWriter> vdb;
  vdb->SetInputData(image);
  std::snprintf(name, sizeof(name), "/model_%04d.vdb", t + 1);
  vdb->SetFileName((dir + name).c_str());
  vdb->AddMetadata("msynth_command", "animate");
  vdb->AddMetadata("frame", std::to_string(t).c_str());
  {
    ProgressBar bar(vdb, name + 1);
    Run(vdb);
  }
}

int Animate(const AnimateOptions& o, const std::string& dir)
{
  vtkNew<vtkMSLabelGridReader> reader;
  reader->GenerateGeometryOff();
  vtkNew<vtkMSFrameSeries> series;
  vtkNew<vtkMSTimeVaryingSynthesis> synthesis;
  synthesis->GenerateGeometryOff(); // frames are written as label images
  // Every frame checked against the example frames in space and time, independently of the
  // solver (Discrete/TimeVarying.h: CheckTimeVarying).
  vtkNew<vtkMSCheckModel> check;
  check->SetInputConnection(synthesis->GetOutputPort());
  check->TimeVaryingOn();
  check->SetLoop(o.Loop);
  if (o.Examples.size() == 1)
  {
    reader->SetFileName(o.Examples[0].c_str());
    Run(reader); // so that the reader's own error (naming the file) is the one reported
    synthesis->SetInputConnection(reader->GetOutputPort());
    synthesis->ExampleTimeFromZOn();
    check->AddExampleConnection(reader->GetOutputPort());
    check->ExampleTimeFromZOn();
  }
  else
  {
    for (const auto& path : o.Examples)
    {
      vtkNew<vtkMSLabelGridReader> frame;
      frame->SetFileName(path.c_str());
      frame->GenerateGeometryOff();
      Run(frame);
      series->AddFrame(frame->GetOutput());
    }
    synthesis->SetInputConnection(series->GetOutputPort());
    check->AddExampleConnection(series->GetOutputPort());
  }
  synthesis->SetOutputSize(o.Size[0], o.Size[1], o.Size[2]);
  synthesis->SetNumberOfFrames(o.Frames);
  synthesis->SetBlockSize(o.Block[0], o.Block[1], o.Block[2], o.BlockFrames);
  synthesis->SetBlockOverlap(o.Overlap[0], o.Overlap[1], o.Overlap[2], o.OverlapFrames);
  synthesis->SetAttemptsPerBlock(o.Attempts);
  synthesis->SetSeed(static_cast<vtkIdType>(o.Seed));
  synthesis->SetLoop(o.Loop);
  synthesis->SetSiteOrder(IndexIn(o.Order, Orders));
  synthesis->SetLabelChoice(IndexIn(o.Choice, Choices));
  {
    ProgressBar bar(synthesis);
    synthesis->UpdateInformation();
    Run(synthesis);
  }
  for (int t = 0; t < o.Frames; ++t)
  {
    WriteFrame(synthesis, t, dir);
  }
  Run(check);
  vtkFieldData* verdict = check->GetOutput()->GetFieldData();
  if (CountOf(verdict, "Valid") != 1)
  {
    throw std::runtime_error(
      "the synthesized animation breaks the example's rules: " + MessageOf(verdict, "Problems"));
  }
  vtkFieldData* fd = synthesis->GetOutput()->GetFieldData();
  const std::string message = MessageOf(fd);
  std::string examples;
  for (std::size_t i = 0; i < o.Examples.size(); ++i)
    examples += (i ? ", " : "") + JsonString(o.Examples[i]);
  StatisticsJson()
    .Raw("examples", "[" + examples + "]")
    .Count("exampleFrames", CountOf(verdict, "ExampleFrames"))
    .Counts("size", { o.Size[0], o.Size[1], o.Size[2] })
    .Count("frames", o.Frames)
    .Flag("loop", o.Loop)
    .Count("seed", o.Seed)
    .Solver(fd)
    .Text("Message", message)
    .Write(dir + "/statistics.json");
  std::cout << message << "\n"
            << "consistent: all " << CountOf(verdict, "PairsChecked")
            << " pairs of neighbours in space and time occur in the example\n"
            << "wrote " << dir << "/frame_0001.vti ... frame_" << std::setw(4) << std::setfill('0')
            << o.Frames << ".vti, " << dir << "/model_0001.vdb ... model_" << std::setw(4)
            << o.Frames << ".vdb, " << dir << "/statistics.json\n";
  return 0;
}
} // namespace

CommandRunner AddAnimate(CLI::App& app)
{
  auto o = std::make_shared<AnimateOptions>();
  CLI::App* a = app.add_subcommand("animate",
    "time-varying synthesis, an animation whose frames follow each other as the example's do: "
    "one EXAMPLE image whose z slices are the frames, or one "
    "file per frame; writes DIR/frame_0001.vti ... (a series ParaView opens as time steps), "
    "DIR/model_0001.vdb ... and DIR/statistics.json");
  a->add_option("EXAMPLE", o->Examples, "the example: one image, or one file per frame")
    ->required();
  a->add_option("--size", o->Size, "frame size NX NY NZ in sites")
    ->expected(3)
    ->required()
    ->check(CLI::Range(1, 1000000000));
  a->add_option("--frames", o->Frames, "number of frames")
    ->required()
    ->check(CLI::Range(1, 1000000));
  a->add_flag("--loop", o->Loop, "join the last frame to the first (a repeating animation)");
  a->add_option("--block", o->Block, "block size BX BY BZ (default: the whole model)")
    ->expected(3)
    ->check(CLI::Range(0, 1000000000));
  a->add_option("--block-frames", o->BlockFrames, "frames per block (0: all)")
    ->check(CLI::Range(0, 1000000));
  a->add_option(
     "--overlap", o->Overlap, "overlap of consecutive blocks OX OY OZ (-1: half a block)")
    ->expected(3)
    ->check(CLI::Range(-1, 1000000000));
  a->add_option("--overlap-frames", o->OverlapFrames, "overlap of blocks in frames (-1: half)")
    ->check(CLI::Range(-1, 1000000));
  AddSeedOption(*a, o->Seed);
  AddAttemptsOption(*a, o->Attempts, "attempts per block");
  AddOrderOption(*a, o->Order, Orders);
  AddChoiceOption(*a, o->Choice, Choices);
  AddOutOption(*a, o->Out);
  return [o]()
  {
    for (const auto& path : o->Examples)
    {
      CheckInputFile(path);
    }
    return IntoFolder(o->Out, [&](const std::string& dir) { return Animate(*o, dir); });
  };
}

} // namespace cli
} // namespace msynth
