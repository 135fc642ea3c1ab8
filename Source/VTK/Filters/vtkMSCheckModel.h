// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSCheckModel
 * @brief The independent checks of a synthesized model, as field data: whether it satisfies
 * its example's constraints, where it does not, and (for patterns) how much it looks like its
 * exemplars. The checks share no code with the solvers (Discrete/ConsistencyCheck.h,
 * Patterns/PatternQuality.h, Continuous/ContinuousMesh.h: CheckContinuousModel).
 *
 * Inputs:
 *  - port 0: the model: a label image (`Label`, else the active scalars), or a continuous
 *    model (vtkPolyData of vtkMSArrangementMesh);
 *  - port 1, optional, one or more connections: the examples: label images (every adjacent
 *    pair of the model must occur along its axis in one of them, Eq. 3.1), or the polyhedral
 *    example of a continuous model (its neighbourhoods, Eq. 4.1).
 *
 * A label image may instead be checked against a tileset's neighbor rules (TilesetFile; with no
 * example connected, the tileset the model's field data names, as the synthesis records it).
 *
 * Output: the model (shallow copy) with field data `Valid` (1 or 0), `Violations` (the number
 * of problems: adjacent pairs that do not occur; 1 for an invalid continuous model),
 * `PairsChecked`, `Problems` (one line each, at most MaximumReported); for label images the
 * first violations as `ViolationSites` (x, y, z of the pair's first site), `ViolationAxes`
 * (0, 1, 2: the pair is (x, x + axis)) and `ViolationLabels` (the two labels); with Shapes,
 * `KL_<shape>` per shape (the KL divergence of the model's configurations to the examples', Yeh
 * et al. 2012 §7) and `PatternLogProbability` (Eq. 3 with the shapes of more than two sites as
 * soft factors worth 1 + Epsilon); for continuous models `Objects`, `DistinctLabels` and the
 * narrowest face, edge or gap `SmallestFeature` and `SmallestFeatureFraction` (of the model's
 * recorded `SmallestSpacing`; under MinimumFeatureFraction of it the model is invalid).
 *
 * Other models (each chosen by its property): with SampleFile, the model is a picture (colour
 * scalars, from a PNG reader or vtkMSPatternImage) and every window of it must be one of the
 * sample's (`Violations`: the windows found wrong, at most MaximumReported); with VoxelModel, a
 * voxel model (palette indices and field data `PaletteRGBA`, as vtkMSLabelGridReader reads a
 * .vox with VoxScene) whose every tile cell must be a tile of the voxel tileset TilesetFile and
 * every adjacent pair allowed (`Cells`, `PairsChecked`).
 *
 * A label model's pins (PinsFile), Counts, Connected network and Path are checked too (compared,
 * counted and joined by code of the check's own, Discrete/LabelChecks.h; tile names of
 * ConnectedTilesetFile, else of the tileset): `PinsKept`, `CountNames`, `CountAchieved`, ...,
 * `CountsKept`, `ConnectedComponents`, `ConnectedKept`, `PathJoined`, and `Findings` (a line
 * each). `Valid` is 0 when one is missed.
 *
 * With TimeVarying, every time step of the model is a frame, checked in space and in time
 * (D§3.5.4, Discrete/TimeVarying.h: CheckTimeVarying) against the examples' frames: the z slices
 * of one example (ExampleTimeFromZ), else the time steps of the example (or one frame per
 * example connected); `ViolationTimes` gives each violation's frame (axis 3 is time), `Frames`
 * and `ExampleFrames` the counts. The output then has no time steps. The filter executes once
 * per time step (CONTINUE_EXECUTING); a step that comes at another time than asked (an input
 * shared with the synthesis, which moved it) is asked for again.
 *
 * Bad input (no example and no tileset, a model without labels) is an error naming it.
 *
 * @sa msynth check, msynth quality
 */
#ifndef vtkMSCheckModel_h
#define vtkMSCheckModel_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkPassInputTypeAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for ivars

class vtkFieldData;
class vtkImageData;
class vtkPolyData;

class MODELSYNTHFILTERS_EXPORT vtkMSCheckModel : public vtkPassInputTypeAlgorithm
{
public:
  static vtkMSCheckModel* New();
  vtkTypeMacro(vtkMSCheckModel, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds an example (data, not a pipeline connection) on port 1.
  void AddExampleData(vtkDataObject* example) { this->AddInputDataObject(1, example); }
  /// Adds an example's connection on port 1.
  void AddExampleConnection(vtkAlgorithmOutput* example) { this->AddInputConnection(1, example); }
  /// Removes every example (port 1).
  void RemoveAllExamples() { this->SetInputConnection(1, nullptr); }

  ///@{
  /// A tileset (.xml) whose neighbor rules a label image must follow (label k is the
  /// tileset's label k), its subset and the folder of a voxel tileset's tiles. "" (the default):
  /// the tileset the model's field data names (`TilesetFile`, `TilesetSubset`, `TilesFolder`)
  /// when no example is connected.
  vtkSetStdStringFromCharMacro(TilesetFile);
  vtkGetCharFromStdStringMacro(TilesetFile);
  vtkSetStdStringFromCharMacro(TilesetSubset);
  vtkGetCharFromStdStringMacro(TilesetSubset);
  vtkSetStdStringFromCharMacro(TilesFolder);
  vtkGetCharFromStdStringMacro(TilesFolder);
  ///@}

  ///@{
  /// An image sample (.png, .bmp): the model is a picture whose every PatternSize x PatternSize
  /// window (wrapping along the axes of PeriodicOutput) must be a window of the sample or one of
  /// its first PatternSymmetry dihedral images (windows of the sample wrap with PeriodicInput;
  /// with Ground the bottom row holds the ground windows). "" (the default): no picture check.
  vtkSetStdStringFromCharMacro(SampleFile);
  vtkGetCharFromStdStringMacro(SampleFile);
  vtkSetClampMacro(PatternSize, int, 1, 8);
  vtkGetMacro(PatternSize, int);
  vtkSetClampMacro(PatternSymmetry, int, 1, 8);
  vtkGetMacro(PatternSymmetry, int);
  vtkSetMacro(PeriodicInput, bool);
  vtkGetMacro(PeriodicInput, bool);
  vtkSetMacro(Ground, bool);
  vtkGetMacro(Ground, bool);
  vtkSetVector2Macro(PeriodicOutput, int);
  vtkGetVector2Macro(PeriodicOutput, int);
  ///@}

  ///@{
  /// Whether the model is a voxel model (palette indices, field data PaletteRGBA) checked cell
  /// by cell against the voxel tileset TilesetFile. Default off.
  vtkSetMacro(VoxelModel, bool);
  vtkGetMacro(VoxelModel, bool);
  vtkBooleanMacro(VoxelModel, bool);
  ///@}

  ///@{
  /// Label counts "L:MIN:MAX,..." the model must hold, a network "LABELS[:N]" whose sites form at
  /// most N components (through a tileset's connecting sides), and a Path "A;B;..." (sites
  /// x,y[,z] or labels) whose sites lie in one of them. L and LABELS are values or tile and
  /// label names of ConnectedTilesetFile ("" the default: the tileset checked against, if any).
  /// A count "region=R:L:MIN:MAX" counts only the sites of region R of CountGuideFile: a guide
  /// volume (.vti) whose integer point array `Region` is stretched over the model as a
  /// synthesis guide is ("" the default: no region counts).
  vtkSetStdStringFromCharMacro(Counts);
  vtkGetCharFromStdStringMacro(Counts);
  vtkSetStdStringFromCharMacro(Connected);
  vtkGetCharFromStdStringMacro(Connected);
  vtkSetStdStringFromCharMacro(Path);
  vtkGetCharFromStdStringMacro(Path);
  vtkSetStdStringFromCharMacro(ConnectedTilesetFile);
  vtkGetCharFromStdStringMacro(ConnectedTilesetFile);
  vtkSetStdStringFromCharMacro(CountGuideFile);
  vtkGetCharFromStdStringMacro(CountGuideFile);
  ///@}

  ///@{
  /// Pinned sites the model must hold (as the synthesis's FixedFile): a label grid (.vti, .txt,
  /// .vox) of the model's size, or a smaller .vti placed by its extent, -1 where free; with
  /// PinsEmptyFree label 0 is free too. "" (the default): no pins checked. Compared site by
  /// site (LabelChecks.h): `PinsChecked`, `PinsMissed`, `PinsKept` and a line in `Findings`.
  vtkSetStdStringFromCharMacro(PinsFile);
  vtkGetCharFromStdStringMacro(PinsFile);
  vtkSetMacro(PinsEmptyFree, bool);
  vtkGetMacro(PinsEmptyFree, bool);
  vtkBooleanMacro(PinsEmptyFree, bool);
  ///@}

  ///@{
  /// A time-varying model (see above); with Loop, the last frame is followed by the first;
  /// ExampleTimeFromZ: the example's z slices are its frames. Default off.
  vtkSetMacro(TimeVarying, bool);
  vtkGetMacro(TimeVarying, bool);
  vtkBooleanMacro(TimeVarying, bool);
  vtkSetMacro(Loop, bool);
  vtkGetMacro(Loop, bool);
  vtkBooleanMacro(Loop, bool);
  vtkSetMacro(ExampleTimeFromZ, bool);
  vtkGetMacro(ExampleTimeFromZ, bool);
  vtkBooleanMacro(ExampleTimeFromZ, bool);
  ///@}

  ///@{
  /// Factor shapes whose KL divergence to the examples is measured ("4H,4V", "3x3", as
  /// vtkMSPatternSynthesis's SoftFactors); "" (the default): the soft shapes the model's field
  /// data records (`SoftShapes`, as vtkMSPatternSynthesis publishes them), else none.
  vtkSetStdStringFromCharMacro(Shapes);
  vtkGetCharFromStdStringMacro(Shapes);
  ///@}

  ///@{
  /// Epsilon of `PatternLogProbability` (default 0.1).
  vtkSetClampMacro(Epsilon, double, 0.0, 1e300);
  vtkGetMacro(Epsilon, double);
  ///@}

  ///@{
  /// The most violations listed (default 10); all are counted.
  vtkSetClampMacro(MaximumReported, int, 0, 1000000);
  vtkGetMacro(MaximumReported, int);
  ///@}

protected:
  vtkMSCheckModel();
  ~vtkMSCheckModel() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSCheckModel(const vtkMSCheckModel&) = delete;
  void operator=(const vtkMSCheckModel&) = delete;

  bool CheckLabels(vtkImageData* model, vtkInformationVector* examples, vtkFieldData* out);
  bool CheckContinuous(vtkPolyData* model, vtkInformationVector* examples, vtkFieldData* out);
  bool CheckOther(vtkImageData* model, vtkFieldData* out);
  int CheckTimeStep(vtkImageData* model, vtkInformationVector* examples, vtkInformation* request,
    vtkFieldData* out);

  struct TimeFrames; ///< the frames a time-varying check collects, step by step
  std::unique_ptr<TimeFrames> Frames;

  std::string TilesetFile;
  std::string TilesetSubset;
  std::string TilesFolder;
  std::string SampleFile;
  int PatternSize = 3;
  int PatternSymmetry = 8;
  bool PeriodicInput = true;
  bool Ground = false;
  int PeriodicOutput[2] = { 0, 0 };
  bool VoxelModel = false;
  bool TimeVarying = false;
  bool Loop = false;
  bool ExampleTimeFromZ = false;
  std::string Counts;
  std::string Connected;
  std::string Path;
  std::string ConnectedTilesetFile;
  std::string CountGuideFile;
  std::string PinsFile;
  bool PinsEmptyFree = false;
  std::string Shapes;
  double Epsilon = 0.1;
  int MaximumReported = 10;
};

#endif
