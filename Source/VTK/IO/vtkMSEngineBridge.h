// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSEngineBridge
 * @brief The error collector of ModelSynth's VTK classes: internal VTK algorithms report through
 * ErrorEvent; the collector keeps their messages so that our own classes can report one clear
 * error that names the file. Execute runs an algorithm and says whether it succeeded.
 *
 * The conversions between VTK data and the engine are in vtkMSLabelArrays, vtkMSPolyhedra,
 * vtkMSFieldData, vtkMSArrangementStorage and vtkMSPipeline.
 */
#ifndef vtkMSEngineBridge_h
#define vtkMSEngineBridge_h

#include "Core/BlockSynthesis.h" // for AddStatistics
#include "ModelSynthIOModule.h"  // for export macro
#include "vtkObject.h"

#include <string>

class vtkAlgorithm;

class MODELSYNTHIO_EXPORT vtkMSEngineBridge : public vtkObject
{
public:
  static vtkMSEngineBridge* New();
  vtkTypeMacro(vtkMSEngineBridge, vtkObject);

  /**
   * Runs @p algorithm's pipeline pass (UpdateInformation when @p informationOnly, else Update)
   * and returns whether it succeeded, judged by the executive's return status (so it holds even
   * when VTK's global warning display is off) and by any ErrorEvent. @p messages receives the
   * collected error messages, or a generic sentence when the algorithm failed silently.
   */
  static bool Execute(vtkAlgorithm* algorithm, std::string& messages, bool informationOnly = false);

  /// Starts collecting ErrorEvent messages of @p source (removes earlier observation).
  void Watch(vtkObject* source);
  /// Stops collecting and forgets messages.
  void Reset();
  /// Collected messages, joined by "; " (empty when none).
  const std::string& GetMessages() const { return this->Messages; }
  bool HasErrors() const { return !this->Messages.empty(); }

protected:
  vtkMSEngineBridge() = default;
  ~vtkMSEngineBridge() override;

private:
  vtkMSEngineBridge(const vtkMSEngineBridge&) = delete;
  void operator=(const vtkMSEngineBridge&) = delete;

  void OnError(vtkObject* caller, unsigned long event, void* data);

  vtkObject* Source = nullptr;
  unsigned long Tag = 0;
  std::string Messages;
};

#endif
