// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_mesh_io.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>
#include <utility>

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

struct Union_find
{
  std::vector<std::size_t> parent;
  explicit Union_find(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
  std::size_t find(std::size_t x)
  {
    while(parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

typedef std::vector<std::vector<std::size_t> > Polygons;

/// Names the first reason why the triangle soup is not a manifold, consistently oriented mesh.
std::string soup_problem(const Polygons& triangles)
{
  // Faces of every undirected edge, with the direction in which each face traverses it.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, bool> > > edges;
  for(std::size_t f = 0; f < triangles.size(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const std::size_t a = triangles[f][c], b = triangles[f][(c + 1) % 3];
      edges[std::make_pair(std::min(a, b), std::max(a, b))].emplace_back(f, a < b);
    }
  for(const auto& e : edges)
    if(e.second.size() > 2)
      return "is not manifold: the edge (" + std::to_string(e.first.first) + ", " + std::to_string(e.first.second) +
             ") is shared by " + std::to_string(e.second.size()) + " faces";
  for(const auto& e : edges)
    if(e.second.size() == 2 && e.second[0].second == e.second[1].second)
      return "has inconsistently oriented faces: faces " + std::to_string(e.second[0].first) + " and " +
             std::to_string(e.second[1].first) + " traverse the edge (" + std::to_string(e.first.first) + ", " +
             std::to_string(e.first.second) +
             ") in the same direction (reorient it, e.g. with CGAL::Polygon_mesh_processing::orient_polygon_soup)";
  // Vertices where several fans of faces meet: corners (face, vertex) joined across edges.
  Union_find corners(3 * triangles.size());
  auto corner = [&](std::size_t f, std::size_t v) {
    for(int c = 0; c < 3; ++c)
      if(triangles[f][c] == v) return 3 * f + c;
    return std::size_t(0);
  };
  for(const auto& e : edges)
    if(e.second.size() == 2)
    {
      const std::size_t f = e.second[0].first, g = e.second[1].first;
      corners.unite(corner(f, e.first.first), corner(g, e.first.first));
      corners.unite(corner(f, e.first.second), corner(g, e.first.second));
    }
  std::map<std::size_t, std::size_t> fan_of_vertex;
  for(std::size_t f = 0; f < triangles.size(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const std::size_t v = triangles[f][c], root = corners.find(3 * f + c);
      auto it = fan_of_vertex.find(v);
      if(it == fan_of_vertex.end())
        fan_of_vertex.emplace(v, root);
      else if(it->second != root)
        return "is not manifold: vertex " + std::to_string(v) + " joins several separate fans of faces";
    }
  return "is not a manifold, consistently oriented surface";
}

std::string lowercase_extension(const std::string& file)
{
  const std::size_t dot = file.find_last_of('.'), slash = file.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = file.substr(dot + 1);
  for(char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

} // namespace

Mesh read_triangle_mesh(const std::string& file)
{
  {
    std::ifstream probe(file);
    if(!probe) throw smc::IO_error("cannot open " + file + ": " + std::strerror(errno));
  }
  if(directory_exists(file)) throw smc::IO_error("cannot read " + file + ": it is a directory");
  const std::string ext = lowercase_extension(file);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl")
    throw smc::IO_error(file + ": unknown mesh format \"" + ext + "\" (comap reads .off, .ply, .obj and .stl)");
  std::vector<Point> points;
  Polygons polygons;
  bool ok = false;
  {
    // CGAL's readers dispatch on the lower-case extension.
    std::ifstream in(file, std::ios::binary);
    if(ext == "off")
      ok = CGAL::IO::read_OFF(in, points, polygons);
    else if(ext == "obj")
      ok = CGAL::IO::read_OBJ(in, points, polygons);
    else if(ext == "ply")
      ok = CGAL::IO::read_PLY(in, points, polygons);
    else
      ok = CGAL::IO::read_STL(in, points, polygons);
  }
  if(!ok || points.empty())
    throw smc::IO_error(file + ": cannot read a mesh from this file (malformed or empty " + ext + " file)");
  if(polygons.empty()) throw smc::Invalid_mesh_error(file + ": the mesh has no faces");
  const std::size_t n = points.size();
  for(std::size_t i = 0; i < n; ++i)
    if(!std::isfinite(points[i].x()) || !std::isfinite(points[i].y()) || !std::isfinite(points[i].z()))
      throw smc::Invalid_mesh_error(file + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  std::size_t non_triangles = 0, first_non_triangle = 0;
  for(std::size_t f = 0; f < polygons.size(); ++f)
  {
    for(std::size_t v : polygons[f])
      if(v >= n)
        throw smc::Invalid_mesh_error(file + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                      " but the file has " + std::to_string(n) + " vertices");
    if(polygons[f].size() != 3 && non_triangles++ == 0) first_non_triangle = f;
  }
  if(non_triangles > 0)
    throw smc::Invalid_mesh_error(file + ": " + std::to_string(non_triangles) + " of " +
                                  std::to_string(polygons.size()) + " faces are not triangles (face " +
                                  std::to_string(first_non_triangle) + " has " +
                                  std::to_string(polygons[first_non_triangle].size()) +
                                  " vertices); triangulate the mesh first");
  for(std::size_t f = 0; f < polygons.size(); ++f)
  {
    const auto& t = polygons[f];
    if(t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw smc::Invalid_mesh_error(file + ": face " + std::to_string(f) + " is degenerate (it repeats a vertex)");
  }
  if(!PMP::is_polygon_soup_a_polygon_mesh(polygons)) throw smc::Invalid_mesh_error(file + " " + soup_problem(polygons));
  std::vector<char> used(n, 0);
  Union_find components(n);
  for(const auto& t : polygons)
  {
    for(std::size_t v : t) used[v] = 1;
    components.unite(t[0], t[1]);
    components.unite(t[1], t[2]);
  }
  for(std::size_t v = 0; v < n; ++v)
    if(!used[v])
      throw smc::Invalid_mesh_error(file + ": vertex " + std::to_string(v) +
                                    " belongs to no face (remove isolated vertices first)");
  std::size_t number_of_components = 0;
  for(std::size_t v = 0; v < n; ++v) number_of_components += components.find(v) == v;
  if(number_of_components > 1)
    throw smc::Invalid_mesh_error(file + " has " + std::to_string(number_of_components) +
                                  " connected components; comap needs one connected surface (keep the largest, "
                                  "e.g. with CGAL::Polygon_mesh_processing::keep_largest_connected_components)");
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if(num_vertices(mesh) != n || num_faces(mesh) != polygons.size())
    throw smc::Invalid_mesh_error(file + ": the faces do not form a valid surface mesh");
  // Vertex i must be the i-th point of the file: maps refer to the file's numbering.
  for(std::size_t i = 0; i < n; ++i)
    if(mesh.point(Mesh::Vertex_index(static_cast<Mesh::size_type>(i))) != points[i])
      throw smc::Invalid_mesh_error(file + ": internal error: the vertex order changed while building the mesh");
  return mesh;
}

Vertex_map read_vertex_map(const std::string& file, int index_base, std::size_t source_vertices,
                           std::size_t target_vertices)
{
  const Vertex_map map = smc::read_vertex_indices(file, index_base);
  smc::check_vertex_map(map, source_vertices, target_vertices, file);
  return map;
}

Vertex_map read_correspondences(const std::string& file, int index_base, std::size_t mesh_vertices)
{
  const Vertex_map list = smc::read_vertex_indices(file, index_base);
  if(list.empty()) throw smc::IO_error(file + ": no correspondence in this file");
  smc::check_vertex_indices(list, mesh_vertices, file);
  return list;
}

void write_vertex_map(const std::string& file, const Vertex_map& map, int index_base)
{
  smc::write_vertex_indices(file, map, index_base);
}

void write_colored_ply(const std::string& file, const Mesh& mesh, const std::vector<Color>& colors)
{
  std::ofstream out(file);
  if(!out) throw smc::IO_error("cannot open " + file + " for writing: " + std::strerror(errno));
  out << "ply\nformat ascii 1.0\ncomment written by comap (Surface_mesh_correspondence)\n"
      << "element vertex " << num_vertices(mesh) << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << num_faces(mesh) << "\nproperty list uchar int vertex_indices\nend_header\n";
  auto byte = [](double c) { return static_cast<int>(std::lround(255.0 * std::min(1.0, std::max(0.0, c)))); };
  char line[160];
  for(Mesh::Vertex_index v : mesh.vertices())
  {
    const Point& p = mesh.point(v);
    const Color& c = colors[v.idx()];
    std::snprintf(line, sizeof(line), "%.7g %.7g %.7g %d %d %d\n", p.x(), p.y(), p.z(), byte(c[0]), byte(c[1]),
                  byte(c[2]));
    out << line;
  }
  for(Mesh::Face_index f : mesh.faces())
  {
    out << "3";
    for(Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) out << ' ' << v.idx();
    out << '\n';
  }
  out.flush();
  if(!out) throw smc::IO_error("error while writing " + file);
}

void write_off(const std::string& file, const Mesh& mesh)
{
  std::ofstream out(file);
  if(!out) throw smc::IO_error("cannot open " + file + " for writing: " + std::strerror(errno));
  out << "OFF\n" << num_vertices(mesh) << ' ' << num_faces(mesh) << " 0\n";
  char line[128];
  for(Mesh::Vertex_index v : mesh.vertices())
  {
    const Point& p = mesh.point(v);
    std::snprintf(line, sizeof(line), "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    out << line;
  }
  for(Mesh::Face_index f : mesh.faces())
  {
    out << "3";
    for(Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) out << ' ' << v.idx();
    out << '\n';
  }
  out.flush();
  if(!out) throw smc::IO_error("error while writing " + file);
}

} // namespace comap
