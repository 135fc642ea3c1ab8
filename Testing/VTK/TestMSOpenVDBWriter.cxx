// SPDX-License-Identifier: BSD-3-Clause
// Writer → reader round trips are exact (labels, fields, extents, transform, metadata); failed
// writes report an error and leave no file.
#include "vtkMSLabelGridReader.h"
#include "vtkMSOpenVDBReader.h"
#include "vtkMSOpenVDBWriter.h"

#include "msynthTestUtilities.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <cstdio>
#include <dirent.h>
#include <sys/stat.h>

namespace
{
bool Exists(const std::string& path)
{
  struct stat s;
  return ::stat(path.c_str(), &s) == 0;
}

/// Temporary files left by writes of @p stem (other tests may be writing in parallel).
int CountTemporaries(const std::string& dir, const std::string& stem)
{
  int n = 0;
  DIR* d = opendir(dir.c_str());
  while (dirent* e = readdir(d))
  {
    n += std::string(e->d_name).rfind(stem + ".tmp-", 0) == 0;
  }
  closedir(d);
  return n;
}
} // namespace

int TestMSOpenVDBWriter(int, char*[])
{
  // An image with a shifted extent, anisotropic spacing, labels, a field, a vector and cell data.
  vtkNew<vtkImageData> image;
  image->SetExtent(-1, 3, 2, 4, 0, 1);
  image->SetOrigin(10.0, -5.0, 0.5);
  image->SetSpacing(0.5, 2.0, 1.0);
  const vtkIdType n = image->GetNumberOfPoints();
  vtkNew<vtkIntArray> labels;
  labels->SetName("Label");
  vtkNew<vtkDoubleArray> entropy;
  entropy->SetName("Entropy");
  vtkNew<vtkFloatArray> vec;
  vec->SetName("Direction");
  vec->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < n; ++i)
  {
    labels->InsertNextValue(i % 4 == 0 ? 0 : static_cast<int>(i * 3 - 7));
    entropy->InsertNextValue(0.25 * static_cast<double>(i));
    vec->InsertNextTuple3(static_cast<double>(i), -1.0, 2.0);
  }
  image->GetPointData()->AddArray(labels);
  image->GetPointData()->AddArray(entropy);
  image->GetPointData()->AddArray(vec);
  vtkNew<vtkIntArray> blockIds;
  blockIds->SetName("Label"); // same name as a point array: written as Label_cell
  for (vtkIdType i = 0; i < image->GetNumberOfCells(); ++i)
  {
    blockIds->InsertNextValue(static_cast<int>(i) + 1);
  }
  image->GetCellData()->AddArray(blockIds);
  vtkNew<vtkStringArray> file;
  file->SetName("ExampleFile");
  file->InsertNextValue("made-in-test");
  image->GetFieldData()->AddArray(file);

  const std::string path = msynth_test::TempFile("writer.vdb");
  std::remove(path.c_str());
  vtkNew<vtkMSOpenVDBWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->WriteFloatLabelsOn();
  writer->AddMetadata("seed", "7");
  MS_CHECK(writer->Write() == 1);
  MS_CHECK(Exists(path));

  vtkNew<vtkMSOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* back = reader->GetOutput();
  int extent[6];
  back->GetExtent(extent);
  MS_CHECK(extent[0] == -1 && extent[1] == 3 && extent[2] == 2 && extent[3] == 4 &&
    extent[4] == 0 && extent[5] == 1);
  double origin[3], spacing[3];
  back->GetOrigin(origin);
  back->GetSpacing(spacing);
  MS_CHECK(origin[0] == 10.0 && origin[1] == -5.0 && origin[2] == 0.5);
  MS_CHECK(spacing[0] == 0.5 && spacing[1] == 2.0 && spacing[2] == 1.0);
  auto* l = vtkIntArray::SafeDownCast(back->GetPointData()->GetArray("Label"));
  auto* lf = vtkFloatArray::SafeDownCast(back->GetPointData()->GetArray("Label_float"));
  auto* e = vtkFloatArray::SafeDownCast(back->GetPointData()->GetArray("Entropy"));
  auto* v = vtkFloatArray::SafeDownCast(back->GetPointData()->GetArray("Direction"));
  MS_CHECK(l && lf && e && v && v->GetNumberOfComponents() == 3);
  for (vtkIdType i = 0; i < n; ++i)
  {
    MS_CHECK(l->GetValue(i) == labels->GetValue(i));
    MS_CHECK(lf->GetValue(i) == static_cast<float>(labels->GetValue(i)));
    MS_CHECK(e->GetValue(i) == static_cast<float>(entropy->GetValue(i)));
    MS_CHECK(v->GetComponent(i, 0) == static_cast<double>(i) && v->GetComponent(i, 1) == -1.0);
  }
  auto* seed = vtkStringArray::SafeDownCast(back->GetFieldData()->GetAbstractArray("seed"));
  auto* ex = vtkStringArray::SafeDownCast(back->GetFieldData()->GetAbstractArray("ExampleFile"));
  auto* gen = vtkStringArray::SafeDownCast(back->GetFieldData()->GetAbstractArray("generator"));
  MS_CHECK(seed && seed->GetValue(0) == "7");
  MS_CHECK(ex && ex->GetValue(0) == "made-in-test");
  MS_CHECK(gen && gen->GetValue(0).rfind("ModelSynth", 0) == 0);

  // The cell array sits at cell centers: another transform, so it is read on its own.
  vtkNew<vtkMSOpenVDBReader> cellReader;
  cellReader->SetFileName(path.c_str());
  cellReader->SetGridName("Label_cell");
  cellReader->Update();
  vtkImageData* cells = cellReader->GetOutput();
  cells->GetOrigin(origin);
  MS_CHECK(origin[0] == 10.25 && origin[1] == -4.0 && origin[2] == 1.0);
  auto* cl = vtkIntArray::SafeDownCast(cells->GetPointData()->GetArray("Label_cell"));
  MS_CHECK(cl && cl->GetNumberOfTuples() == image->GetNumberOfCells());
  for (vtkIdType i = 0; i < cl->GetNumberOfTuples(); ++i)
  {
    MS_CHECK(cl->GetValue(i) == blockIds->GetValue(i));
  }

  // A 2D image is a one-voxel slab.
  vtkNew<vtkMSLabelGridReader> checker;
  checker->SetFileName(msynth_test::DataFile("Examples/Checkerboard.vti").c_str());
  vtkNew<vtkMSOpenVDBWriter> slab;
  slab->SetInputConnection(checker->GetOutputPort());
  const std::string slabPath = msynth_test::TempFile("slab.vdb");
  slab->SetFileName(slabPath.c_str());
  MS_CHECK(slab->Write() == 1);
  vtkNew<vtkMSOpenVDBReader> slabBack;
  slabBack->SetFileName(slabPath.c_str());
  slabBack->Update();
  int dims[3];
  slabBack->GetOutput()->GetDimensions(dims);
  MS_CHECK(dims[0] == 4 && dims[1] == 4 && dims[2] == 1);

  // Failures: an unwritable folder, and an input with nothing to write. No file, no temporary.
  vtkNew<msynth_test::ErrorObserver> errors;
  const std::string nowhere = msynth_test::TempFile("missing-folder/out.vdb");
  vtkNew<vtkMSOpenVDBWriter> bad;
  errors->Observe(bad);
  bad->SetInputData(image);
  bad->SetFileName(nowhere.c_str());
  MS_CHECK(bad->Write() == 0);
  MS_CHECK(errors->HasError(nowhere));
  MS_CHECK(!Exists(nowhere));

  errors->Clear();
  vtkNew<vtkImageData> emptyArrays;
  emptyArrays->SetDimensions(2, 2, 2);
  const std::string none = msynth_test::TempFile("nothing.vdb");
  std::remove(none.c_str());
  bad->SetInputData(emptyArrays);
  bad->SetFileName(none.c_str());
  MS_CHECK(bad->Write() == 0);
  MS_CHECK(errors->HasError("no array that maps to a VDB grid"));
  MS_CHECK(!Exists(none));
  MS_CHECK(CountTemporaries(msynth_test::Env("MSYNTH_TMP"), "nothing.vdb") == 0);
  MS_CHECK(CountTemporaries(msynth_test::Env("MSYNTH_TMP"), "writer.vdb") == 0);
  return EXIT_SUCCESS;
}
