// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Examples.h
 * @brief The example readers and analyses the commands share: a label grid and its transition
 * tables (D§3.3.2), a polyhedral example and its neighbourhood labels (D§4.3).
 */
#include "vtkSmartPointer.h"

#include <string>

class vtkMSLabelGridReader;
class vtkMSNeighbourhoodLabels;
class vtkMSPolyhedralExampleReader;
class vtkMSTransitionTables;

namespace msynth
{
namespace cli
{

struct ExampleTables
{
  vtkSmartPointer<vtkMSLabelGridReader> Reader;
  vtkSmartPointer<vtkMSTransitionTables> Tables;
};

/// Reads the label grid @p example and computes its tables (errors as exceptions).
ExampleTables AnalyzeLabelGrid(const std::string& example);

/// How a polyhedral example is read: its object types and its up axis.
struct PolyhedralReading
{
  std::string Types;    ///< NAME=TYPE,... (vtkMSPolyhedralExampleReader::ObjectTypes)
  std::string Up = "z"; ///< "z", or "y" for a file modelled with y up
};

/// Sets @p reader to read the polyhedral example @p path as @p reading says.
void ConfigureReader(
  vtkMSPolyhedralExampleReader* reader, const std::string& path, const PolyhedralReading& reading);

/// Reads a polyhedral example and computes its neighbourhood labels (errors as exceptions).
vtkSmartPointer<vtkMSNeighbourhoodLabels> PolyhedralLabels(
  const std::string& path, const PolyhedralReading& reading);

} // namespace cli
} // namespace msynth
