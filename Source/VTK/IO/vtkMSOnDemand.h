// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSOnDemand
 * @brief The VTK algorithms only some runs use, from a module loaded the first time one is asked
 * for.
 *
 * Four VTK classes are used in one place each, yet linking them would load half of VTK in every
 * process: vtkOBJReader (VTK::IOGeometry, which brings FiltersHybrid, RenderingCore,
 * FiltersGeneral, FiltersGeometry, FiltersSources, ImagingSources), vtkPointInterpolator with a
 * vtkVoronoiKernel (VTK::FiltersPoints, which brings FiltersModeling), vtkTriangleFilter
 * (VTK::FiltersCore) and vtkPNGReader (VTK::IOImage, which brings ImagingCore, DICOMParser,
 * metaio, libtiff, libjpeg and more): about 30 shared libraries and 60 % of the symbol binding of
 * a small `msynth` run's start-up (Documentation/performance.md, "What a 16² run costs").
 *
 * They are built into the module `libModelSynthVTKOnDemand.so` (vtkMSOnDemandModule.cxx), which
 * these functions open with dlopen from the folder of libModelSynthIO on first use and keep open.
 * The module exports one C function, `msynth_vtk_on_demand`, returning a table of factories. A
 * module that does not load is an error naming it and the loader's reason (msynth::Error).
 */
#ifndef vtkMSOnDemand_h
#define vtkMSOnDemand_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkSmartPointer.h"

#include <string>

class vtkAlgorithm;

class MODELSYNTHIO_EXPORT vtkMSOnDemand
{
public:
  /// A vtkOBJReader of @p fileName.
  static vtkSmartPointer<vtkAlgorithm> NewOBJReader(const std::string& fileName);
  /// A vtkPNGReader of @p fileName.
  static vtkSmartPointer<vtkAlgorithm> NewPNGReader(const std::string& fileName);
  /// A vtkPointInterpolator with a vtkVoronoiKernel (each output point takes the values of the
  /// nearest input point): input port 0 the points to sample at, port 1 (its "source") the data.
  static vtkSmartPointer<vtkAlgorithm> NewNearestPointResampler();
  /// A vtkTriangleFilter that drops vertices and lines.
  static vtkSmartPointer<vtkAlgorithm> NewTriangulator();
};

/// The module's table (C linkage; each factory returns a new reference).
struct vtkMSOnDemandTable
{
  vtkAlgorithm* (*NewOBJReader)(const char* fileName);
  vtkAlgorithm* (*NewPNGReader)(const char* fileName);
  vtkAlgorithm* (*NewNearestPointResampler)();
  vtkAlgorithm* (*NewTriangulator)();
};

/// The symbol the module exports.
#define MSYNTH_VTK_ON_DEMAND_SYMBOL "msynth_vtk_on_demand"

#endif
