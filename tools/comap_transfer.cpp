// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_transfer.h"
#include "comap_commands.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#ifdef SMC_WITH_PNG
#include <png.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

struct Box
{
  std::array<double, 3> lo{{0, 0, 0}}, hi{{0, 0, 0}};
  int longest = 0;
  double size(int a) const { return std::max(hi[a] - lo[a], 1e-300); }
};

Box bounding_box(const smc::Triangle_soup& mesh)
{
  Box b;
  bool first = true;
  for(const smc::Triangle_soup::Point& c : mesh.points())
  {
    for(int a = 0; a < 3; ++a)
    {
      b.lo[a] = first ? c[a] : std::min(b.lo[a], c[a]);
      b.hi[a] = first ? c[a] : std::max(b.hi[a], c[a]);
    }
    first = false;
  }
  for(int a = 1; a < 3; ++a)
    if(b.size(a) > b.size(b.longest)) b.longest = a;
  return b;
}

} // namespace

std::vector<Color> coordinate_colors(const smc::Triangle_soup& mesh)
{
  const Box b = bounding_box(mesh);
  const double extent = b.size(b.longest);
  std::vector<Color> colors(mesh.number_of_vertices());
  for(std::size_t v = 0; v < colors.size(); ++v)
  {
    const smc::Triangle_soup::Point& c = mesh.points()[v];
    const double band = 0.8 + 0.2 * std::sin(2 * CGAL_PI * 6 * (c[b.longest] - b.lo[b.longest]) / extent);
    for(int a = 0; a < 3; ++a) colors[v][a] = (0.1 + 0.8 * (c[a] - b.lo[a]) / b.size(a)) * band;
  }
  return colors;
}

Color Texture::sample(double u, double v) const
{
  if(width <= 0 || height <= 0) return {{0.5, 0.5, 0.5}};
  u -= std::floor(u);
  v = std::min(1.0, std::max(0.0, v));
  const double x = u * width - 0.5, y = (1.0 - v) * height - 0.5;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto pixel = [&](int px, int py, int c) {
    px = ((px % width) + width) % width;  // u wraps around
    py = std::min(height - 1, std::max(0, py));
    return rgb[(static_cast<std::size_t>(py) * width + px) * 3 + c] / 255.0;
  };
  Color out;
  for(int c = 0; c < 3; ++c)
    out[c] = (1 - fy) * ((1 - fx) * pixel(x0, y0, c) + fx * pixel(x0 + 1, y0, c)) +
             fy * ((1 - fx) * pixel(x0, y0 + 1, c) + fx * pixel(x0 + 1, y0 + 1, c));
  return out;
}

bool has_png_support()
{
#ifdef SMC_WITH_PNG
  return true;
#else
  return false;
#endif
}

Texture read_png(const std::string& file)
{
#ifdef SMC_WITH_PNG
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  if(!png_image_begin_read_from_file(&image, file.c_str()))
    throw smc::IO_error("cannot read the PNG image " + file + ": " + image.message);
  image.format = PNG_FORMAT_RGB;
  Texture t;
  t.width = static_cast<int>(image.width);
  t.height = static_cast<int>(image.height);
  t.rgb.resize(PNG_IMAGE_SIZE(image));
  if(!png_image_finish_read(&image, nullptr, t.rgb.data(), 0, nullptr))
  {
    const std::string message = image.message;
    png_image_free(&image);
    throw smc::IO_error("cannot read the PNG image " + file + ": " + message);
  }
  if(t.width == 0 || t.height == 0) throw smc::IO_error("the PNG image " + file + " is empty");
  return t;
#else
  throw smc::IO_error("cannot read " + file + ": this comap was built without PNG support (install libpng-dev and "
                      "reconfigure)");
#endif
}

std::vector<Color> texture_colors(const smc::Triangle_soup& mesh, const Texture& texture)
{
  const Box b = bounding_box(mesh);
  const int a = b.longest, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
  const double c1 = 0.5 * (b.lo[b1] + b.hi[b1]), c2 = 0.5 * (b.lo[b2] + b.hi[b2]);
  std::vector<Color> colors(mesh.number_of_vertices());
  for(std::size_t v = 0; v < colors.size(); ++v)
  {
    const smc::Triangle_soup::Point& c = mesh.points()[v];
    const double u = (std::atan2(c[b2] - c2, c[b1] - c1) + CGAL_PI) / (2 * CGAL_PI);
    const double t = (c[a] - b.lo[a]) / b.size(a);
    colors[v] = texture.sample(u, t);
  }
  return colors;
}

std::vector<Color> pull_colors(const std::vector<Color>& target_colors, const Vertex_map& map_12)
{
  std::vector<Color> out(map_12.size());
  for(std::size_t i = 0; i < map_12.size(); ++i) out[i] = target_colors[map_12[i]];
  return out;
}

std::string target_file_name(const std::string& ply_file)
{
  const std::size_t slash = ply_file.find_last_of('/'), dot = ply_file.find_last_of('.');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return ply_file + "_target.ply";
  return ply_file.substr(0, dot) + "_target" + ply_file.substr(dot);
}

int run_transfer(int argc, char** argv)
{
  Common_options common;
  std::string source, target, map_file, out, texture_file;
  int index_base = 1;
  Option_parser p("transfer", "comap transfer --source S --target T --map-12 FILE --out FILE.ply [options]",
                  "Colours the target with a smooth function of its coordinates (or a texture) and pulls the colours "
                  "to the source through the map S -> T. Writes the source as FILE.ply and the target as "
                  "FILE_target.ply, both with vertex colours (MeshLab, Blender, ParaView).");
  p.section("Files");
  p.value("--source", "MESH", "the source mesh S", "", [&](const std::string& v) { source = v; });
  p.value("--target", "MESH", "the target mesh T", "", [&](const std::string& v) { target = v; });
  p.value("--map-12", "FILE", "the map S -> T", "", [&](const std::string& v) { map_file = v; });
  p.value("--out", "FILE.ply", "output: the coloured source (the target goes to FILE_target.ply)", "",
          [&](const std::string& v) { out = v; });
  p.value("--texture", "IMAGE.png",
          "wrap this image around the target (cylindrical projection about its bounding box's longest axis) "
          "instead of the coordinate colours",
          "", [&](const std::string& v) { texture_file = v; });
  p.value("--index-base", "0|1", "index of the first vertex in the map file (0 or 1)", "1",
          [&](const std::string& v) { index_base = parse_int("--index-base", v, 0, 1); });
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> extra = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(!extra.empty()) throw Usage_error("unexpected argument " + extra.front());
  if(source.empty() || target.empty() || map_file.empty() || out.empty())
    throw Usage_error("transfer needs --source, --target, --map-12 and --out");
  const std::string out_target = target_file_name(out);
  check_outputs_are_new({{"--source", source}, {"--target", target}, {"--map-12", map_file}, {"--texture", texture_file}},
                        {{"--out", out}, {"the target's output (from --out)", out_target}});
  check_writable(out);
  const Progress progress(common.quiet);
  const smc::Triangle_soup ms = read_mesh_soup(source), mt = read_mesh_soup(target);
  const Vertex_map map_12 = read_vertex_map(map_file, index_base, ms.number_of_vertices(), mt.number_of_vertices());
  std::vector<Color> colors;
  if(texture_file.empty())
    colors = coordinate_colors(mt);
  else
  {
    const Texture texture = read_png(texture_file);
    progress.line("read " + texture_file + " (" + std::to_string(texture.width) + " x " +
                  std::to_string(texture.height) + ")");
    colors = texture_colors(mt, texture);
  }
  write_colored_ply(out, ms, pull_colors(colors, map_12));
  write_colored_ply(out_target, mt, colors);
  std::cout << "wrote " << out << " (source, " << ms.number_of_vertices() << " vertices, colours pulled through "
            << map_file << ") and " << out_target << " (target, " << mt.number_of_vertices() << " vertices, "
            << (texture_file.empty() ? std::string("coordinate colours") : "texture " + texture_file) << ")\n";
  return 0;
}

} // namespace comap
