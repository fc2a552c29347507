// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_svg.h"
#include "comap_common.h"
#include "comap_mesh_io.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace comap {

const char* series_color(int i)
{
  static const char* colors[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000"};
  return colors[i % 7];
}

namespace {

std::string escape(const std::string& s)
{
  std::string out;
  for(char c : s)
  {
    if(c == '&') out += "&amp;";
    else if(c == '<') out += "&lt;";
    else if(c == '>') out += "&gt;";
    else if(c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

/// About `count` round tick values covering [lo, hi].
std::vector<double> ticks(double lo, double hi, int count)
{
  std::vector<double> out;
  const double range = hi - lo;
  if(!(range > 0)) return {lo};
  const double raw = range / count, magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for(double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if(m * magnitude >= raw)
    {
      step = m * magnitude;
      break;
    }
  for(double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * range; t += step)
    out.push_back(std::abs(t) < 1e-12 * range ? 0.0 : t);
  return out;
}

std::string tick_label(double t)
{
  std::string s = shortest(std::round(t * 1e6) / 1e6);
  return s;
}

} // namespace

void write_svg(const std::string& file, const Plot& plot)
{
  const double width = 720, height = 480, left = 70, right = 20, top = 40, bottom = 55;
  const double pw = width - left - right, ph = height - top - bottom;
  const double xr = plot.x_max - plot.x_min, yr = plot.y_max - plot.y_min;
  auto X = [&](double x) { return left + (x - plot.x_min) / (xr > 0 ? xr : 1) * pw; };
  auto Y = [&](double y) { return top + ph - (y - plot.y_min) / (yr > 0 ? yr : 1) * ph; };
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"Helvetica, Arial, sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << width / 2 << "\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">" << escape(plot.title)
      << "</text>\n";
  // Grid and ticks.
  svg << "<g stroke=\"#e0e0e0\" stroke-width=\"1\">\n";
  const std::vector<double> xt = ticks(plot.x_min, plot.x_max, 8), yt = ticks(plot.y_min, plot.y_max, 8);
  for(double t : xt) svg << "<line x1=\"" << X(t) << "\" y1=\"" << top << "\" x2=\"" << X(t) << "\" y2=\"" << top + ph << "\"/>\n";
  for(double t : yt) svg << "<line x1=\"" << left << "\" y1=\"" << Y(t) << "\" x2=\"" << left + pw << "\" y2=\"" << Y(t) << "\"/>\n";
  svg << "</g>\n<g font-size=\"12\" fill=\"#333\">\n";
  for(double t : xt)
    svg << "<text x=\"" << X(t) << "\" y=\"" << top + ph + 18 << "\" text-anchor=\"middle\">" << tick_label(t) << "</text>\n";
  for(double t : yt)
    svg << "<text x=\"" << left - 8 << "\" y=\"" << Y(t) + 4 << "\" text-anchor=\"end\">" << tick_label(t) << "</text>\n";
  svg << "</g>\n"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#333\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"" << height - 12 << "\" text-anchor=\"middle\" font-size=\"14\">"
      << escape(plot.x_label) << "</text>\n"
      << "<text transform=\"translate(18," << top + ph / 2 << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"14\">"
      << escape(plot.y_label) << "</text>\n";
  // Series, clipped to the plot area.
  svg << "<defs><clipPath id=\"area\"><rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw
      << "\" height=\"" << ph << "\"/></clipPath></defs>\n<g clip-path=\"url(#area)\">\n";
  for(const Plot_series& s : plot.series)
  {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    if(s.markers)
    {
      svg << "<g fill=\"" << s.color << "\">\n";
      for(std::size_t i = 0; i < n; ++i)
        if(std::isfinite(s.y[i]))
          svg << "<circle cx=\"" << fixed(X(s.x[i]), 1) << "\" cy=\"" << fixed(Y(s.y[i]), 1) << "\" r=\"2.2\"/>\n";
      svg << "</g>\n";
      continue;
    }
    svg << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"2\""
        << (s.dashed ? " stroke-dasharray=\"7,4\"" : "") << " points=\"";
    for(std::size_t i = 0; i < n; ++i)
      if(std::isfinite(s.y[i])) svg << fixed(X(s.x[i]), 1) << "," << fixed(Y(s.y[i]), 1) << " ";
    svg << "\"/>\n";
  }
  svg << "</g>\n";
  // Legend.
  const double lw = 20 + 8 * [&] {
    std::size_t m = 0;
    for(const Plot_series& s : plot.series) m = std::max(m, s.label.size());
    return static_cast<double>(m);
  }() + 40;
  const double lh = 20.0 * plot.series.size() + 10;
  const double lx = plot.legend_bottom_right ? left + pw - lw - 10 : left + 10;
  const double ly = plot.legend_bottom_right ? top + ph - lh - 10 : top + 10;
  svg << "<rect x=\"" << lx << "\" y=\"" << ly << "\" width=\"" << lw << "\" height=\"" << lh
      << "\" fill=\"white\" fill-opacity=\"0.9\" stroke=\"#999\"/>\n";
  for(std::size_t i = 0; i < plot.series.size(); ++i)
  {
    const Plot_series& s = plot.series[i];
    const double y = ly + 18 + 20.0 * i;
    if(s.markers)
      svg << "<circle cx=\"" << lx + 22 << "\" cy=\"" << y - 4 << "\" r=\"3\" fill=\"" << s.color << "\"/>\n";
    else
      svg << "<line x1=\"" << lx + 8 << "\" y1=\"" << y - 4 << "\" x2=\"" << lx + 36 << "\" y2=\"" << y - 4
          << "\" stroke=\"" << s.color << "\" stroke-width=\"2\"" << (s.dashed ? " stroke-dasharray=\"7,4\"" : "")
          << "/>\n";
    svg << "<text x=\"" << lx + 44 << "\" y=\"" << y << "\" font-size=\"12\">" << escape(s.label) << "</text>\n";
  }
  svg << "</svg>\n";
  CGAL::Surface_mesh_correspondence::Atomic_output_file out(file);
  out.stream() << svg.str();
  commit_outputs({&out});
}

} // namespace comap
