// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_mesh_io.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

#include <sys/stat.h>

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;

Mesh read_triangle_mesh(const std::string& file)
{
  Mesh mesh;
  smc::read_triangle_mesh(file, mesh);
  return mesh;
}

smc::Triangle_soup read_mesh_soup(const std::string& file)
{
  return smc::read_triangle_soup(file);
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

bool same_file(const std::string& a, const std::string& b)
{
  struct stat sa, sb;
  if(::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const std::filesystem::path pa = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ea);
  const std::filesystem::path pb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), eb);
  return !ea && !eb && pa == pb;
}

void check_outputs_are_new(const std::vector<Named_file>& inputs, const std::vector<Named_file>& outputs)
{
  for(std::size_t i = 0; i < outputs.size(); ++i)
  {
    const Named_file& out = outputs[i];
    if(out.path.empty()) continue;
    for(const Named_file& in : inputs)
      if(!in.path.empty() && same_file(out.path, in.path))
        throw Usage_error(out.name + " " + out.path + " names the same file as " + in.name + " " + in.path +
                          ": an output never replaces an input");
    for(std::size_t j = 0; j < i; ++j)
      if(!outputs[j].path.empty() && same_file(out.path, outputs[j].path))
        throw Usage_error(outputs[j].name + " " + outputs[j].path + " and " + out.name + " " + out.path +
                          " name the same file: each output needs its own");
  }
}

void commit_outputs(std::initializer_list<smc::Atomic_output_file*> files)
{
  for(smc::Atomic_output_file* f : files) f->close();
  if(std::getenv("COMAP_TEST_KILL_BEFORE_COMMIT")) std::raise(SIGKILL);
  for(smc::Atomic_output_file* f : files) f->commit();
}

void write_vertex_map(const std::string& file, const Vertex_map& map, int index_base)
{
  smc::Atomic_output_file out(file);
  smc::write_vertex_indices(out.stream(), map, index_base);
  commit_outputs({&out});
}

void write_vertex_maps(const std::string& file_12, const Vertex_map& map_12, const std::string& file_21,
                       const Vertex_map& map_21, int index_base)
{
  smc::Atomic_output_file out_12(file_12), out_21(file_21);
  smc::write_vertex_indices(out_12.stream(), map_12, index_base);
  smc::write_vertex_indices(out_21.stream(), map_21, index_base);
  commit_outputs({&out_12, &out_21});
}

void write_colored_ply(const std::string& file, const smc::Triangle_soup& mesh, const std::vector<Color>& colors)
{
  smc::Atomic_output_file atomic(file);
  std::ostream& out = atomic.stream();
  out << "ply\nformat ascii 1.0\ncomment written by comap (Surface_mesh_correspondence)\n"
      << "element vertex " << mesh.number_of_vertices() << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << mesh.number_of_triangles() << "\nproperty list uchar int vertex_indices\nend_header\n";
  auto byte = [](double c) { return static_cast<int>(std::lround(255.0 * std::min(1.0, std::max(0.0, c)))); };
  char line[160];
  for(std::size_t v = 0; v < mesh.number_of_vertices(); ++v)
  {
    const smc::Triangle_soup::Point& p = mesh.points()[v];
    const Color& c = colors[v];
    std::snprintf(line, sizeof(line), "%.7g %.7g %.7g %d %d %d\n", p[0], p[1], p[2], byte(c[0]), byte(c[1]),
                  byte(c[2]));
    out << line;
  }
  for(const smc::Triangle_soup::Triangle& t : mesh.triangles()) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  commit_outputs({&atomic});
}

void write_off(const std::string& file, const Mesh& mesh)
{
  smc::Atomic_output_file atomic(file);
  std::ostream& out = atomic.stream();
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
  commit_outputs({&atomic});
}

std::vector<std::pair<std::size_t, std::size_t> > read_landmarks(const std::string& file, int index_base,
                                                                 std::size_t n1, std::size_t n2)
{
  std::ifstream in(file);
  if(!in) throw Input_error("cannot open the landmark file " + file);
  std::vector<std::pair<std::size_t, std::size_t> > out;
  std::string line;
  for(int number = 1; std::getline(in, line); ++number)
  {
    const std::string content = line.substr(0, line.find('#'));
    if(content.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(content);
    long long a = 0, b = 0;
    std::string rest;
    if(!(fields >> a >> b) || (fields >> rest))
      throw Input_error(file + ":" + std::to_string(number) + ": expected two vertex indices, found '" + content + "'");
    if(a < index_base || b < index_base || std::size_t(a - index_base) >= n1 || std::size_t(b - index_base) >= n2)
      throw Input_error(file + ":" + std::to_string(number) + ": landmark (" + std::to_string(a) + ", " +
                        std::to_string(b) + ") is out of range (" + std::to_string(index_base) + "-based; " +
                        std::to_string(n1) + " and " + std::to_string(n2) + " vertices)");
    out.emplace_back(std::size_t(a - index_base), std::size_t(b - index_base));
  }
  if(out.empty()) throw Input_error("the landmark file " + file + " has no landmarks");
  return out;
}

} // namespace comap
