// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSRenderLabels
 * @brief What the render grids of a label image are made of (msynth::vdb::LabelRenderView):
 * the colour and the name of each label, from the image's field data.
 *
 * Colours: the palette of a `.vox` example (field data `PaletteRGBA`, label = palette index),
 * else the label's colour in every picture of the project (msynth::LabelColor, as mesh.vtp,
 * mesh.glb and picture.png show it), turned from sRGB to linear. Names: a voxel tileset's
 * tiles (`LabelTile`), else a tileset's labels (`TileNames`, a tile's orientations together
 * under the tile's name), else the text format's pieces (`PieceLabels`, `PieceNames`).
 * Internal to vtkMSOpenVDBWriter (not wrapped, not installed).
 */
#ifndef vtkMSRenderLabels_h
#define vtkMSRenderLabels_h

#include "VDB/RenderGrids.h"

class vtkFieldData;

class vtkMSRenderLabels
{
public:
  /// Fills the Colors of @p view for every label of its Labels and, when @p named, its Names
  /// from @p fields (keys: the values of NameKeys, or of Labels without).
  static void Describe(vtkFieldData* fields, bool named, msynth::vdb::LabelRenderView& view);
};

#endif
