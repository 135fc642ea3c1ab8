// SPDX-License-Identifier: BSD-3-Clause
// The filter's tables are checked against Eq. 3.2 recomputed here by brute force from the image
// (no engine code): for every site and axis, the pair (label, label at +axis).
#include "vtkMSLabelGridReader.h"
#include "vtkMSTransitionTables.h"

#include "msynthTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkTable.h"
#include "vtkVariant.h"

#include <map>
#include <tuple>

int TestMSTransitionTables(int, char*[])
{
  vtkNew<vtkMSLabelGridReader> reader;
  reader->SetFileName(msynth_test::DataFile("Examples/Village.vti").c_str());
  vtkNew<vtkMSTransitionTables> tables;
  tables->SetInputConnection(reader->GetOutputPort());
  tables->Update();
  vtkTable* transitions = tables->GetOutput(0);
  vtkTable* labels = tables->GetOutput(1);

  // Brute force from the image.
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* label = image->GetPointData()->GetArray("Label");
  std::map<std::tuple<int, int, int>, vtkIdType> pairs; // (axis, from, to) -> count
  std::map<int, vtkIdType> counts;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        const int p[3] = { x, y, z };
        const int b = static_cast<int>(label->GetTuple1(x + dims[0] * (y + dims[1] * z)));
        ++counts[b];
        for (int a = 0; a < 3; ++a)
        {
          int q[3] = { x, y, z };
          q[a] += 1;
          if (q[a] < dims[a])
          {
            const int c =
              static_cast<int>(label->GetTuple1(q[0] + dims[0] * (q[1] + dims[1] * q[2])));
            ++pairs[{ a, b, c }];
          }
        }
        (void)p;
      }

  MS_CHECK(transitions->GetNumberOfRows() == static_cast<vtkIdType>(pairs.size()));
  vtkIdType row = 0;
  for (const auto& kv : pairs) // std::map order = (axis, from, to), the table's documented order
  {
    MS_CHECK(transitions->GetValueByName(row, "Axis").ToInt() == std::get<0>(kv.first));
    MS_CHECK(transitions->GetValueByName(row, "From").ToInt() == std::get<1>(kv.first));
    MS_CHECK(transitions->GetValueByName(row, "To").ToInt() == std::get<2>(kv.first));
    MS_CHECK(transitions->GetValueByName(row, "Count").ToLongLong() == kv.second);
    const char* dir[3] = { "+x", "+y", "+z" };
    MS_CHECK(
      transitions->GetValueByName(row, "Direction").ToString() == dir[std::get<0>(kv.first)]);
    ++row;
  }
  // The village's ground is under walls, never above them.
  MS_CHECK(pairs.count({ 2, 1, 2 }) == 1 && pairs.count({ 2, 2, 1 }) == 0);

  MS_CHECK(labels->GetNumberOfRows() == static_cast<vtkIdType>(counts.size()));
  row = 0;
  for (const auto& kv : counts)
  {
    MS_CHECK(labels->GetValueByName(row, "Label").ToInt() == kv.first);
    MS_CHECK(labels->GetValueByName(row, "Index").ToInt() == row);
    MS_CHECK(labels->GetValueByName(row, "Count").ToLongLong() == kv.second);
    MS_CHECK(labels->GetValueByName(row, "Frequency").ToDouble() ==
      static_cast<double>(kv.second) / (dims[0] * dims[1] * dims[2]));
    ++row;
  }

  // Field data: the pairs per axis and the label values.
  auto* tz = vtkIntArray::SafeDownCast(transitions->GetFieldData()->GetArray("TransitionsZ"));
  MS_CHECK(tz && tz->GetNumberOfComponents() == 2);
  vtkIdType nz = 0;
  for (const auto& kv : pairs)
  {
    nz += std::get<0>(kv.first) == 2;
  }
  MS_CHECK(tz->GetNumberOfTuples() == nz);
  MS_CHECK(labels->GetFieldData()->GetArray("Labels")->GetNumberOfTuples() ==
    static_cast<vtkIdType>(counts.size()));
  MS_CHECK(transitions->GetFieldData()->GetAbstractArray("ExampleFile") != nullptr);

  // A float array is refused with a clear error.
  vtkNew<vtkImageData> bad;
  bad->SetDimensions(2, 2, 1);
  bad->AllocateScalars(VTK_FLOAT, 1);
  bad->GetPointData()->GetScalars()->SetName("Label");
  vtkNew<vtkMSTransitionTables> refuse;
  vtkNew<msynth_test::ErrorObserver> errors;
  errors->Observe(refuse);
  refuse->SetInputData(bad);
  refuse->Update();
  MS_CHECK(errors->HasError("labels must be integers"));
  MS_CHECK(refuse->GetOutput(0)->GetNumberOfRows() == 0);
  return EXIT_SUCCESS;
}
