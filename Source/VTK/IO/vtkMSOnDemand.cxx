// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOnDemand.h"

#include "vtkAlgorithm.h"

#include "Core/Error.h"
#include "Core/ModuleBeside.h"

namespace
{
const vtkMSOnDemandTable* Load()
{
  using Entry = const vtkMSOnDemandTable* (*)();
  // Beside this library (libModelSynthIO), kept loaded: the objects it made may outlive any
  // one caller.
  const auto entry =
    reinterpret_cast<Entry>(msynth::ModuleEntryBeside(reinterpret_cast<const void*>(&Load),
      MSYNTH_VTK_ON_DEMAND_MODULE, MSYNTH_VTK_ON_DEMAND_SYMBOL));
  if (const vtkMSOnDemandTable* table = entry())
    return table;
  throw msynth::Error(
    std::string("the module '") + MSYNTH_VTK_ON_DEMAND_MODULE + "' gave no table");
}

const vtkMSOnDemandTable& Table()
{
  // A throwing initialization is retried by the next call (C++ static-local semantics).
  static const vtkMSOnDemandTable* const table = Load();
  return *table;
}

vtkSmartPointer<vtkAlgorithm> Take(vtkAlgorithm* algorithm)
{
  return vtkSmartPointer<vtkAlgorithm>::Take(algorithm);
}
} // namespace

vtkSmartPointer<vtkAlgorithm> vtkMSOnDemand::NewOBJReader(const std::string& fileName)
{
  return Take(Table().NewOBJReader(fileName.c_str()));
}

vtkSmartPointer<vtkAlgorithm> vtkMSOnDemand::NewPNGReader(const std::string& fileName)
{
  return Take(Table().NewPNGReader(fileName.c_str()));
}

vtkSmartPointer<vtkAlgorithm> vtkMSOnDemand::NewNearestPointResampler()
{
  return Take(Table().NewNearestPointResampler());
}

vtkSmartPointer<vtkAlgorithm> vtkMSOnDemand::NewTriangulator()
{
  return Take(Table().NewTriangulator());
}
