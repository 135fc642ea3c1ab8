// SPDX-License-Identifier: BSD-3-Clause
// Every malformed example gives one clear error naming the file and the problem, and no output.
#include "vtkMSLabelGridReader.h"

#include "msynthTestUtilities.h"

#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

namespace
{
int ExpectError(const std::string& relative, const std::string& problem, vtkIdType maxSites = 0)
{
  const std::string path = msynth_test::DataFile(relative);
  vtkNew<vtkMSLabelGridReader> reader;
  if (maxSites > 0)
  {
    reader->SetMaximumNumberOfSites(maxSites);
  }
  vtkNew<msynth_test::ErrorObserver> errors;
  errors->Observe(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!errors->HasError("'" + path + "'") || !errors->HasError(problem))
  {
    std::cerr << relative << ": expected an error naming the file and '" << problem << "', got:\n"
              << errors->Errors << "\n";
    return EXIT_FAILURE;
  }
  MS_CHECK(reader->GetErrorCode() != vtkErrorCode::NoError);
  MS_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  return EXIT_SUCCESS;
}

/// An <Objects> trailer of another shape is no error: the model loads, the trailer is kept
/// verbatim, no pieces are named, and a warning says where the section departs from the shape.
int ExpectKeptTrailer(const std::string& relative, const std::string& warning)
{
  const std::string path = msynth_test::DataFile(relative);
  vtkNew<vtkMSLabelGridReader> reader;
  vtkNew<msynth_test::ErrorObserver> errors;
  errors->Observe(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  MS_CHECK(errors->Errors.empty());
  MS_CHECK(errors->Warnings.find("'" + path + "'") != std::string::npos);
  MS_CHECK(errors->Warnings.find(warning) != std::string::npos);
  vtkImageData* image = reader->GetOutput();
  MS_CHECK(image->GetNumberOfPoints() == 1);
  MS_CHECK(image->GetFieldData()->GetAbstractArray("PieceNames") == nullptr);
  auto* trailer =
    vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("TextModelTrailer"));
  MS_CHECK(trailer && trailer->GetValue(0) == "<Objects>\nscene\n4\nwall\n#\n");
  return EXIT_SUCCESS;
}
} // namespace

int TestMSLabelGridReaderMalformed(int, char*[])
{
  int rc = EXIT_SUCCESS;
  rc |= ExpectError("Malformed/does-not-exist.vti", "no such file");
  rc |= ExpectError("Malformed/not-xml.vti", "not a readable VTK image data");
  rc |= ExpectError("Malformed/truncated.vti", "not a readable VTK image data");
  rc |= ExpectError(
    "Malformed/no-label-array.vti", "has no label array 'Label' (arrays present: Density)");
  rc |= ExpectError("Malformed/float-labels.vti", "labels must be integers");
  rc |= ExpectError("Malformed/two-component-labels.vti", "2 components");
  rc |=
    ExpectError("Malformed/huge-extent.vti", "too large to read (over 2^20 points along an axis");
  rc |= ExpectError("Malformed/too-few-values.vti", "could not be read");
  rc |= ExpectError("Examples/Village.vti", "more than the maximum of 100 sites", 100);
  // The original program's text format: errors name the file and the line.
  // Values are a stream, as the original program reads them: a short row shifts them, so the
  // trailer's first word is read as the last value.
  rc |= ExpectError("Malformed/text-short-row.txt", "line 7: '<Objects>' is not an integer");
  rc |= ExpectError("Malformed/text-bad-dimensions.txt", "line 4: 'three' is not an integer");
  rc |= ExpectError("Malformed/text-huge.txt", "exceed the limit of 134217728 sites");
  rc |= ExpectError("Malformed/text-missing-slice.txt", "the file ends in slice 1");
  rc |= ExpectKeptTrailer("Malformed/text-bad-objects.txt", "starting with '$'");
  rc |= ExpectError("Examples/Village.txt", "exceed the limit of 100 sites", 100);
  // MagicaVoxel: every length and count is checked against the file.
  rc |= ExpectError("Malformed/vox-bad-magic.vox", "does not start with 'VOX '");
  rc |= ExpectError("Malformed/vox-truncated.vox", "more children than the file holds");
  rc |= ExpectError("Malformed/vox-no-model.vox", "no model");
  rc |= ExpectError("Malformed/vox-voxel-outside.vox", "voxel (5, 0, 0) lies outside");
  rc |= ExpectError("Malformed/vox-count-too-large.vox", "declares 1000000 voxels but holds 1");
  rc |= ExpectError("Malformed/vox-huge-size.vox", "outside 1..2048");
  rc |= ExpectError("Examples/Village.vox", "voxels, more than the 100 this reading may hold", 100);
  return rc;
}
