// SPDX-License-Identifier: BSD-3-Clause
// The module libModelSynthVTKOnDemand.so: the VTK algorithms only some runs use, behind the C
// table of vtkMSOnDemand.h so that only the processes that use one load their libraries.
#include "vtkMSOnDemand.h"

#include "vtkOBJReader.h"
#include "vtkPNGReader.h"
#include "vtkPointInterpolator.h"
#include "vtkTriangleFilter.h"
#include "vtkVoronoiKernel.h"

#include "vtkNew.h"

namespace
{
vtkAlgorithm* NewOBJReader(const char* fileName)
{
  vtkOBJReader* reader = vtkOBJReader::New();
  reader->SetFileName(fileName);
  return reader;
}

vtkAlgorithm* NewPNGReader(const char* fileName)
{
  vtkPNGReader* reader = vtkPNGReader::New();
  reader->SetFileName(fileName);
  return reader;
}

vtkAlgorithm* NewNearestPointResampler()
{
  vtkPointInterpolator* interpolator = vtkPointInterpolator::New();
  vtkNew<vtkVoronoiKernel> nearest;
  interpolator->SetKernel(nearest);
  return interpolator;
}

vtkAlgorithm* NewTriangulator()
{
  vtkTriangleFilter* triangles = vtkTriangleFilter::New();
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  return triangles;
}

const vtkMSOnDemandTable Table = { &NewOBJReader, &NewPNGReader, &NewNearestPointResampler,
  &NewTriangulator };
} // namespace

extern "C" __attribute__((visibility("default"))) const vtkMSOnDemandTable* msynth_vtk_on_demand()
{
  return &Table;
}
