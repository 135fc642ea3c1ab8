// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGridReader.h"

#include "msynthTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataReader.h"

int TestMSLabelGridReader(int, char*[])
{
  // Point labels: the same values as VTK's own reader sees, as a vtkIntArray named Label.
  const std::string village = msynth_test::DataFile("Examples/Village.vti");
  vtkNew<vtkMSLabelGridReader> reader;
  reader->SetFileName(village.c_str());
  reader->Update();
  vtkImageData* out = reader->GetOutput();
  int dims[3];
  out->GetDimensions(dims);
  MS_CHECK(dims[0] == 7 && dims[1] == 7 && dims[2] == 5);
  auto* labels = vtkIntArray::SafeDownCast(out->GetPointData()->GetArray("Label"));
  MS_CHECK(labels != nullptr);
  MS_CHECK(out->GetPointData()->GetScalars() == labels);
  vtkNew<vtkXMLImageDataReader> plain;
  plain->SetFileName(village.c_str());
  plain->Update();
  vtkDataArray* expected = plain->GetOutput()->GetPointData()->GetArray("Label");
  MS_CHECK(expected->GetNumberOfTuples() == labels->GetNumberOfTuples());
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    MS_CHECK(labels->GetValue(i) == static_cast<int>(expected->GetTuple1(i)));
  }
  auto* source = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("ExampleFile"));
  MS_CHECK(source && source->GetValue(0) == village);
  MS_CHECK(vtkMSLabelGridReader::CanReadFile(village.c_str()) == 1);
  MS_CHECK(vtkMSLabelGridReader::CanReadFile("x.obj") == 0);

  // Cell labels: one site per cell, at the cell centers; 4x4x2 points hold 3x3x1 cells.
  vtkNew<vtkMSLabelGridReader> cells;
  cells->SetFileName(msynth_test::DataFile("Examples/CheckerboardCells.vti").c_str());
  cells->Update();
  vtkImageData* c = cells->GetOutput();
  c->GetDimensions(dims);
  MS_CHECK(dims[0] == 3 && dims[1] == 3 && dims[2] == 1);
  double origin[3];
  c->GetOrigin(origin);
  MS_CHECK(origin[0] == 0.5 && origin[1] == 0.5 && origin[2] == 0.5);
  auto* cl = vtkIntArray::SafeDownCast(c->GetPointData()->GetArray("Label"));
  MS_CHECK(cl && cl->GetNumberOfTuples() == 9);
  for (int y = 0; y < 3; ++y)
  {
    for (int x = 0; x < 3; ++x)
    {
      MS_CHECK(cl->GetValue(x + 3 * y) == (x + y) % 2);
    }
  }
  return EXIT_SUCCESS;
}
