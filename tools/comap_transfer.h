// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: colour functions on a target mesh and their transfer to the source through a map, for
// looking at maps in MeshLab or Blender.
//
// Without a texture, the target's colour is a smooth function of its position in its bounding
// box B (with extent e = the largest side of B, and the longest axis a):
//   rgb(p) = (0.1 + 0.8 (p - min B) / size B) * (0.8 + 0.2 sin(2 pi * 6 (p_a - min B_a) / e)),
// i.e. normalised xyz with six soft bands along the longest axis: a right map gives the source
// the same smooth colours, a wrong one shows as colour jumps or misplaced bands.
// With a texture (PNG), the image is wrapped around the target by a cylindrical projection about
// the longest axis a of the bounding box, through its centre c: for the two other axes (b1, b2),
//   u = (atan2(p_b2 - c_b2, p_b1 - c_b1) + pi) / (2 pi),   v = (p_a - min B_a) / size B_a,
// with u wrapping around and v = 0 at the bottom row of the image; bilinear interpolation.

#ifndef SMC_TOOLS_COMAP_TRANSFER_H
#define SMC_TOOLS_COMAP_TRANSFER_H

#include "comap_mesh_io.h"

#include <string>
#include <vector>

namespace comap {

/// The smooth coordinate colours of every vertex (see above).
std::vector<Color> coordinate_colors(const CGAL::Surface_mesh_correspondence::Triangle_soup& mesh);

/// An RGB image, rows from top to bottom.
struct Texture
{
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  ///< 3 bytes per pixel
  /// Bilinear sample at (u, v) in [0, 1]^2 (u wraps around; v = 0 is the bottom row).
  Color sample(double u, double v) const;
};

/// True when comap was built with libpng.
bool has_png_support();

/// Reads a PNG image. \throws IO_error naming the file (or telling that PNG support is missing).
Texture read_png(const std::string& file);

/// The colours of the texture wrapped around the mesh by the cylindrical projection (see above).
std::vector<Color> texture_colors(const CGAL::Surface_mesh_correspondence::Triangle_soup& mesh, const Texture& texture);

/// The colours of the source pulled through `map_12`: source vertex i gets the colour of target
/// vertex map_12[i].
std::vector<Color> pull_colors(const std::vector<Color>& target_colors, const Vertex_map& map_12);

/// "dir/name.ply" -> "dir/name_target.ply".
std::string target_file_name(const std::string& ply_file);

} // namespace comap

#endif // SMC_TOOLS_COMAP_TRANSFER_H
