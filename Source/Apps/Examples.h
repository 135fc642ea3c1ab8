// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Examples.h
 * @brief The example readers and analyses the commands share: a label grid and its transition
 * tables (D§3.3.2), a polyhedral example and its neighbourhood labels (D§4.3).
 */
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkMSLabelGridReader;
class vtkPolyData;
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

/// The polygon data of @p path when it is a model msynth wrote (a .vtp whose field data names its
/// example, ExampleFile), else null. @throw std::runtime_error when the .vtp cannot be read.
vtkSmartPointer<vtkPolyData> WrittenModel(const std::string& path);
/// The example, tileset or image sample a label grid msynth wrote (labels.vti) was made from (its
/// field data ExampleFile, TilesetFile or SampleFile, with Seed; read without the grid's
/// arrays), or "" for any other file.
std::string WrittenFrom(const std::string& path);
/// The example a model msynth wrote names: WrittenModel's for a .vtp, else WrittenFrom's.
std::string WrittenExample(const std::string& path);

/**
 * @throw UsageError when the files of `msynth @p usage` ("check EXAMPLE MODEL") are given the
 * other way round: @p model is an example only (a tileset, an .obj), or one of @p examples is a
 * file msynth wrote (a model whose field data names its example, a picture it wrote, a
 * streamed model's pieces) while @p model is not. The one line names both files, the order and
 * the command with them swapped. Files that are missing or cannot be read pass: the command's
 * own checks say why.
 */
void CheckOrder(
  const std::string& usage, const std::vector<std::string>& examples, const std::string& model);

} // namespace cli
} // namespace msynth
