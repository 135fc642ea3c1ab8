// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The resemblance of a continuous model to its example (field data `Resemblance*` of the mesh
// and check filters, vtkMSCheckKinds::AddResemblance) as the commands print and record it.
#include <iosfwd>
#include <string>

class vtkFieldData;

namespace msynth::cli
{
/// The measures out of bounds (`ResemblanceFailed`), -1 when @p fd has no resemblance.
int ResemblanceFailed(vtkFieldData* fd);
/// The measures as a table on @p out ("resemblance to the example: ..."), nothing without.
void PrintResemblance(vtkFieldData* fd, std::ostream& out);
/// One line: "N of M structure measures within bounds" and the ones out of bounds.
std::string ResemblanceSummary(vtkFieldData* fd);
/// The measures as a JSON array of {"measure", "example", "model", "bounds", "passes"}.
std::string ResemblanceJson(vtkFieldData* fd);
} // namespace msynth::cli
