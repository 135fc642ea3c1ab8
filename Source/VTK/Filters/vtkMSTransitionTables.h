// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSTransitionTables
 * @brief Analyzes a discrete example model: its labels, how often each occurs, and the
 * transition tables Tx, Ty, Tz of dissertation §3.1, Eq. 3.2 (which label may follow which
 * along +x, +y, +z).
 *
 * Input: vtkImageData with an integer label array on its points (the input array to process;
 * default point array `Label`, else the active scalars), as produced by vtkMSLabelGridReader.
 *
 * Output port 0, "Transitions": a vtkTable with one row per allowed pair, sorted by axis, then
 * From, then To: `Axis` (0, 1, 2), `Direction` ("+x", "+y", "+z"), `From` and `To` (label
 * values) and `Count` (how many times the pair occurs in the example).
 *
 * Output port 1, "Labels": a vtkTable with `Label` (value, ascending), `Index` (position in
 * that order, the label index used by the solver), `Count` and `Frequency` (Count / sites).
 *
 * Field data of both tables: `Labels` (the label values), `LabelCounts`, and `TransitionsX`,
 * `TransitionsY`, `TransitionsZ` (2-component int arrays of allowed (From, To) value pairs),
 * plus `ExampleFile` when the input carries it, and the infallibility analysis (§3.3.7,
 * msynth/Infallibility.h): `Infallible` (1 when proved), `InfallibilityExplanation`,
 * `Recommendation` (whole-model or block synthesis) and `InfallibilityRegion` (the region size
 * of Algorithm 3.6 that proved it: 2x2(x2), or up to 3x3 for 2D examples).
 *
 * In parallel (pvbatch --mpi) the analysis runs once: piece 0 asks for the whole example and
 * computes the tables; the other pieces ask for nothing and output empty tables, so gathered
 * results are not duplicated.
 *
 * @sa vtkMSLabelGridReader
 */
#ifndef vtkMSTransitionTables_h
#define vtkMSTransitionTables_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkTableAlgorithm.h"

class MODELSYNTHFILTERS_EXPORT vtkMSTransitionTables : public vtkTableAlgorithm
{
public:
  static vtkMSTransitionTables* New();
  vtkTypeMacro(vtkMSTransitionTables, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMSTransitionTables();
  ~vtkMSTransitionTables() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSTransitionTables(const vtkMSTransitionTables&) = delete;
  void operator=(const vtkMSTransitionTables&) = delete;
};

#endif
