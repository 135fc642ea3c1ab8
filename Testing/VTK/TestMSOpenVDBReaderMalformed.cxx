// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOpenVDBReader.h"
#include "vtkMSOpenVDBWriter.h"

#include "msynthTestUtilities.h"

#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <fstream>
#include <iterator>

namespace
{
int ExpectError(const std::string& path, const std::string& problem, vtkIdType maxVoxels = 0)
{
  vtkNew<vtkMSOpenVDBReader> reader;
  if (maxVoxels > 0)
  {
    reader->SetMaximumNumberOfVoxels(maxVoxels);
  }
  vtkNew<msynth_test::ErrorObserver> errors;
  errors->Observe(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!errors->HasError("'" + path + "'") || !errors->HasError(problem))
  {
    std::cerr << path << ": expected an error naming the file and '" << problem << "', got:\n"
              << errors->Errors << "\n";
    return EXIT_FAILURE;
  }
  MS_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  return EXIT_SUCCESS;
}
} // namespace

int TestMSOpenVDBReaderMalformed(int, char*[])
{
  int rc = EXIT_SUCCESS;
  rc |= ExpectError(msynth_test::TempFile("absent.vdb"), "no such file");
  rc |= ExpectError(msynth_test::DataFile("Examples/Village.vti"), "not a readable OpenVDB file");

  // A good file, then cut short.
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 8);
  image->AllocateScalars(VTK_INT, 1);
  auto* a = vtkIntArray::SafeDownCast(image->GetPointData()->GetScalars());
  a->SetName("Label");
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    a->SetValue(i, static_cast<int>(i % 5));
  }
  const std::string good = msynth_test::TempFile("reader-good.vdb");
  vtkNew<vtkMSOpenVDBWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(good.c_str());
  MS_CHECK(writer->Write() == 1);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = msynth_test::TempFile("reader-truncated.vdb");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  rc |= ExpectError(cut, "truncated");

  // A dense output over the limit is refused before allocating.
  rc |= ExpectError(good, "more than the limit of 100 voxels", 100);
  return rc;
}
