// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_mesh_io.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

#include <sys/stat.h>

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

typedef std::vector<std::vector<std::size_t> > Polygons;

/// A polygon soup read from a file, with the line of each vertex and face in the file (0 for
/// the binary formats, whose elements have no line).
struct Soup
{
  std::vector<Point> points;
  Polygons polygons;
  std::vector<std::size_t> point_lines, face_lines;
};

/// The lines of a text file with their numbers, without comments ('#' to the end of the line)
/// and blank lines.
class Text_lines
{
public:
  explicit Text_lines(const std::string& file) : file_(file), in_(file) {}

  /// The next line that holds something, split into tokens; false at the end of the file.
  bool next(std::vector<std::string>& tokens)
  {
    std::string line;
    while(std::getline(in_, line))
    {
      ++number_;
      const std::size_t hash = line.find('#');
      if(hash != std::string::npos) line.erase(hash);
      std::istringstream words(line);
      tokens.clear();
      std::string w;
      while(words >> w) tokens.push_back(w);
      if(!tokens.empty()) return true;
    }
    return false;
  }
  std::size_t number() const { return number_; }
  /// "FILE:LINE: "
  std::string where() const { return file_ + ":" + std::to_string(number_) + ": "; }

private:
  std::string file_;
  std::ifstream in_;
  std::size_t number_ = 0;
};

/// A number token ("nan" and "inf" are read as such, so that they can be named).
bool parse_number(const std::string& token, double& x)
{
  const char* begin = token.c_str();
  char* end = nullptr;
  x = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

bool parse_index(const std::string& token, long long& i)
{
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  i = std::strtoll(begin, &end, 10);
  return end != begin && *end == '\0' && errno != ERANGE;
}

/// Reads a point from the first three tokens of a line (from `first`).
Point read_point(const Text_lines& lines, const std::vector<std::string>& tokens, std::size_t first, std::size_t vertex)
{
  double c[3];
  if(tokens.size() < first + 3)
    throw smc::IO_error(lines.where() + "vertex " + std::to_string(vertex) + ": expected three coordinates");
  for(int k = 0; k < 3; ++k)
    if(!parse_number(tokens[first + std::size_t(k)], c[k]))
      throw smc::IO_error(lines.where() + "vertex " + std::to_string(vertex) + ": \"" + tokens[first + std::size_t(k)] +
                          "\" is not a number");
  return Point(c[0], c[1], c[2]);
}

/// An ASCII OFF file ("OFF", optional comments, "nv nf ne", nv vertex lines, nf face lines).
Soup read_off_text(const std::string& file)
{
  Text_lines lines(file);
  std::vector<std::string> t;
  if(!lines.next(t)) throw smc::IO_error(file + ": the file is empty");
  const std::string header = t[0];  // OFF, or COFF, NOFF, ... (the extra vertex columns are skipped)
  if(header.size() < 3 || header.compare(header.size() - 3, 3, "OFF") != 0)
    throw smc::IO_error(lines.where() + "expected the OFF header, found \"" + header + "\"");
  std::vector<std::string> counts(t.begin() + 1, t.end());  // on the header's line, or the next one
  if(counts.empty() && !lines.next(counts)) throw smc::IO_error(file + ": truncated after the OFF header");
  long long nv = -1, nf = -1;
  if(counts.size() < 2 || !parse_index(counts[0], nv) || !parse_index(counts[1], nf) || nv < 0 || nf < 0)
    throw smc::IO_error(lines.where() + "expected the numbers of vertices and faces");
  Soup soup;
  soup.points.reserve(std::size_t(nv));
  soup.polygons.reserve(std::size_t(nf));
  for(long long i = 0; i < nv; ++i)
  {
    if(!lines.next(t))
      throw smc::IO_error(file + ": truncated: the header declares " + std::to_string(nv) + " vertices and " +
                          std::to_string(nf) + " faces, the file ends after " + std::to_string(i) + " vertices");
    soup.points.push_back(read_point(lines, t, 0, std::size_t(i)));
    soup.point_lines.push_back(lines.number());
  }
  for(long long f = 0; f < nf; ++f)
  {
    if(!lines.next(t))
      throw smc::IO_error(file + ": truncated: the header declares " + std::to_string(nf) + " faces, the file ends after " +
                          std::to_string(f));
    long long k = 0;
    if(!parse_index(t[0], k) || k < 1)
      throw smc::IO_error(lines.where() + "face " + std::to_string(f) + ": expected its number of vertices, found \"" +
                          t[0] + "\"");
    if(t.size() < std::size_t(k) + 1)
      throw smc::IO_error(lines.where() + "face " + std::to_string(f) + ": expected " + std::to_string(k) +
                          " vertex indices, found " + std::to_string(t.size() - 1));
    std::vector<std::size_t> face;
    for(long long c = 1; c <= k; ++c)
    {
      long long v = 0;
      if(!parse_index(t[std::size_t(c)], v))
        throw smc::IO_error(lines.where() + "face " + std::to_string(f) + ": \"" + t[std::size_t(c)] +
                            "\" is not a vertex index");
      if(v < 0 || v >= nv)
        throw smc::Invalid_mesh_error(lines.where() + "face " + std::to_string(f) + " refers to vertex " +
                                      std::to_string(v) + " but the file has " + std::to_string(nv) + " vertices");
      face.push_back(std::size_t(v));
    }
    soup.polygons.push_back(face);
    soup.face_lines.push_back(lines.number());
  }
  return soup;
}

/// An OBJ file: its "v" and "f" lines (f entries "i", "i/t", "i//n" or "i/t/n", negative indices
/// counting back from the last vertex read); other lines are skipped.
Soup read_obj_text(const std::string& file)
{
  Text_lines lines(file);
  std::vector<std::string> t;
  Soup soup;
  while(lines.next(t))
  {
    if(t[0] == "v")
    {
      soup.points.push_back(read_point(lines, t, 1, soup.points.size()));
      soup.point_lines.push_back(lines.number());
    }
    else if(t[0] == "f")
    {
      const std::size_t f = soup.polygons.size();
      std::vector<std::size_t> face;
      for(std::size_t c = 1; c < t.size(); ++c)
      {
        long long v = 0;
        if(!parse_index(t[c].substr(0, t[c].find('/')), v) || v == 0)
          throw smc::IO_error(lines.where() + "face " + std::to_string(f) + ": \"" + t[c] + "\" is not a vertex index");
        const long long n = static_cast<long long>(soup.points.size());
        const long long index = v > 0 ? v - 1 : n + v;
        if(index < 0 || index >= n)
          throw smc::Invalid_mesh_error(lines.where() + "face " + std::to_string(f) + " refers to vertex " +
                                        std::to_string(v) + " but " + std::to_string(n) +
                                        " vertices are defined before it");
        face.push_back(std::size_t(index));
      }
      if(face.empty()) throw smc::IO_error(lines.where() + "face " + std::to_string(f) + " has no vertex");
      soup.polygons.push_back(face);
      soup.face_lines.push_back(lines.number());
    }
  }
  return soup;
}

bool is_binary_off(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  std::string first;
  std::getline(in, first);
  return first.find("BINARY") != std::string::npos;
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
  Soup soup;
  if(ext == "obj")
    soup = read_obj_text(file);
  else if(ext == "off" && !is_binary_off(file))
    soup = read_off_text(file);
  else
  {
    // PLY, STL and binary OFF: CGAL's readers; the checks below name the vertex or the face.
    std::ifstream in(file, std::ios::binary);
    bool ok = false;
    if(ext == "off")
      ok = CGAL::IO::read_OFF(in, soup.points, soup.polygons);
    else if(ext == "ply")
      ok = CGAL::IO::read_PLY(in, soup.points, soup.polygons);
    else
      ok = CGAL::IO::read_STL(in, soup.points, soup.polygons);
    if(!ok || soup.points.empty())
      throw smc::IO_error(file + ": cannot read a mesh from this file (malformed or empty " + ext + " file)");
  }
  smc::Triangle_soup_origin origin(file);
  origin.vertex_lines = std::move(soup.point_lines);
  origin.face_lines = std::move(soup.face_lines);
  Mesh mesh;
  smc::triangle_soup_to_mesh(soup.points, soup.polygons, mesh, origin);
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

void write_colored_ply(const std::string& file, const Mesh& mesh, const std::vector<Color>& colors)
{
  smc::Atomic_output_file atomic(file);
  std::ostream& out = atomic.stream();
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

} // namespace comap
