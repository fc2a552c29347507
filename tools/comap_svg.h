// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: line plots written as standalone SVG files (axes, ticks, grid, legend), for the
// cumulative error curves and per-pair error plots of the benchmark and the demo.

#ifndef SMC_TOOLS_COMAP_SVG_H
#define SMC_TOOLS_COMAP_SVG_H

#include <string>
#include <vector>

namespace comap {

struct Plot_series
{
  std::string label;
  std::vector<double> x, y;
  std::string color = "#1f77b4";
  bool dashed = false;
  bool markers = false;   ///< small dots at the points instead of a line
};

struct Plot
{
  std::string title, x_label, y_label;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  std::vector<Plot_series> series;
  bool legend_bottom_right = true;  ///< else top left
};

/// Writes `plot` as an SVG file. \throws IO_error when the file cannot be written.
void write_svg(const std::string& file, const Plot& plot);

/// The colours used for the series, in order (a colour-blind-friendly palette).
const char* series_color(int i);

} // namespace comap

#endif // SMC_TOOLS_COMAP_SVG_H
