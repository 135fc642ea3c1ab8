// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPatternSynthesis
 * @brief Factor-graph pattern synthesis (Yeh et al. 2012): BLOCKSS, or the baselines of its §8.
 *
 * Inputs:
 *  - port 0, one or more connections: the exemplars, label images (`Label`, else the active
 *    scalars) over one set of tiles, 2D or 3D (none when TilesetFile gives the pairs);
 *  - port 1, optional: the zoning, an integer image of zone ids (`Zone`, else `Label`, else the
 *    active scalars), stretched over the output as guides are (cell floor((p + ½) · D / S));
 *  - port 2, optional: fixed sites, a label image of the output's size; sites holding a tile
 *    are fixed to it, others (e.g. -1) are free.
 *
 * The factors are hard pairs along every axis of the output (2H, 2V, 2D) and the soft shapes of
 * SoftFactors ("4H,4V", "3x3", "2x2x2", stencils "0:0+1:0+1:1"), worth 1 + Epsilon where an
 * exemplar shows the configuration. ZoneTiles "1:0;2:8,9" restricts zone 1 to label 0 and zone
 * 2 to labels 8 and 9; ZoneExemplars "1:1;2:2" takes zone 1's soft factors from the first
 * exemplar and zone 2's from the second (style mixing, Fig. 15). Mirror (x, y, z) synthesizes
 * half and mirrors it, with MirrorSwaps "a:b,..." the labels that are each other's images.
 *
 * Output: a label image of OutputSize with one time step per sample (Samples after BurnIn),
 * point arrays `Label`, `SatisfiedSoft` (soft factors anchored at the site whose configuration
 * an exemplar shows) and `LastChange` (the move that last changed the site), and field data:
 * `Sample`, `Samples`, `LogProbability`, `KL_<shape>` per soft shape (PatternQuality.h),
 * the run's counts (`Moves`, `WalkMoves`, `AnnealingMoves`, `AcceptedAnnealingMoves`,
 * `FirstValidMoves`, `FirstValidSeconds`, `Seconds`, `HardFactors`, `SoftFactors`, `Tiles`,
 * `ReplacementBlocks`), `Method` and `Seed`; with Connected, the sample's `ConnectedLabels`,
 * `ConnectedMaximum`, `ConnectedComponents`, `ConnectedBefore` (before its repairs),
 * `ConnectedRepairs` and `ConnectedRedone` (with a Path, `ConnectedPathSites`), and the run's
 * `NetworkSeconds`. The samples are
 * computed once and cached: asking for another time step does not sample again.
 *
 * @sa msynth/PatternSynthesis.h, vtkMSTileImage (pictures of tileset patterns)
 */
#ifndef vtkMSPatternSynthesis_h
#define vtkMSPatternSynthesis_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for the cache
#include <string> // for ivars
#include <vector> // for inputs

class vtkFieldData;
namespace msynth
{
class LabelGrid;
struct PatternOptions;
struct PatternResult;
struct PatternSample;
}

class MODELSYNTHFILTERS_EXPORT vtkMSPatternSynthesis : public vtkImageAlgorithm
{
public:
  static vtkMSPatternSynthesis* New();
  vtkTypeMacro(vtkMSPatternSynthesis, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Starts
  {
    RANDOM_START = 0,
    SOLVER_START = 1
  };
  enum Methods
  {
    BLOCKSS = 0,
    METROPOLIS_HASTINGS = 1,
    CONSTRAINT_SOLVER = 2
  };

  /// Adds an exemplar (data, not a pipeline connection).
  void AddExemplarData(vtkDataObject* exemplar) { this->AddInputDataObject(0, exemplar); }
  /// Removes every exemplar (port 0), keeping the zones and fixed sites.
  void RemoveAllExemplars() { this->SetInputConnection(0, nullptr); }
  void SetZonesData(vtkDataObject* zones) { this->SetInputDataObject(1, zones); }
  void SetFixedData(vtkDataObject* fixed) { this->SetInputDataObject(2, fixed); }
  void SetZonesConnection(vtkAlgorithmOutput* zones) { this->SetInputConnection(1, zones); }
  void SetFixedConnection(vtkAlgorithmOutput* fixed) { this->SetInputConnection(2, fixed); }

  ///@{
  /// A WaveFunctionCollapse simple-tiled tileset (.xml) whose neighbor rules are hard pairs
  /// besides the exemplars' (label k is the tileset's label k); with it no exemplar is needed.
  /// Default none. TilesetSubset picks a <subset>.
  vtkSetStdStringFromCharMacro(TilesetFile);
  vtkGetCharFromStdStringMacro(TilesetFile);
  vtkSetStdStringFromCharMacro(TilesetSubset);
  vtkGetCharFromStdStringMacro(TilesetSubset);
  ///@}
  ///@{
  /// Output size in sites. Default 20 20 1.
  vtkSetVector3Macro(OutputSize, int);
  vtkGetVector3Macro(OutputSize, int);
  ///@}
  ///@{
  /// Soft factor shapes, comma-separated. Default "" (hard pairs only).
  vtkSetStdStringFromCharMacro(SoftFactors);
  vtkGetCharFromStdStringMacro(SoftFactors);
  /// ε: a soft factor is 1 + ε where an exemplar shows its configuration. Default 0.1.
  vtkSetClampMacro(Epsilon, double, 0.0, 1.0e6);
  vtkGetMacro(Epsilon, double);
  ///@}
  ///@{
  /// Replacement blocks: scheme B1–B6 (default 6), or the shapes of BlockShapes when set.
  vtkSetClampMacro(BlockScheme, int, 1, 6);
  vtkGetMacro(BlockScheme, int);
  vtkSetStdStringFromCharMacro(BlockShapes);
  vtkGetCharFromStdStringMacro(BlockShapes);
  ///@}
  ///@{
  vtkSetClampMacro(Method, int, BLOCKSS, CONSTRAINT_SOLVER);
  vtkGetMacro(Method, int);
  /// Where BLOCKSS starts: random tiles (Algorithm 1, default) or a constraint-solver pattern.
  vtkSetClampMacro(Start, int, RANDOM_START, SOLVER_START);
  vtkGetMacro(Start, int);
  vtkSetClampMacro(Samples, int, 1, 100000);
  vtkGetMacro(Samples, int);
  vtkSetClampMacro(BurnIn, int, 0, 100000);
  vtkGetMacro(BurnIn, int);
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}
  ///@{
  /// BlockSampleSAT's parameters (the paper's defaults 0.25, 0.6, 0.1).
  vtkSetClampMacro(Temperature, double, 1.0e-6, 1.0e6);
  vtkGetMacro(Temperature, double);
  vtkSetClampMacro(WalkProbability, double, 0.0, 1.0);
  vtkGetMacro(WalkProbability, double);
  vtkSetClampMacro(FlipProbability, double, 0.0, 1.0);
  vtkGetMacro(FlipProbability, double);
  /// Moves before a sample may end; -1: one per site (0: Algorithm 2 exactly).
  vtkSetClampMacro(MovesPerSample, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(MovesPerSample, vtkIdType);
  /// Moves allowed for a sample before the run fails; -1: 20,000 per site (at least 10^7).
  vtkSetClampMacro(MaxMoves, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(MaxMoves, vtkIdType);
  ///@}
  ///@{
  vtkSetStdStringFromCharMacro(ZoneTiles);
  vtkGetCharFromStdStringMacro(ZoneTiles);
  vtkSetStdStringFromCharMacro(ZoneExemplars);
  vtkGetCharFromStdStringMacro(ZoneExemplars);
  vtkSetVector3Macro(Mirror, int);
  vtkGetVector3Macro(Mirror, int);
  vtkSetStdStringFromCharMacro(MirrorSwaps);
  vtkGetCharFromStdStringMacro(MirrorSwaps);
  ///@}

  ///@{
  /// A connected network "LABELS[:N]" (see the class comment); "" for none. Its labels' names
  /// and connecting sides come from ConnectedTilesetFile (a tileset that only names and draws
  /// the tiles, e.g. Data/Patterns/City.xml), else from TilesetFile.
  vtkSetStdStringFromCharMacro(Connected);
  vtkGetCharFromStdStringMacro(Connected);
  vtkSetStdStringFromCharMacro(ConnectedTilesetFile);
  vtkGetCharFromStdStringMacro(ConnectedTilesetFile);
  /// A path the Connected network joins, "A;B;...": sites "x,y[,z]" and labels (values or tile
  /// names: every site holding one) lie in one component of each sample's network, as
  /// vtkMSDiscreteSynthesis's Path; field data `ConnectedPathSites`. "" for none (default).
  vtkSetStdStringFromCharMacro(Path);
  vtkGetCharFromStdStringMacro(Path);
  ///@}

protected:
  vtkMSPatternSynthesis();
  ~vtkMSPatternSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSPatternSynthesis(const vtkMSPatternSynthesis&) = delete;
  /// The exemplars of port 0 into @p exemplars, their images into @p inputs; false (with the
  /// error said) when one is not a label image.
  bool ReadExemplars(vtkInformationVector* exemplarPort, std::vector<vtkDataObject*>& inputs,
    std::vector<msynth::LabelGrid>& exemplars);
  /// The text properties (factor and block shapes, zone lists, mirror swaps, the tileset's
  /// pairs) into @p options, and the output size checked; false (with the error said) if bad.
  bool ParseLists(msynth::PatternOptions& options);
  /// Zones (port 1) and fixed sites (port 2) into @p options; their images join @p inputs.
  bool ReadZonesAndFixed(vtkInformationVector** inputVector, msynth::PatternOptions& options,
    std::vector<vtkDataObject*>& inputs);
  /// The field data of @p sample of @p result.
  void AddFields(
    vtkFieldData* fd, const msynth::PatternResult& result, const msynth::PatternSample& sample);
  void operator=(const vtkMSPatternSynthesis&) = delete;

  std::string TilesetFile;
  std::string TilesetSubset;
  int OutputSize[3] = { 20, 20, 1 };
  std::string SoftFactors;
  double Epsilon = 0.1;
  int BlockScheme = 6;
  std::string BlockShapes;
  int Method = BLOCKSS;
  int Start = RANDOM_START;
  int Samples = 1;
  int BurnIn = 5;
  vtkIdType Seed = 0;
  double Temperature = 0.25;
  double WalkProbability = 0.6;
  double FlipProbability = 0.1;
  vtkIdType MovesPerSample = -1;
  vtkIdType MaxMoves = -1;
  std::string ZoneTiles;
  std::string ZoneExemplars;
  int Mirror[3] = { 0, 0, 0 };
  std::string MirrorSwaps;
  std::string Connected;
  std::string ConnectedTilesetFile;
  std::string Path;

  struct Cache;
  std::unique_ptr<Cache> Cached;
};

#endif
