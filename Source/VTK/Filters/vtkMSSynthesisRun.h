// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMSSynthesisRun.h
 * @brief What every synthesis filter shares (vtkMSDiscreteSynthesis, vtkMSTimeVaryingSynthesis,
 * vtkMSContinuousSynthesis; private to the Filters module): the result cache, the abort path
 * (progress and cancellation), the guarded call into the engine, the report of a run's
 * status, and the catalog arrays of a snapshot.
 *
 * The filters derive from different VTK algorithms (image, poly data, multi-time-step), which
 * VTK's wrapping cannot give one templated base; they own these pieces instead.
 */
#ifndef vtkMSSynthesisRun_h
#define vtkMSSynthesisRun_h

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"

#include "Core/BlockSynthesis.h"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

class vtkDataSet;

/**
 * The result of a filter's last run and what it was computed from. Fresh() says whether a new
 * run is needed: the filter or an input (by pointer and modification time) changed since, or
 * the last run did not succeed (a cancelled run is never kept).
 */
template <class ResultT>
struct vtkMSSynthesisCache
{
  ResultT Result;

  bool Fresh(vtkAlgorithm* filter, const std::vector<vtkDataObject*>& inputs) const
  {
    return !this->Valid || this->FilterTime != filter->GetMTime() || this->Inputs != Stamps(inputs);
  }
  /// Records the run just made; @p valid: it succeeded.
  void Keep(vtkAlgorithm* filter, const std::vector<vtkDataObject*>& inputs, bool valid)
  {
    this->FilterTime = filter->GetMTime();
    this->Inputs = Stamps(inputs);
    this->Valid = valid;
  }
  void Clear() { this->Valid = false; }

private:
  using Stamp = std::pair<vtkDataObject*, vtkMTimeType>;
  static std::vector<Stamp> Stamps(const std::vector<vtkDataObject*>& inputs)
  {
    std::vector<Stamp> out;
    for (vtkDataObject* d : inputs)
      out.emplace_back(d, d ? d->GetMTime() : 0);
    return out;
  }
  vtkMTimeType FilterTime = 0;
  std::vector<Stamp> Inputs;
  bool Valid = false;
};

namespace vtkMSSynthesisRun
{
/// The engine's progress callback for @p filter: its progress, and false once it is aborted.
std::function<bool(double)> Progress(vtkAlgorithm* filter);

/// A guide's point arrays named Weight_<suffix>, as (suffix, one weight per point), in array
/// order. @throw msynth::Error naming an array that has more than one component.
std::vector<std::pair<std::string, std::vector<float>>> GuideWeights(vtkDataSet* guide);

/**
 * Calls @p solve; an exception becomes an error of @p filter (running out of memory says that
 * @p what needs more memory than is available). Returns false after an error.
 */
bool Solve(vtkAlgorithm* filter, const std::string& what, const std::function<void()>& solve);

/// A run's outcome: an error of @p filter (prefixed by @p context when set) unless it
/// succeeded or was cancelled. Returns whether it succeeded.
bool Report(vtkAlgorithm* filter, msynth::SynthesisStatus status, const std::string& message,
  const std::string& context = std::string());

/**
 * Blocks shared among the processes of the global controller (MPI ranks) when there are two or
 * more and every one passes the same nonzero @p fingerprint (the same inputs and options, so
 * the same schedule); else an inactive exchange (each process computes alone). Collective:
 * every process calls it.
 */
msynth::BlockExchange ProcessExchange(std::int64_t fingerprint);

/// The catalog on @p output: point arrays CatalogSize and Entropy.
void AddCatalog(
  vtkDataSet* output, const std::vector<std::int32_t>& size, const std::vector<float>& entropy);

/// Which snapshot @p output shows: field values Step, ActiveBlock and StepAssignments.
void AddStep(vtkDataSet* output, std::int64_t step, std::int64_t block, std::int64_t assignments);
}

#endif
