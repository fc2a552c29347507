// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reading triangle meshes from files (OFF, OBJ, PLY, STL) as triangle soups, with messages that
// name the file and, for the text formats users edit by hand (OFF, OBJ), the line and the vertex
// or face; then the checks of check_triangle_soup() and the conversion to a FaceGraph.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_MESH_IO_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_MESH_IO_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The faces of a soup read from a file: vertex indices, 0-based (any number per face until
/// check_triangle_soup() rejects the non-triangles).
typedef std::vector<std::vector<std::size_t> > Soup_polygons;

namespace internal {

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
inline bool parse_number(const std::string& token, double& x)
{
  const char* begin = token.c_str();
  char* end = nullptr;
  x = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

inline bool parse_index(const std::string& token, long long& i)
{
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  i = std::strtoll(begin, &end, 10);
  return end != begin && *end == '\0' && errno != ERANGE;
}

/// Reads a point from the first three tokens of a line (from `first`).
template <typename Point>
Point read_point(const Text_lines& lines, const std::vector<std::string>& tokens, std::size_t first, std::size_t vertex)
{
  double c[3];
  if(tokens.size() < first + 3)
    throw IO_error(lines.where() + "vertex " + std::to_string(vertex) + ": expected three coordinates");
  for(int k = 0; k < 3; ++k)
    if(!parse_number(tokens[first + std::size_t(k)], c[k]))
      throw IO_error(lines.where() + "vertex " + std::to_string(vertex) + ": \"" + tokens[first + std::size_t(k)] +
                     "\" is not a number");
  return Point(c[0], c[1], c[2]);
}

/// An ASCII OFF file ("OFF", optional comments, "nv nf ne", nv vertex lines, nf face lines).
template <typename Point>
void read_off_text(const std::string& file, std::vector<Point>& points, Soup_polygons& polygons,
                   Triangle_soup_origin& origin)
{
  Text_lines lines(file);
  std::vector<std::string> t;
  if(!lines.next(t)) throw IO_error(file + ": the file is empty");
  const std::string header = t[0];  // OFF, or COFF, NOFF, ... (the extra vertex columns are skipped)
  if(header.size() < 3 || header.compare(header.size() - 3, 3, "OFF") != 0)
    throw IO_error(lines.where() + "expected the OFF header, found \"" + header + "\"");
  std::vector<std::string> counts(t.begin() + 1, t.end());  // on the header's line, or the next one
  if(counts.empty() && !lines.next(counts)) throw IO_error(file + ": truncated after the OFF header");
  long long nv = -1, nf = -1;
  if(counts.size() < 2 || !parse_index(counts[0], nv) || !parse_index(counts[1], nf) || nv < 0 || nf < 0)
    throw IO_error(lines.where() + "expected the numbers of vertices and faces");
  points.reserve(std::size_t(nv));
  polygons.reserve(std::size_t(nf));
  for(long long i = 0; i < nv; ++i)
  {
    if(!lines.next(t))
      throw IO_error(file + ": truncated: the header declares " + std::to_string(nv) + " vertices and " +
                     std::to_string(nf) + " faces, the file ends after " + std::to_string(i) + " vertices");
    points.push_back(read_point<Point>(lines, t, 0, std::size_t(i)));
    origin.vertex_lines.push_back(lines.number());
  }
  for(long long f = 0; f < nf; ++f)
  {
    if(!lines.next(t))
      throw IO_error(file + ": truncated: the header declares " + std::to_string(nf) + " faces, the file ends after " +
                     std::to_string(f));
    long long k = 0;
    if(!parse_index(t[0], k) || k < 1)
      throw IO_error(lines.where() + "face " + std::to_string(f) + ": expected its number of vertices, found \"" +
                     t[0] + "\"");
    if(t.size() < std::size_t(k) + 1)
      throw IO_error(lines.where() + "face " + std::to_string(f) + ": expected " + std::to_string(k) +
                     " vertex indices, found " + std::to_string(t.size() - 1));
    std::vector<std::size_t> face;
    for(long long c = 1; c <= k; ++c)
    {
      long long v = 0;
      if(!parse_index(t[std::size_t(c)], v))
        throw IO_error(lines.where() + "face " + std::to_string(f) + ": \"" + t[std::size_t(c)] +
                       "\" is not a vertex index");
      if(v < 0 || v >= nv)
        throw Invalid_mesh_error(lines.where() + "face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + " but the file has " + std::to_string(nv) + " vertices");
      face.push_back(std::size_t(v));
    }
    polygons.push_back(face);
    origin.face_lines.push_back(lines.number());
  }
}

/// An OBJ file: its "v" and "f" lines (f entries "i", "i/t", "i//n" or "i/t/n", negative indices
/// counting back from the last vertex read); other lines are skipped.
template <typename Point>
void read_obj_text(const std::string& file, std::vector<Point>& points, Soup_polygons& polygons,
                   Triangle_soup_origin& origin)
{
  Text_lines lines(file);
  std::vector<std::string> t;
  while(lines.next(t))
  {
    if(t[0] == "v")
    {
      points.push_back(read_point<Point>(lines, t, 1, points.size()));
      origin.vertex_lines.push_back(lines.number());
    }
    else if(t[0] == "f")
    {
      const std::size_t f = polygons.size();
      std::vector<std::size_t> face;
      for(std::size_t c = 1; c < t.size(); ++c)
      {
        long long v = 0;
        if(!parse_index(t[c].substr(0, t[c].find('/')), v) || v == 0)
          throw IO_error(lines.where() + "face " + std::to_string(f) + ": \"" + t[c] + "\" is not a vertex index");
        const long long n = static_cast<long long>(points.size());
        const long long index = v > 0 ? v - 1 : n + v;
        if(index < 0 || index >= n)
          throw Invalid_mesh_error(lines.where() + "face " + std::to_string(f) + " refers to vertex " +
                                   std::to_string(v) + " but " + std::to_string(n) +
                                   " vertices are defined before it");
        face.push_back(std::size_t(index));
      }
      if(face.empty()) throw IO_error(lines.where() + "face " + std::to_string(f) + " has no vertex");
      polygons.push_back(face);
      origin.face_lines.push_back(lines.number());
    }
  }
}

inline bool is_binary_off(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  std::string first;
  std::getline(in, first);
  return first.find("BINARY") != std::string::npos;
}

inline std::string lowercase_extension(const std::string& file)
{
  const std::size_t dot = file.find_last_of('.'), slash = file.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = file.substr(dot + 1);
  for(char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Reads the points and faces of a mesh file as they are in the file: OFF (text: the package's
/// own reader; binary: CGAL's), OBJ (the package's own reader: "v" and "f" lines), PLY and STL
/// (CGAL's readers). `origin` receives the file name and, for OFF and OBJ text files, the line of
/// every vertex and face, for the messages of check_triangle_soup().
/// \tparam Point a point type constructible from three doubles (e.g. a CGAL kernel's Point_3)
/// \throws IO_error for a file that is missing, a directory, of an unknown format, empty,
///   truncated or malformed (naming the file, and the line for OFF and OBJ);
///   Invalid_mesh_error for a face index out of range in an OFF or OBJ file (with its line)
template <typename Point>
void read_triangle_soup(const std::string& file, std::vector<Point>& points, Soup_polygons& polygons,
                        Triangle_soup_origin& origin)
{
  points.clear();
  polygons.clear();
  origin = Triangle_soup_origin(file);
  {
    std::ifstream probe(file);
    if(!probe) throw IO_error("cannot open " + file + ": " + std::strerror(errno));
  }
  struct stat status;
  if(::stat(file.c_str(), &status) == 0 && S_ISDIR(status.st_mode))
    throw IO_error("cannot read " + file + ": it is a directory");
  const std::string ext = internal::lowercase_extension(file);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl")
    throw IO_error(file + ": unknown mesh format \"" + ext + "\" (.off, .ply, .obj and .stl are read)");
  if(ext == "obj")
    internal::read_obj_text(file, points, polygons, origin);
  else if(ext == "off" && !internal::is_binary_off(file))
    internal::read_off_text(file, points, polygons, origin);
  else
  {
    // PLY, STL and binary OFF: CGAL's readers; check_triangle_soup() names the vertex or face.
    std::ifstream in(file, std::ios::binary);
    bool ok = false;
    if(ext == "off")
      ok = CGAL::IO::read_OFF(in, points, polygons);
    else if(ext == "ply")
      ok = CGAL::IO::read_PLY(in, points, polygons);
    else
      ok = CGAL::IO::read_STL(in, points, polygons);
    if(!ok || points.empty())
      throw IO_error(file + ": cannot read a mesh from this file (malformed or empty " + ext + " file)");
  }
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Reads a mesh file (read_triangle_soup()) into `mesh` (triangle_soup_to_mesh()): vertex i of
/// `mesh` is the i-th point of the file, so that maps read from files refer to it.
/// \tparam PolygonMesh a model of `MutableFaceGraph`
/// \throws IO_error (see read_triangle_soup()), Invalid_mesh_error (see check_triangle_soup()),
///   each naming the file
template <typename PolygonMesh>
void read_triangle_mesh(const std::string& file, PolygonMesh& mesh)
{
  typedef typename boost::property_traits<
      typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>::value_type Point;
  std::vector<Point> points;
  Soup_polygons polygons;
  Triangle_soup_origin origin;
  read_triangle_soup(file, points, polygons, origin);
  triangle_soup_to_mesh(points, polygons, mesh, origin);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Reads a mesh file (read_triangle_soup()) into a Triangle_soup, with the file name and, for OFF
/// and OBJ text files, the lines of the vertices and faces for its messages: point i is the i-th
/// point of the file. No halfedge data structure is built.
/// \throws IO_error (see read_triangle_soup()), Invalid_mesh_error (the checks of Triangle_soup),
///   each naming the file
inline Triangle_soup read_triangle_soup(const std::string& file)
{
  std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
  Soup_polygons polygons;
  Triangle_soup_origin origin;
  read_triangle_soup(file, points, polygons, origin);
  return Triangle_soup(points, polygons, std::move(origin));
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_MESH_IO_H
