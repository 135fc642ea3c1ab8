// SPDX-License-Identifier: BSD-3-Clause
#include "Examples.h"

#include "Common.h"

#include "vtkMSLabelGridReader.h"
#include "vtkMSNeighbourhoodLabels.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkMSTransitionTables.h"

namespace msynth
{
namespace cli
{

ExampleTables AnalyzeLabelGrid(const std::string& example)
{
  ExampleTables a;
  a.Reader = vtkSmartPointer<vtkMSLabelGridReader>::New();
  a.Reader->SetFileName(example.c_str());
  a.Reader->GenerateGeometryOff(); // the command line needs the labels only
  // The grid, its copies and the analysis take about 20 bytes a site (measured on an empty
  // 512 x 512 x 256 .vox: 1.4 GB): refused before reading when the memory cannot hold it.
  a.Reader->SetMaximumNumberOfSites(
    static_cast<vtkIdType>(SitesWithinMemory(24, a.Reader->GetMaximumNumberOfSites())));
  Run(a.Reader);
  a.Tables = vtkSmartPointer<vtkMSTransitionTables>::New();
  a.Tables->SetInputConnection(a.Reader->GetOutputPort());
  Run(a.Tables);
  return a;
}

void ConfigureReader(
  vtkMSPolyhedralExampleReader* reader, const std::string& path, const PolyhedralReading& reading)
{
  reader->SetFileName(path.c_str());
  reader->SetObjectTypes(reading.Types.c_str());
  reader->SetUpAxis(reading.Up == "y" ? 1 : 2);
}

vtkSmartPointer<vtkMSNeighbourhoodLabels> PolyhedralLabels(
  const std::string& path, const PolyhedralReading& reading)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  ConfigureReader(reader, path, reading);
  Run(reader); // so that the reader's own error (naming the file) is the one reported
  auto labels = vtkSmartPointer<vtkMSNeighbourhoodLabels>::New();
  labels->SetInputConnection(reader->GetOutputPort());
  Run(labels);
  return labels;
}

} // namespace cli
} // namespace msynth
