// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOnDemand.h"

#include "vtkAlgorithm.h"

#include "Core/Error.h"

#include <dlfcn.h>

namespace
{
/// The folder of this library (libModelSynthIO), where the module is built and installed.
std::string ThisLibraryFolder()
{
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&ThisLibraryFolder), &info) == 0 || !info.dli_fname)
  {
    return std::string();
  }
  const std::string path = info.dli_fname;
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

const vtkMSOnDemandTable* Load()
{
  const std::string path = ThisLibraryFolder() + MSYNTH_VTK_ON_DEMAND_MODULE;
  // Kept loaded for the life of the process: the objects it made may outlive any one caller.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
  {
    const char* why = dlerror();
    throw msynth::Error(
      "the module '" + path + "' does not load (" + (why ? why : "no reason given") + ")");
  }
  using Entry = const vtkMSOnDemandTable* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, MSYNTH_VTK_ON_DEMAND_SYMBOL));
  const vtkMSOnDemandTable* table = entry ? entry() : nullptr;
  if (!table)
  {
    throw msynth::Error("the module '" + path + "' has no " MSYNTH_VTK_ON_DEMAND_SYMBOL);
  }
  return table;
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
