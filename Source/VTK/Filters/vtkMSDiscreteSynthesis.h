// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSDiscreteSynthesis
 * @brief Discrete model synthesis (Merrell's dissertation ch. 3): a new label grid of any size
 * whose every adjacent pair occurs in the example (the adjacency constraint, Eq. 3.3).
 *
 * Input: the example, vtkImageData with an integer point array of labels (default `Label`, else
 * the active scalars), as produced by vtkMSLabelGridReader.
 *
 * Output: vtkImageData of OutputSize points, with the example's spacing and origin. Point data:
 * `Label` (the model) and `LastBlock` (the block that last changed each site, -1 for never).
 * Field data: `Seed`, `ExampleFile` and the run statistics under the names every solver uses
 * (`Blocks`, `BlocksAccepted`, `BlocksFailed`, `BlocksRejected`, `Attempts`, `FailedAttempts`,
 * `Assignments`, `Phases`, `Threads`, `Processes`, `Seconds`, `Status`, `Message`,
 * `TrivialLabel` in block mode, `FailedBlockOrigins` and `FailedBlockSites` as 3-component
 * arrays; vtkMSFieldData::AddStatistics).
 *
 * BlockSize 0 on every axis (or at least OutputSize) runs Algorithm 3.1 on the whole model;
 * smaller blocks run Algorithm 3.4, which modifies a trivial consistent start block by block
 * and rolls a block back when it fails. A failed Algorithm 3.1 is an error and produces no
 * model.
 *
 * Boundary labels (Fig. 3.11) fix the outer layer of chosen faces, in the order -x, +x, -y,
 * +y, -z, +z: e.g. UseBoundary = (1,1,1,1,1,1) with BoundaryLabels = (0,0,0,0,g,0) puts ground
 * g along the bottom and empty space around.
 *
 * Symmetry (§3.5.2): Mirror = (x, y, z) flags make the output symmetric about the middle plane
 * of those axes, M(n − 1 − x) = f(M(x)); MirrorSwaps lists the labels that are each other's
 * mirror images as "a:b,c:d" (each pair swaps; other labels are their own image). The example's
 * rules must be symmetric under the map; otherwise the filter says which pair is not.
 * Translate = (x, y, z) flags repeat the output along those axes with TranslationPeriod
 * (0: the output size, which makes the output tile seamlessly), M(x + P) = f(M(x)) with f given
 * by TranslationMap "a:b,c:d" (a's image one period on is b; others map to themselves).
 * Rotate turns a quadrant into the other three: the output turned 90° counter-clockwise about
 * the vertical is f of itself, with f given by RotationMap (e.g. a tileset's orientations
 * "1:2,2:3,3:4,4:1"); the output must be square in x and y. These cannot be combined with each
 * other or with Mirror.
 *
 * Soft constraints (Merrell 2007, §4.2): TargetFractions "label:fraction,..." keeps each
 * block's change with the Metropolis probability min(1, exp(−ΔE / SoftTemperature)), where
 * E = N · Σ (fraction − target)², so label fractions drift toward the targets. Block
 * synthesis only; field data `BlocksRejected` counts the blocks rolled back.
 *
 * Label counts: Counts "L:MIN:MAX,..." keeps the number of sites of each label (or, with a
 * tileset, tile) L within [MIN, MAX]; impossible counts fail before any work. An entry
 * "region=R:L:MIN:MAX" counts only the sites of region R of the guide: the guide's integer
 * point array `Region` (stretched over the output box as its weights are) gives each site's.
 *
 * Large-scale constraints (§3.5.3): an optional second input, the guide, is vtkImageData
 * stretched over the output box whose point arrays `Weight_<label>` (e.g. `Weight_2`) give
 * each label's relative probability per guide point; 0 removes the label there. Labels without
 * an array have weight 1.
 *
 * Where the rules come from (SetSource): the example on input 0 (SetSourceToExample), a tileset
 * (SetSourceToTileset, TilesetFile) or an image sample (SetSourceToSample, SampleFile); by
 * default (AUTOMATIC_SOURCE) the file that is set, else the example. An explicit source uses
 * its own file only and fails the request when it is not set.
 *
 * Tilesets: with TilesetFile set (simple-tiled XML, msynth/Tileset.h) the rules come from the
 * tileset and the example input is not needed; label i is an orientation of a tile, named in
 * the field array `TileNames` ("tile k"). vtkMSTileImage composes the tiles' images.
 * MarkovJunior's voxel tilesets (`<tileset>` root, Formats/VoxelTileset.h) work the same way,
 * their tiles read from TilesFolder (default: the folder named like the XML); label i is a
 * distinct image of a tile, recorded per label in the field arrays `LabelTile` (the tile's
 * name) and `LabelSymmetry` (a symmetry giving it, 0-7 or 0-47), and the geometry output shows
 * the tiles' coloured voxels (vtkMSLabelArrays::TileVoxels, cell array `PaletteColor`).
 *
 * Image samples (the overlapping model of WaveFunctionCollapse, Discrete/OverlappingModel.h):
 * with SampleFile set (a PNG or BMP picture) the labels are the sample's PatternSize ×
 * PatternSize pixel windows, with the first PatternSymmetry of their dihedral images, wrapping
 * around the sample with PeriodicInput; patterns are neighbours where they overlap. OutputSize
 * is then the picture's size in pixels: the label grid has (W − N + 1) × (H − N + 1) sites, or W
 * (H) along an axis that Translate makes repeat (a seamlessly tiling picture). Ground puts the
 * sample's bottom-middle window along the bottom row and nowhere else (no guide input then).
 * The field data records the sample and its options (`SampleFile`, `PatternSize`,
 * `PatternSymmetry`, `PeriodicInput`, `Ground`, `PeriodicOutput`), from which vtkMSPatternImage
 * composes the picture.
 *
 * The result depends only on the inputs and Seed.
 *
 * Watching the solver: with CatalogSnapshotsPerBlock S > 0 the output has time steps
 * 0 .. Blocks × S (known before the run from the sizes): step 0 is the start, then S steps per
 * block taken as the block's sites get decided; the last step is the model. Each step adds the
 * point arrays `CatalogSize` (labels still possible) and `Entropy` (of the weighted possible
 * labels), and `Label` holds vtkMSLabelArrays::Undecided (VTK_INT_MIN) where a site is not decided
 * yet (CatalogSize > 1). Field data adds `Step`, `ActiveBlock` and `StepAssignments`. The run is
 * done once and cached; changing the time step only picks another snapshot.
 *
 * Geometry: output port 1 (GetGeometryOutput) is the model's voxel surface, vtkPolyData with
 * the cell scalars `Label`, so that a viewer shows the model itself rather than the outline of
 * a label image: each non-empty site is a cube, with a face wherever it meets another label
 * (vtkMSLabelArrays::VoxelSurface). Sites holding EmptyLabel, and in a snapshot the sites not
 * decided yet, give none. It follows the requested time step, and under MPI each piece holds a
 * slab of the sites. GenerateGeometry off leaves it empty (it costs about as much as writing
 * the model). For model pieces in place of voxels, use vtkMSLabelGeometry on port 0.
 *
 * @sa vtkMSLabelGridReader, vtkMSTransitionTables, vtkMSLabelGeometry
 */
#ifndef vtkMSDiscreteSynthesis_h
#define vtkMSDiscreteSynthesis_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <functional> // for std::function
#include <memory>     // for std::unique_ptr
#include <string>     // for ivar
#include <vector>     // for std::vector

class vtkDataArray;
class vtkImageData;
class vtkPolyData;
namespace msynth
{
class AdjacencyRules;
struct BlockFailure;
struct SynthesisOptions;
struct SynthesisResult;
}

class MODELSYNTHFILTERS_EXPORT vtkMSDiscreteSynthesis : public vtkImageAlgorithm
{
public:
  static vtkMSDiscreteSynthesis* New();
  vtkTypeMacro(vtkMSDiscreteSynthesis, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How labels are drawn from the catalog.
  enum LabelChoices
  {
    UNIFORM = 0,    ///< every possible label equally likely (the dissertation)
    FREQUENCY = 1,  ///< weighted by the label's frequency in the example
    RESEMBLANCE = 2 ///< weighted by how well the site's window matches the example (2007, Eqs. 2-6)
  };
  /// The order in which sites are assigned.
  enum SiteOrders
  {
    SCAN_LINE = 0,      ///< x fastest, then y, then z (the dissertation)
    RANDOM = 1,         ///< a seeded random permutation
    MINIMUM_ENTROPY = 2 ///< fewest choices first (as WaveFunctionCollapse)
  };
  /// Where the rules come from.
  enum Sources
  {
    AUTOMATIC_SOURCE = 0, ///< the file that is set (tileset or sample), else the example
    EXAMPLE_SOURCE = 1,   ///< the label grid on input 0
    TILESET_SOURCE = 2,   ///< TilesetFile
    SAMPLE_SOURCE = 3     ///< SampleFile
  };
  /// How block synthesis starts (msynth::BlockStart).
  enum BlockStarts
  {
    AUTOMATIC_START = 0,  ///< a probe chooses: trivial unless it leaves the model blank
    TRIVIAL_START = 1,    ///< Algorithm 3.4's trivial model (one label, or layers)
    UNDECIDED_START = 2,  ///< every site free until a block decides it
    WHOLE_MODEL_START = 3 ///< a whole-model solution that the blocks modify
  };

  ///@{
  /// Where the rules come from: a Sources value. Default AUTOMATIC_SOURCE.
  vtkSetClampMacro(Source, int, AUTOMATIC_SOURCE, SAMPLE_SOURCE);
  vtkGetMacro(Source, int);
  void SetSourceToExample() { this->SetSource(EXAMPLE_SOURCE); }
  void SetSourceToTileset() { this->SetSource(TILESET_SOURCE); }
  void SetSourceToSample() { this->SetSource(SAMPLE_SOURCE); }
  /// The source a run uses: Source, or for AUTOMATIC_SOURCE the file that is set (TILESET_SOURCE
  /// when both are, which the run refuses).
  int GetActiveSource() const;
  ///@}

  ///@{
  /// Output size in sites (n_z = 1 for 2D). Default 32 × 32 × 8.
  vtkSetVector3Macro(OutputSize, int);
  vtkGetVector3Macro(OutputSize, int);
  ///@}

  ///@{
  /**
   * A region of the world (x0 y0 z0 x1 y1 z1, half-open; all 0: the whole output): OutputSize
   * is then the world's size, and the output holds just the region's sites, placed where they
   * lie in the world (the origin moved by x0 · spacing, ...), computed from the region's
   * dependency cone alone (msynth::SynthesizeRegion): the same labels as a whole run, at a cost
   * set by the region. Label grids and tilesets; no
   * symmetry, soft constraints, pins, guide, snapshots or resemblance. Default all 0.
   */
  vtkSetVector6Macro(Region, int);
  vtkGetVector6Macro(Region, int);
  ///@}

  ///@{
  /**
   * The streaming pipeline's way to a region: the output's whole extent is the world
   * (OutputSize, up to 2^31 sites per axis) and a request for a smaller update extent (an
   * *Extract Subset* downstream, a piece under MPI) computes just that extent from its
   * dependency cone (msynth::SynthesizeRegion), with no exchange between processes; the field
   * Blocks counts the blocks run. The same restrictions as Region; not with Region or an image
   * sample. Default off.
   */
  vtkSetMacro(ComputeRequestedExtent, bool);
  vtkGetMacro(ComputeRequestedExtent, bool);
  vtkBooleanMacro(ComputeRequestedExtent, bool);
  /// Whether requested extents are computed: ComputeRequestedExtent, without Region or a sample.
  bool ProducesSubExtents() const;
  ///@}

  ///@{
  /// Block size of Algorithm 3.4; 0 on an axis means the whole axis. Default 0 0 0 (whole
  /// model, Algorithm 3.1).
  vtkSetVector3Macro(BlockSize, int);
  vtkGetVector3Macro(BlockSize, int);
  ///@}

  ///@{
  /// Overlap of consecutive blocks; -1 means half a block. Default -1 -1 -1.
  vtkSetVector3Macro(BlockOverlap, int);
  vtkGetVector3Macro(BlockOverlap, int);
  ///@}

  ///@{
  /// Attempts per block before it keeps its previous labels. Default 10.
  vtkSetClampMacro(AttemptsPerBlock, int, 1, 1000000);
  vtkGetMacro(AttemptsPerBlock, int);
  ///@}

  ///@{
  /// Choices an attempt may undo when a catalog becomes empty (chronological backtracking; a
  /// deviation from the dissertation's algorithms, which end the attempt there: 0). Default 1000.
  vtkSetClampMacro(BacktracksPerAttempt, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(BacktracksPerAttempt, vtkIdType);
  ///@}

  ///@{
  /// Try blocks whose attempts all failed once more after every other block (twice the
  /// attempts, alternating minimum-entropy and scan-line order; not with snapshots or soft
  /// constraints). Default on.
  vtkSetMacro(RepairFailedBlocks, bool);
  vtkGetMacro(RepairFailedBlocks, bool);
  vtkBooleanMacro(RepairFailedBlocks, bool);
  ///@}

  ///@{
  /// How block synthesis starts: a BlockStarts value. Default AUTOMATIC_START (the field data's
  /// StartFrom says which was used).
  vtkSetClampMacro(BlockStart, int, AUTOMATIC_START, WHOLE_MODEL_START);
  vtkGetMacro(BlockStart, int);
  ///@}

  ///@{
  /// D§3.3.8: run Algorithm 3.1 on an infallible refinement E_I of the label-grid example and
  /// map the model back with f (msynth::SynthesizeViaInfallible): the whole model, scan-line
  /// order, one attempt, no blocks. An error when no refinement is found, for tilesets and
  /// samples, and with options that name E's labels or blocks. The Message field names the
  /// split. Default off.
  vtkSetMacro(ViaInfallible, bool);
  vtkGetMacro(ViaInfallible, bool);
  vtkBooleanMacro(ViaInfallible, bool);
  ///@}

  ///@{
  /// When whole-model synthesis fails every attempt, synthesize in 32-site blocks instead and say
  /// so in the Message field (not with snapshots). Default on.
  vtkSetMacro(BlocksWhenWholeFails, bool);
  vtkGetMacro(BlocksWhenWholeFails, bool);
  vtkBooleanMacro(BlocksWhenWholeFails, bool);
  ///@}

  ///@{
  /// Random seed (any value; used as 64 bits). Default 0.
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// LabelChoices value. Default UNIFORM.
  vtkSetClampMacro(LabelChoice, int, UNIFORM, RESEMBLANCE);
  vtkGetMacro(LabelChoice, int);
  void SetLabelChoiceToUniform() { this->SetLabelChoice(UNIFORM); }
  void SetLabelChoiceToFrequency() { this->SetLabelChoice(FREQUENCY); }
  void SetLabelChoiceToResemblance() { this->SetLabelChoice(RESEMBLANCE); }
  ///@}

  ///@{
  /// Sets the guide volume (input port 1); nullptr removes it.
  void SetGuideConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetGuideData(vtkDataObject* guide) { this->SetInputData(1, guide); }
  ///@}

  ///@{
  /// Sets the pinned sites (input port 2), to complete a partial model: image data of the output
  /// size whose point array "Label" (or active scalars) holds the labels to keep and -1 where
  /// sites are synthesized; nullptr removes it. Pins that cannot hold are an error before any
  /// work; with blocks each pin is first placed with a block around it, and no block changes it.
  /// A picture on the input (unsigned char RGB(A) scalars, no "Label" array, e.g. a
  /// vtkPNGReader's output) pins the tiles of a 2D tileset run: it is cut into tile-sized cells,
  /// each a tile's image (pinned) or fully transparent (free) (msynth::PinsFromPicture); and
  /// the patterns of an image sample run: a site whose N × N window is drawn (no transparent
  /// pixel) is pinned to that window's pattern (msynth::PatternSet::PinsFromPicture).
  void SetFixedConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetFixedData(vtkDataObject* fixed) { this->SetInputData(2, fixed); }
  /// The pinned sites from a file when input port 2 is not connected: a label grid (.vti, .txt,
  /// .vox) or, for a 2D tileset or an image sample, a picture (.png, .bmp) as above. Default "".
  /// The tileset and image-sample proxies, which have no inputs, offer this in the GUI.
  vtkSetStdStringFromCharMacro(FixedFile);
  vtkGetCharFromStdStringMacro(FixedFile);
  /// Label 0 of the pinned sites is free too (a MagicaVoxel model's empty voxels). Default off.
  vtkSetMacro(FixedEmptyFree, bool);
  vtkGetMacro(FixedEmptyFree, bool);
  vtkBooleanMacro(FixedEmptyFree, bool);

  ///@{
  /// A tileset (.xml) to take the rules from instead of the example, and the subset of its tiles
  /// to use ("" for all). Default "".
  vtkSetStdStringFromCharMacro(TilesetFile);
  vtkGetCharFromStdStringMacro(TilesetFile);
  vtkSetStdStringFromCharMacro(TilesetSubset);
  vtkGetCharFromStdStringMacro(TilesetSubset);
  ///@}

  ///@{
  /// The folder of a voxel tileset's tiles (`NAME.vox` per tile): as given, or relative to the
  /// tileset's folder; "" (default) for the folder named like the tileset file.
  vtkSetStdStringFromCharMacro(TilesFolder);
  vtkGetCharFromStdStringMacro(TilesFolder);
  ///@}

  ///@{
  /// An image sample (.png, .bmp) to take the rules from instead of the example: its
  /// PatternSize × PatternSize windows (1-8, default 3) with the first PatternSymmetry (1-8,
  /// default 8) of their dihedral images are the labels; PeriodicInput (default on) lets windows
  /// wrap around the sample; Ground keeps the bottom-middle window on the bottom row. Default
  /// "" (none).
  vtkSetStdStringFromCharMacro(SampleFile);
  vtkGetCharFromStdStringMacro(SampleFile);
  vtkSetClampMacro(PatternSize, int, 1, 8);
  vtkGetMacro(PatternSize, int);
  vtkSetClampMacro(PatternSymmetry, int, 1, 8);
  vtkGetMacro(PatternSymmetry, int);
  vtkSetMacro(PeriodicInput, bool);
  vtkGetMacro(PeriodicInput, bool);
  vtkBooleanMacro(PeriodicInput, bool);
  vtkSetMacro(Ground, bool);
  vtkGetMacro(Ground, bool);
  vtkBooleanMacro(Ground, bool);
  ///@}

  ///@{
  /// Soft constraints: wanted label fractions, "label:fraction,..." ("" for none), and the
  /// temperature of their Metropolis acceptance. Defaults "" and 0.01.
  vtkSetStdStringFromCharMacro(TargetFractions);
  vtkGetCharFromStdStringMacro(TargetFractions);
  vtkSetClampMacro(SoftTemperature, double, 1e-9, 1e9);
  vtkGetMacro(SoftTemperature, double);
  ///@}

  ///@{
  /// Label counts (a hard constraint, msynth::SynthesisOptions::Counts): "L:MIN:MAX,..." ("" for
  /// none; default), the sites holding L are MIN to MAX; with a tileset L may name a tile (all
  /// its orientations) or a label ("tile k"); "region=R:L:MIN:MAX" counts in the guide's region
  /// R only (its point array `Region`). Field data `CountNames`, `CountMinimum`,
  /// `CountMaximum`, `CountAchieved`, `CountRegion` (-1: whole model) report them.
  vtkSetStdStringFromCharMacro(Counts);
  vtkGetCharFromStdStringMacro(Counts);
  ///@}

  ///@{
  /// A connected network (a hard constraint, msynth::SynthesisOptions::Connected): "LABELS[:N]"
  /// ("" for none; default), the sites holding any of LABELS (values, or with a tileset tile or
  /// label names; commas between) form at most N (default 1) components, through the tiles'
  /// `connects` sides where the tileset gives them. Field data `ConnectedComponents`,
  /// `ConnectedBefore`, `ConnectedRepairs`, `ConnectedRedone` report the run.
  vtkSetStdStringFromCharMacro(Connected);
  vtkGetCharFromStdStringMacro(Connected);
  /// A path the network joins, "A;B;...": sites "x,y[,z]" and labels (values or names: every
  /// site holding one), all in one component of the Connected network (which must be given);
  /// field data `ConnectedPathSites`. "" for none (default).
  vtkSetStdStringFromCharMacro(Path);
  vtkGetCharFromStdStringMacro(Path);
  ///@}

  ///@{
  /// Threads for block synthesis; 0 uses one per core. The model does not depend on it.
  /// Default 0.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// Under MPI (pvbatch --mpi), spread the blocks of each phase over the ranks and exchange
  /// the results (the model is the same as on one process; every rank outputs it). Runs with
  /// catalog snapshots or translation/rotation symmetry run every block on every rank.
  /// Default on.
  vtkSetMacro(DistributeBlocks, bool);
  vtkGetMacro(DistributeBlocks, bool);
  vtkBooleanMacro(DistributeBlocks, bool);
  ///@}

  ///@{
  /// Half-width w of the resemblance window ((2w + 1)³ sites). Default 1.
  vtkSetClampMacro(ResemblanceWindow, int, 0, 8);
  vtkGetMacro(ResemblanceWindow, int);
  ///@}

  ///@{
  /// SiteOrders value. Default SCAN_LINE.
  vtkSetClampMacro(SiteOrder, int, SCAN_LINE, MINIMUM_ENTROPY);
  vtkGetMacro(SiteOrder, int);
  void SetSiteOrderToScanLine() { this->SetSiteOrder(SCAN_LINE); }
  void SetSiteOrderToRandom() { this->SetSiteOrder(RANDOM); }
  void SetSiteOrderToMinimumEntropy() { this->SetSiteOrder(MINIMUM_ENTROPY); }
  ///@}

  ///@{
  /// Which faces (-x, +x, -y, +y, -z, +z) have a fixed boundary label. Default none.
  vtkSetVector6Macro(UseBoundary, int);
  vtkGetVector6Macro(UseBoundary, int);
  ///@}

  ///@{
  /// One face of the boundary at a time (the ParaView panel's check boxes, one per face): a
  /// face has its fixed label when UseBoundary or its own flag here says so. Default 0.
  void SetBoundaryXMin(int use) { this->SetBoundaryFace(0, use); }
  void SetBoundaryXMax(int use) { this->SetBoundaryFace(1, use); }
  void SetBoundaryYMin(int use) { this->SetBoundaryFace(2, use); }
  void SetBoundaryYMax(int use) { this->SetBoundaryFace(3, use); }
  void SetBoundaryZMin(int use) { this->SetBoundaryFace(4, use); }
  void SetBoundaryZMax(int use) { this->SetBoundaryFace(5, use); }
  /// @p face 0-5 in the order of UseBoundary.
  void SetBoundaryFace(int face, int use);
  int GetBoundaryFace(int face) const;
  ///@}

  ///@{
  /// The label value fixed on each face where UseBoundary is set. Default 0.
  vtkSetVector6Macro(BoundaryLabels, int);
  vtkGetVector6Macro(BoundaryLabels, int);
  ///@}

  ///@{
  /// Use TrivialLabel as the trivial start of block synthesis instead of choosing one
  /// automatically (label 0 when it can tile space, else the most frequent such label).
  vtkSetMacro(UseTrivialLabel, bool);
  vtkGetMacro(UseTrivialLabel, bool);
  vtkBooleanMacro(UseTrivialLabel, bool);
  vtkSetMacro(TrivialLabel, int);
  vtkGetMacro(TrivialLabel, int);
  ///@}

  ///@{
  /// Axes (x, y, z) along which the output is mirror-symmetric. Default 0 0 0.
  vtkSetVector3Macro(Mirror, int);
  vtkGetVector3Macro(Mirror, int);
  ///@}

  ///@{
  /// Label pairs that are mirror images, "a:b,c:d". Default "" (every label is its own image).
  vtkSetStdStringFromCharMacro(MirrorSwaps);
  vtkGetCharFromStdStringMacro(MirrorSwaps);
  ///@}

  ///@{
  /// Axes (x, y, z) along which the output repeats (translation symmetry). Default 0 0 0.
  vtkSetVector3Macro(Translate, int);
  vtkGetVector3Macro(Translate, int);
  ///@}

  ///@{
  /// The period per translated axis; 0 means the output size (a tileable output). Default 0 0 0.
  vtkSetVector3Macro(TranslationPeriod, int);
  vtkGetVector3Macro(TranslationPeriod, int);
  ///@}

  ///@{
  /// Each label's image one period on, "a:b,c:d". Default "" (every label is its own image).
  vtkSetStdStringFromCharMacro(TranslationMap);
  vtkGetCharFromStdStringMacro(TranslationMap);
  ///@}

  ///@{
  /// Rotation symmetry by 90° about the vertical through the centre. Default off.
  vtkSetMacro(Rotate, bool);
  vtkGetMacro(Rotate, bool);
  vtkBooleanMacro(Rotate, bool);
  ///@}

  ///@{
  /// Each label's image turned 90° counter-clockwise, "a:b,c:d". Default "": every label is its
  /// own image, or with a tileset, each tile's next orientation.
  vtkSetStdStringFromCharMacro(RotationMap);
  vtkGetCharFromStdStringMacro(RotationMap);
  ///@}

  ///@{
  /// Catalog snapshots per block, exposed as time steps (see above). Default 0 (none).
  vtkSetClampMacro(CatalogSnapshotsPerBlock, int, 0, 100000);
  vtkGetMacro(CatalogSnapshotsPerBlock, int);
  ///@}

  ///@{
  /// Memory allowed for snapshots (sites × steps × 12 bytes). Default 2 GiB.
  vtkSetClampMacro(MaximumSnapshotMemory, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumSnapshotMemory, vtkIdType);
  ///@}

  ///@{
  /// Whether output port 1 holds the model's voxel surface. Default on.
  vtkSetMacro(GenerateGeometry, bool);
  vtkGetMacro(GenerateGeometry, bool);
  vtkBooleanMacro(GenerateGeometry, bool);
  ///@}

  ///@{
  /// The label that gives no geometry on port 1 (the example's empty space). Default 0.
  vtkSetMacro(EmptyLabel, int);
  vtkGetMacro(EmptyLabel, int);
  ///@}

  /// Output port 1: the model's voxel surface.
  vtkPolyData* GetGeometryOutput();

  /// The label grid's size along @p axis: OutputSize, or with a SampleFile the number of
  /// pattern sites a picture of OutputSize pixels needs.
  int GridSize(int axis) const;

  /// Whether Region is set (not all 0).
  bool HasRegion() const;

  /// Synthesize, SynthesizeRegion with a Region or a requested extent, or SynthesizeStreamed
  /// within StreamWorld.
  msynth::SynthesisResult Run(
    const msynth::AdjacencyRules& rules, const msynth::SynthesisOptions& options);

#ifndef __VTK_WRAP__
  /**
   * Makes the next update compute the world slab by slab in bounded memory instead of as one
   * output (msynth::SynthesizeStreamed; `msynth synthesize --stream`): slabs of @p thickness
   * sites along the axis with the most blocks (0: about 2^21 sites a slab), from slab @p first
   * on, each handed to @p receive (with its index and the number of slabs) as soon as no later
   * block can change it: an image placed where it lies in the world, with the output's arrays
   * and field data. False from @p receive cancels; what it throws fails the update with its
   * message. The slabs equal the same sites of the whole output. Needs blocks smaller than the
   * world, no Region or requested extent, and no option that needs the whole world (symmetry,
   * soft constraints, pins, guide, snapshots, resemblance). That update's output holds no
   * sites, only the run's field data, until the filter is modified again. Each slab's field
   * data lists the failed blocks whose first layer is its own (FailedBlockOrigins,
   * FailedBlockSites); a resumed run (@p first > 0) takes those of the slabs it keeps in
   * @p kept (Block keys are recomputed from the origins), so its output reports the world's
   * failures as an uninterrupted run does.
   */
  void StreamNextUpdate(vtkIdType thickness, int first,
    const std::function<bool(vtkImageData* slab, int index, int count)>& receive,
    const std::vector<msynth::BlockFailure>& kept = {});
#endif

  /// The event StreamNextUpdate(thickness, first) invokes for each slab.
  enum
  {
    SlabEvent = 0x4D530001 // vtkCommand::UserEvent range
  };
  /**
   * StreamNextUpdate for scripts: each slab becomes GetCurrentSlab() (with its index in
   * GetCurrentSlabIndex() of GetNumberOfSlabs()) while SlabEvent is invoked; setting
   * AbortExecute in an observer cancels.
   */
  void StreamNextUpdate(vtkIdType thickness, int first);
  vtkImageData* GetCurrentSlab();
  vtkGetMacro(CurrentSlabIndex, int);
  vtkGetMacro(NumberOfSlabs, int);

protected:
  vtkMSDiscreteSynthesis();
  ~vtkMSDiscreteSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSDiscreteSynthesis(const vtkMSDiscreteSynthesis&) = delete;
  void operator=(const vtkMSDiscreteSynthesis&) = delete;

  /// Runs the engine on the example (or the tileset, or the sample) into the cache; false after
  /// an error.
  bool Solve(vtkImageData* input, vtkDataArray* labels, msynth::SynthesisOptions& options);
  /// The patterns of SampleFile and their synthesis, into the cache.
  void SolveSample(msynth::SynthesisOptions& options);
  /// The model of @p result (or the requested snapshot) placed at @p extent in the world (all
  /// -1: at the origin), LastBlock and the field data on @p output.
  void FillOutput(vtkImageData* input, vtkImageData* output, std::size_t step,
    const msynth::SynthesisResult& result, const int extent[6]);

  int OutputSize[3] = { 32, 32, 8 };
  int BlockSize[3] = { 0, 0, 0 };
  int BlockOverlap[3] = { -1, -1, -1 };
  int Region[6] = { 0, 0, 0, 0, 0, 0 };
  bool ComputeRequestedExtent = false;
  int AttemptsPerBlock = 10;
  vtkIdType BacktracksPerAttempt = 1000;
  bool RepairFailedBlocks = true;
  int BlockStart = AUTOMATIC_START;
  int Source = AUTOMATIC_SOURCE;
  bool BlocksWhenWholeFails = true;
  bool ViaInfallible = false;
  vtkIdType Seed = 0;
  int LabelChoice = UNIFORM;
  int SiteOrder = SCAN_LINE;
  int UseBoundary[6] = { 0, 0, 0, 0, 0, 0 };
  int BoundaryFaces[6] = { 0, 0, 0, 0, 0, 0 };
  int BoundaryLabels[6] = { 0, 0, 0, 0, 0, 0 };
  bool UseTrivialLabel = false;
  int TrivialLabel = 0;
  int CatalogSnapshotsPerBlock = 0;
  int ResemblanceWindow = 1;
  int NumberOfThreads = 0;
  bool DistributeBlocks = true;
  int Mirror[3] = { 0, 0, 0 };
  std::string MirrorSwaps;
  int Translate[3] = { 0, 0, 0 };
  int TranslationPeriod[3] = { 0, 0, 0 };
  std::string TranslationMap;
  bool Rotate = false;
  std::string RotationMap;
  std::string TilesetFile;
  std::string TilesFolder;
  std::string TargetFractions;
  double SoftTemperature = 0.01;
  std::string Counts;
  std::string Connected;
  std::string Path;
  std::string TilesetSubset;
  std::string FixedFile;
  bool FixedEmptyFree = false;
  std::string SampleFile;
  int PatternSize = 3;
  int PatternSymmetry = 8;
  bool PeriodicInput = true;
  bool Ground = false;
  vtkIdType MaximumSnapshotMemory = vtkIdType(1) << 31;
  bool GenerateGeometry = true;
  int EmptyLabel = 0;
  int CurrentSlabIndex = -1;
  int NumberOfSlabs = 0;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
