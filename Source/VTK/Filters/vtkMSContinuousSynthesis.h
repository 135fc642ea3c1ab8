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
 * `Message`, ...; see vtkMSEngineBridge::AddStatistics). With NumberOfSnapshots S > 0 the output
 * has S + 1 time steps: the catalog at the start and at S even fractions of the work, so ParaView
 * can animate it shrinking; `Label` is then −1 where undecided and `ModelLabel` holds the finished
 * model at every step.
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

class MODELSYNTHFILTERS_EXPORT vtkMSContinuousSynthesis : public vtkPolyDataAlgorithm
{
public:
  static vtkMSContinuousSynthesis* New();
  vtkTypeMacro(vtkMSContinuousSynthesis, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The arrangement input (port 1).
  void SetArrangementConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// Random seed; equal seeds give equal models. Default 0.
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// Block edge in plane spacings (of the family with the largest spacing); blocks overlap by
  /// half. 0 labels the whole arrangement at once. Default 4.
  vtkSetClampMacro(BlockSize, double, 0.0, 1e6);
  vtkGetMacro(BlockSize, double);
  ///@}

  ///@{
  /// Attempts per block (or for the whole model). Default 20.
  vtkSetClampMacro(Attempts, int, 1, 1000000);
  vtkGetMacro(Attempts, int);
  ///@}

  ///@{
  /// Vertex order: 0 scan line (the dissertation), 1 random, 2 fewest labels first. Default 2.
  vtkSetClampMacro(SiteOrder, int, 0, 2);
  vtkGetMacro(SiteOrder, int);
  ///@}

  ///@{
  /// Label choice: 0 uniform (the dissertation), 1 weighted by occurrences in the example.
  vtkSetClampMacro(LabelChoice, int, 0, 1);
  vtkGetMacro(LabelChoice, int);
  ///@}

  ///@{
  /// Catalog snapshots as time steps (0: none). Default 0.
  vtkSetClampMacro(NumberOfSnapshots, int, 0, 10000);
  vtkGetMacro(NumberOfSnapshots, int);
  ///@}

protected:
  vtkMSContinuousSynthesis();
  ~vtkMSContinuousSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSContinuousSynthesis(const vtkMSContinuousSynthesis&) = delete;
  void operator=(const vtkMSContinuousSynthesis&) = delete;

  vtkIdType Seed = 0;
  double BlockSize = 4;
  int Attempts = 20;
  int SiteOrder = 2;
  int LabelChoice = 0;
  int NumberOfSnapshots = 0;

  struct Cache;
  std::unique_ptr<Cache> Cached;
};

#endif
