// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSTimeVaryingSynthesis
 * @brief Time-varying (4D) discrete model synthesis, dissertation §3.5.4.
 *
 * The example is a label image with time steps (a file series in ParaView: every time step is
 * requested and read), each step one frame; or, with ExampleTimeFromZ, one image whose z slices
 * are the frames (a 2D example over time, like Fig. 3.27). The output is a label image of
 * OutputSize with NumberOfFrames time steps 0, 1, ...: the frame at the requested time, with the
 * point array `Label` and the run statistics as field data. Every site has spatial and temporal
 * neighbours and the adjacency constraint holds along both; with Loop the last frame is also
 * followed by the first, so the animation repeats without a jump.
 *
 * BlockSize (x, y, z, t; 0 = the whole axis) chooses Algorithm 3.4 in 4D blocks from a trivial
 * start; all 0 is Algorithm 3.1. A whole-model failure is an error, never an output. The model
 * is synthesized once and cached: asking for other time steps does not solve again.
 *
 * Output port 1 (GetGeometryOutput) is the frame's voxel surface with the cell scalars `Label`
 * (vtkMSLabelArrays::VoxelSurface), so a viewer shows the model rather than the outline of a
 * label image; sites holding EmptyLabel give none. GenerateGeometry off leaves it empty.
 *
 * In parallel (pvbatch --mpi) piece 0 does the work; other pieces output empty images.
 *
 * @sa msynth/TimeVarying.h, vtkMSDiscreteSynthesis
 */
#ifndef vtkMSTimeVaryingSynthesis_h
#define vtkMSTimeVaryingSynthesis_h

#include "ModelSynthFiltersModule.h"
#include "vtkMultiTimeStepAlgorithm.h"

#include <memory>

class vtkImageData;
class vtkPolyData;

class MODELSYNTHFILTERS_EXPORT vtkMSTimeVaryingSynthesis : public vtkMultiTimeStepAlgorithm
{
public:
  static vtkMSTimeVaryingSynthesis* New();
  vtkTypeMacro(vtkMSTimeVaryingSynthesis, vtkMultiTimeStepAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The example (a label image) as data instead of a pipeline connection.
  void SetInputData(vtkDataObject* example) { this->SetInputDataObject(0, example); }
  /// The frame of the last update.
  vtkImageData* GetOutput();
  /// Output port 1: the frame's voxel surface.
  vtkPolyData* GetGeometryOutput();

  /// Whether output port 1 holds the frame's voxel surface. Default on.
  vtkSetMacro(GenerateGeometry, bool);
  vtkGetMacro(GenerateGeometry, bool);
  vtkBooleanMacro(GenerateGeometry, bool);
  /// The label that gives no geometry on port 1. Default 0.
  vtkSetMacro(EmptyLabel, int);
  vtkGetMacro(EmptyLabel, int);

  /// The values of vtkMSDiscreteSynthesis's LabelChoices and SiteOrders that apply here.
  enum LabelChoices
  {
    UNIFORM = 0,
    FREQUENCY = 1
  };
  enum SiteOrders
  {
    SCAN_LINE = 0,
    RANDOM = 1
  };

  ///@{
  /// Spatial size of the output frames. Default 32 32 1.
  vtkSetVector3Macro(OutputSize, int);
  vtkGetVector3Macro(OutputSize, int);
  ///@}

  ///@{
  /// Number of frames (time steps) of the output. Default 16.
  vtkSetClampMacro(NumberOfFrames, int, 1, 1 << 20);
  vtkGetMacro(NumberOfFrames, int);
  ///@}

  ///@{
  /// Block size (x, y, z, t); 0 on an axis means the whole axis. Default 0 0 0 0.
  vtkSetVector4Macro(BlockSize, int);
  vtkGetVector4Macro(BlockSize, int);
  ///@}

  ///@{
  /// Overlap of consecutive blocks (x, y, z, t); -1 means half a block. Default -1 -1 -1 -1.
  vtkSetVector4Macro(BlockOverlap, int);
  vtkGetVector4Macro(BlockOverlap, int);
  ///@}

  ///@{
  vtkSetClampMacro(AttemptsPerBlock, int, 1, 1000000);
  vtkGetMacro(AttemptsPerBlock, int);
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  vtkSetClampMacro(LabelChoice, int, UNIFORM, FREQUENCY);
  vtkGetMacro(LabelChoice, int);
  void SetLabelChoiceToUniform() { this->SetLabelChoice(UNIFORM); }
  void SetLabelChoiceToFrequency() { this->SetLabelChoice(FREQUENCY); }
  vtkSetClampMacro(SiteOrder, int, SCAN_LINE, RANDOM);
  vtkGetMacro(SiteOrder, int);
  void SetSiteOrderToScanLine() { this->SetSiteOrder(SCAN_LINE); }
  void SetSiteOrderToRandom() { this->SetSiteOrder(RANDOM); }
  ///@}

  ///@{
  /// The last frame is followed by the first (a looping animation). Default off.
  vtkSetMacro(Loop, bool);
  vtkGetMacro(Loop, bool);
  vtkBooleanMacro(Loop, bool);
  ///@}

  ///@{
  /// The example's z slices are its frames (one image, no time steps). Default off.
  vtkSetMacro(ExampleTimeFromZ, bool);
  vtkGetMacro(ExampleTimeFromZ, bool);
  vtkBooleanMacro(ExampleTimeFromZ, bool);
  ///@}

protected:
  vtkMSTimeVaryingSynthesis();
  ~vtkMSTimeVaryingSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The base class asks for one example time step per pass; every pass needs the whole extent.
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int Execute(vtkInformation* request, const std::vector<vtkSmartPointer<vtkDataObject>>& inputs,
    vtkInformationVector* outputVector) override;

private:
  vtkMSTimeVaryingSynthesis(const vtkMSTimeVaryingSynthesis&) = delete;
  void operator=(const vtkMSTimeVaryingSynthesis&) = delete;

  int OutputSize[3] = { 32, 32, 1 };
  int NumberOfFrames = 16;
  int BlockSize[4] = { 0, 0, 0, 0 };
  int BlockOverlap[4] = { -1, -1, -1, -1 };
  int AttemptsPerBlock = 10;
  vtkIdType Seed = 0;
  int LabelChoice = UNIFORM;
  int SiteOrder = SCAN_LINE;
  bool Loop = false;
  bool ExampleTimeFromZ = false;
  bool GenerateGeometry = true;
  int EmptyLabel = 0;

  struct Cache;
  std::unique_ptr<Cache> Cached;
};

#endif
