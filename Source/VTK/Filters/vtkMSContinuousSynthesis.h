// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSContinuousSynthesis
 * @brief The label solver of continuous model synthesis (dissertation §4.5, Algorithm 4.1;
 * msynth::SynthesizeContinuous) on the vertices of a plane arrangement.
 *
 * Input 0: the polyhedral example. Input 1: the output of vtkMSPlaneArrangement built from the
 * same example (the arrangement is rebuilt exactly from its field data).
 *
 * Output: the arrangement with point arrays `Label` (the example label id of each vertex, as
 * listed by vtkMSNeighbourhoodLabels), `CatalogSize` and `Entropy`, and the run statistics as
 * field data (`Success`, `Seed`, and the names every solver uses: `Blocks`, `BlocksAccepted`,
 * `BlocksFailed`, `Attempts`, `FailedAttempts`, `Assignments`, `Backtracks`, `Seconds`, `Status`,
 * `Message`, ...; see vtkMSFieldData::AddStatistics). With NumberOfSnapshots S > 0 the output
 * has S + 1 time steps: the catalog at the start and at S even fractions of the work, so ParaView
 * can animate it shrinking; `Label` is then vtkMSLabelArrays::Undecided (VTK_INT_MIN, as in
 * every filter) where undecided and `ModelLabel` holds the finished
 * model at every step.
 *
 * Constraints beyond adjacency (TVCG 2010 §4.5–4.7, msynth::ContinuousConstraints): Grounded
 * outputs, Thickness (dimensional constraints), Connected (growth from seeds), proportions of
 * object types (on by default; TargetFractions), and a guide (input port 2, optional): image data
 * stretched over the output box whose point arrays `Weight_<type>` (a type number or name) weight
 * the labels holding that type, 0 removing them there. The field data then also has `Components`,
 * `GroundedComponents`, `FloatingPartsRemoved`, `PartsBeyondSeedsRemoved` and `TypeShare_<type>`
 * (vertex occupancy; the mesh filter gives volume shares). Always: `NarrowPartsRemoved`, the solid
 * parts emptied because a corner came within a tenth of the smallest spacing of another plane's
 * face, edge or corner (no slivers), and with proportions steered `ProportionPartsRemoved`
 * (solid parts emptied to bring the types' shares within 25 % of the example's),
 * `ProportionVolumeRemoved` (the fraction of the solid volume they held),
 * `ProportionBlocksRedrawn` (blocks synthesized again where emptying parts could not keep the
 * shares or would empty more than half of the solid) and `ProportionsOutside` (the types still
 * outside, their shares and why; empty when none).
 *
 * Whole-model synthesis (BlockSize 0) that fails in every attempt is an error; with blocks, the
 * model starts empty and a block that fails in every attempt is left as it was.
 *
 * @sa vtkMSPlaneArrangement vtkMSArrangementMesh
 */
#ifndef vtkMSContinuousSynthesis_h
#define vtkMSContinuousSynthesis_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class MODELSYNTHFILTERS_EXPORT vtkMSContinuousSynthesis : public vtkPolyDataAlgorithm
{
public:
  static vtkMSContinuousSynthesis* New();
  vtkTypeMacro(vtkMSContinuousSynthesis, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The values of vtkMSDiscreteSynthesis's LabelChoices and SiteOrders that apply here.
  enum LabelChoices
  {
    UNIFORM = 0,  ///< every possible label equally likely (the dissertation)
    FREQUENCY = 1 ///< weighted by occurrences in the example
  };
  enum SiteOrders
  {
    SCAN_LINE = 0,       ///< z, then y, then x (the dissertation)
    RANDOM = 1,          ///< a seeded random order
    MINIMUM_ENTROPY = 2, ///< fewest labels first
    /// Scan line where the example's sizes are followed and nothing grows from seeds (a part's
    /// end is drawn next to the vertices it has decided), fewest labels first otherwise.
    AUTOMATIC_ORDER = 3
  };

  /// The arrangement input (port 1).
  void SetArrangementConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  /// The optional guide (port 2): image data with point arrays Weight_<type>.
  void SetGuideConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }

  ///@{
  /// Random seed; equal seeds give equal models. Default 0.
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// Block edge in plane spacings (of the family with the largest spacing); blocks overlap by
  /// half. 0 labels the whole arrangement at once; negative: automatic, room for the example's
  /// parts (twice its longest wall, slab or road with ExampleSizes, at least 4; else 4). The
  /// edge used is the output's field array BlockSize. Default -1 (automatic).
  vtkSetClampMacro(BlockSize, double, -1.0, 1e6);
  vtkGetMacro(BlockSize, double);
  ///@}

  ///@{
  /// Attempts per block (or for the whole model). Default 20.
  vtkSetClampMacro(Attempts, int, 1, 1000000);
  vtkGetMacro(Attempts, int);
  ///@}

  ///@{
  /// Threads for blocks (non-touching blocks of a phase run concurrently); 0 uses one per core.
  /// The model does not depend on it. Runs with connectivity seeds or snapshots use one.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Under MPI (pvbatch --mpi, a parallel pvserver): spread the blocks of each phase over the
   * ranks and exchange the finished blocks after it. Rank 0, which holds the arrangement, sends
   * the ranks the example and the arrangement's parameters; the model is the one a single
   * process computes, and rank 0 outputs it (the arrangement's piece). Runs whose blocks go one
   * after the other (connectivity seeds, snapshots) are computed on every rank. Default on.
   */
  vtkSetMacro(DistributeBlocks, bool);
  vtkGetMacro(DistributeBlocks, bool);
  vtkBooleanMacro(DistributeBlocks, bool);
  ///@}

  ///@{
  /// Vertex order (SiteOrders). Default AUTOMATIC_ORDER; the order used is the output's field
  /// array SiteOrder.
  vtkSetClampMacro(SiteOrder, int, SCAN_LINE, AUTOMATIC_ORDER);
  vtkGetMacro(SiteOrder, int);
  void SetSiteOrderToScanLine() { this->SetSiteOrder(SCAN_LINE); }
  void SetSiteOrderToRandom() { this->SetSiteOrder(RANDOM); }
  void SetSiteOrderToMinimumEntropy() { this->SetSiteOrder(MINIMUM_ENTROPY); }
  void SetSiteOrderToAutomatic() { this->SetSiteOrder(AUTOMATIC_ORDER); }
  ///@}

  ///@{
  /// Label choice (LabelChoices). Default UNIFORM.
  vtkSetClampMacro(LabelChoice, int, UNIFORM, FREQUENCY);
  vtkGetMacro(LabelChoice, int);
  void SetLabelChoiceToUniform() { this->SetLabelChoice(UNIFORM); }
  void SetLabelChoiceToFrequency() { this->SetLabelChoice(FREQUENCY); }
  ///@}

  ///@{
  /// Catalog snapshots as time steps (0: none). Default 0.
  vtkSetClampMacro(NumberOfSnapshots, int, 0, 10000);
  vtkGetMacro(NumberOfSnapshots, int);
  ///@}

  ///@{
  /// Grounded output: ground labels only on the ground, objects grown from it, floating parts
  /// emptied. Default off.
  vtkSetMacro(Grounded, bool);
  vtkGetMacro(Grounded, bool);
  vtkBooleanMacro(Grounded, bool);
  ///@}
  ///@{
  /// Dimensional constraints, "TYPE:AXIS[:N],..." (AXIS x, y, z or hK; N plane spacings; "N+"
  /// for whole multiples of N), or widths "TYPE:AXES" with several axes (one spacing across at
  /// least one). Default "".
  vtkSetStdStringFromCharMacro(Thickness);
  vtkGetCharFromStdStringMacro(Thickness);
  ///@}
  ///@{
  /// Overhang limits, "TYPE,...": each type's undersides are at most one plane spacing wide (it
  /// reaches one spacing past what holds it up, as eaves). Default "".
  vtkSetStdStringFromCharMacro(Overhang);
  vtkGetCharFromStdStringMacro(Overhang);
  ///@}
  ///@{
  /// Connectivity constraints, "TYPE[:SEEDS],..." (TYPE "solid" for every type). Default "".
  vtkSetStdStringFromCharMacro(Connected);
  vtkGetCharFromStdStringMacro(Connected);
  ///@}
  ///@{
  /// Keep the example's proportions of object types (by volume). Default on.
  vtkSetMacro(KeepProportions, bool);
  vtkGetMacro(KeepProportions, bool);
  vtkBooleanMacro(KeepProportions, bool);
  ///@}
  ///@{
  /// Parts as long as the example's: where a label would end a run of an upright object type
  /// (walls, slabs, roads) along x or y, it is drawn with the chance that the example's runs of
  /// that length end (RunEnds.h), instead of the same odds at every length, and no part is
  /// begun where it cannot reach the example's lengths. Default on.
  vtkSetMacro(ExampleSizes, bool);
  vtkGetMacro(ExampleSizes, bool);
  vtkBooleanMacro(ExampleSizes, bool);
  ///@}
  ///@{
  /// Target shares of the solid volume per object type, "TYPE:F,..." (others keep the example's
  /// proportions among themselves). Default "".
  vtkSetStdStringFromCharMacro(TargetFractions);
  vtkGetCharFromStdStringMacro(TargetFractions);
  ///@}
  ///@{
  /// Reflection symmetry: flags (x, y, z); the model is its own mirror image across a plane near
  /// the middle of the box normal to each axis flagged. Default (0, 0, 0).
  vtkSetVector3Macro(Mirror, int);
  vtkGetVector3Macro(Mirror, int);
  ///@}
  ///@{
  /// With proportions steered: labellings tried per block, the best kept. Default 1.
  vtkSetClampMacro(BlockCandidates, int, 1, 64);
  vtkGetMacro(BlockCandidates, int);
  ///@}
  ///@{
  /// Whole models synthesized (seeds Seed, Seed + 1, ...), the one closest to the guide, the
  /// proportions and the seeds kept ("generate several, keep the best match", TVCG §4.7); the
  /// field data then has `ModelChosen` and `MatchError`. Not with snapshots. Default 1.
  vtkSetClampMacro(ModelCandidates, int, 1, 1000);
  vtkGetMacro(ModelCandidates, int);
  ///@}

  /**
   * Checks Thickness, Overhang, Connected and TargetFractions against the object types and plane
   * families of @p example (analysed with the arrangement's @p angleToleranceDegrees and
   * @p maximumSmallInteger) before anything is computed: "" when they read, else the problem in
   * one line, as RequestData would report it after the plane arrangement is built (a mistyped
   * constraint then costs seconds, not the arrangement's minutes).
   */
  std::string CheckConstraints(
    vtkPolyData* example, double angleToleranceDegrees, int maximumSmallInteger);

protected:
  vtkMSContinuousSynthesis();
  ~vtkMSContinuousSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSContinuousSynthesis(const vtkMSContinuousSynthesis&) = delete;
  void operator=(const vtkMSContinuousSynthesis&) = delete;

  /// The labels (or the requested snapshot), the catalog and the field data on @p output.
  void FillOutput(vtkPolyData* arrangementData, vtkPolyData* output, vtkInformation* outInfo);

  vtkIdType Seed = 0;
  double BlockSize = -1;
  int Attempts = 20;
  int NumberOfThreads = 0;
  bool DistributeBlocks = true;
  int SiteOrder = AUTOMATIC_ORDER;
  int LabelChoice = UNIFORM;
  int NumberOfSnapshots = 0;
  bool Grounded = false;
  std::string Thickness;
  std::string Overhang;
  std::string Connected;
  bool KeepProportions = true;
  bool ExampleSizes = true;
  std::string TargetFractions;
  int BlockCandidates = 1;
  int ModelCandidates = 1;
  int Mirror[3] = { 0, 0, 0 };

  struct Cache;
  std::unique_ptr<Cache> Cached;
};

#endif
