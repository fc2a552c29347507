// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Meshes given as a triangle soup (points and index triples: what a file holds, what numpy
// arrays hold): the checks the package needs, with messages that name the vertex or the face
// (and the file and line when the soup was read from a text file), and the conversion to a
// FaceGraph whose vertex i is point i.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_TRIANGLE_SOUP_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_TRIANGLE_SOUP_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Where a triangle soup comes from, for the messages of check_triangle_soup(): a name (a file,
/// "mesh 1") and, for a soup read from a text file, the line of each vertex and face.
struct Triangle_soup_origin
{
  std::string name = "mesh";
  /// Line of vertex i / face f in the file (empty, or shorter than the soup: not known).
  std::vector<std::size_t> vertex_lines, face_lines;

  Triangle_soup_origin() = default;
  Triangle_soup_origin(std::string n) : name(std::move(n)) {}

  /// "NAME:LINE: " for vertex i when its line is known, "NAME: " otherwise.
  std::string where_vertex(std::size_t i) const { return where(vertex_lines, i); }
  /// The same for face f.
  std::string where_face(std::size_t f) const { return where(face_lines, f); }

private:
  std::string where(const std::vector<std::size_t>& lines, std::size_t i) const
  {
    return i < lines.size() ? name + ":" + std::to_string(lines[i]) + ": " : name + ": ";
  }
};

namespace internal {

template <typename Index>
long long soup_index(const Index& i)
{
  static_assert(std::is_integral<Index>::value, "the faces of a triangle soup hold integer vertex indices");
  if constexpr(std::is_unsigned<Index>::value)
    return i > Index(std::numeric_limits<long long>::max()) ? std::numeric_limits<long long>::max()
                                                             : static_cast<long long>(i);
  else
    return static_cast<long long>(i);
}

/// Throws unless the two faces of every interior manifold edge traverse it in opposite directions
/// (the orientation of the faces around an edge in more than two of them, e.g. a fin, is not
/// checked: some of them must traverse it in the same direction).
inline void check_soup_orientation(const Indexed_mesh& m, const std::string& label)
{
  // The face that traverses each directed edge (a -> b).
  std::map<std::pair<int, int>, int> directed;
  for(int f = 0; f < m.number_of_triangles(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int a = m.triangles(f, c), b = m.triangles(f, (c + 1) % 3);
      const auto inserted = directed.emplace(std::make_pair(a, b), f);
      const std::array<int, 2> edge{{std::min(a, b), std::max(a, b)}};
      if(!inserted.second &&
         !std::binary_search(m.non_manifold_edges.begin(), m.non_manifold_edges.end(), edge))
        throw Invalid_mesh_error(label + " has inconsistently oriented faces: faces " +
                                 std::to_string(inserted.first->second) + " and " + std::to_string(f) +
                                 " traverse the edge (" + std::to_string(std::min(a, b)) + ", " +
                                 std::to_string(std::max(a, b)) +
                                 ") in the same direction (reorient it, e.g. with "
                                 "CGAL::Polygon_mesh_processing::orient_polygon_soup)");
    }
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A triangle mesh given as a triangle soup: points and index triples, vertex i being point i.
/// It is the package's input form that needs no halfedge data structure (what a mesh file holds,
/// what numpy arrays hold): `Correspondence_shape<Triangle_soup>` prepares it for matching
/// directly, and maps between such shapes are vectors of point indices.
///
/// The constructor copies the soup and checks what belongs to the soup itself: at least one
/// vertex and one face, finite coordinates, faces of three distinct vertices in range. What
/// belongs to the surface (zero-area faces, non-manifold edges and vertices, orientation,
/// isolated vertices, components) is checked where the soup is prepared (check_triangle_soup(),
/// Correspondence_shape), with the same messages.
class Triangle_soup
{
public:
  typedef std::array<double, 3> Point;
  typedef std::array<int, 3> Triangle;

  /// An empty soup (a shape cannot be prepared from it).
  Triangle_soup() = default;

  /// Copies `points` and `polygons`.
  /// \tparam PointRange a random-access range of points whose coordinates are read with `p[0]`,
  ///   `p[1]`, `p[2]` (CGAL points, `std::array<double, 3>`)
  /// \tparam PolygonRange a random-access range of faces, each a range of integer vertex indices
  ///   with `size()` and `operator[]`
  /// \param points the positions of the vertices (point i: vertex i)
  /// \param polygons the faces, as indices into `points`
  /// \param origin the name of the soup (a file, "mesh 1") and, for a soup read from a text file,
  ///   the line of each vertex and face, for the messages
  /// \throws Invalid_mesh_error naming the first problem, the vertex or face, and where it comes
  ///   from
  template <typename PointRange, typename PolygonRange>
  Triangle_soup(const PointRange& points, const PolygonRange& polygons, Triangle_soup_origin origin = Triangle_soup_origin())
      : origin_(std::move(origin))
  {
    const std::string& label = origin_.name;
    const std::size_t n = points.size(), nf = polygons.size();
    if(n == 0) throw Invalid_mesh_error(label + ": the mesh has no vertices");
    if(nf == 0) throw Invalid_mesh_error(label + ": the mesh has no faces");
    points_.resize(n);
    for(std::size_t i = 0; i < n; ++i)
    {
      const auto& p = points[i];
      points_[i] = {{double(p[0]), double(p[1]), double(p[2])}};
      if(!std::isfinite(points_[i][0]) || !std::isfinite(points_[i][1]) || !std::isfinite(points_[i][2]))
      {
        std::ostringstream s;
        s << points_[i][0] << " " << points_[i][1] << " " << points_[i][2];
        throw Invalid_mesh_error(origin_.where_vertex(i) + "vertex " + std::to_string(i) +
                                 " has a non-finite coordinate (" + s.str() + ")");
      }
    }
    std::size_t non_triangles = 0, first_non_triangle = 0;
    for(std::size_t f = 0; f < nf; ++f)
    {
      const auto& face = polygons[f];
      for(std::size_t c = 0; c < std::size_t(face.size()); ++c)
      {
        const long long v = internal::soup_index(face[c]);
        if(v < 0 || v >= static_cast<long long>(n))
          throw Invalid_mesh_error(origin_.where_face(f) + "face " + std::to_string(f) + " refers to vertex " +
                                   std::to_string(v) + " but the mesh has " + std::to_string(n) + " vertices");
      }
      if(face.size() != 3 && non_triangles++ == 0) first_non_triangle = f;
    }
    if(non_triangles > 0)
      throw Invalid_mesh_error(origin_.where_face(first_non_triangle) + std::to_string(non_triangles) + " of " +
                               std::to_string(nf) + " faces are not triangles (face " +
                               std::to_string(first_non_triangle) + " has " +
                               std::to_string(polygons[first_non_triangle].size()) +
                               " vertices); triangulate the mesh first");
    if(n > std::size_t(std::numeric_limits<int>::max()) || nf > std::size_t(std::numeric_limits<int>::max() / 3))
      throw Invalid_mesh_error(label + ": the mesh is too large (" + std::to_string(n) + " vertices, " +
                               std::to_string(nf) + " faces)");
    triangles_.resize(nf);
    for(std::size_t f = 0; f < nf; ++f)
    {
      const auto& t = polygons[f];
      for(int c = 0; c < 3; ++c) triangles_[f][std::size_t(c)] = int(t[std::size_t(c)]);
      if(t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        throw Invalid_mesh_error(origin_.where_face(f) + "face " + std::to_string(f) +
                                 " is degenerate: it repeats vertex " +
                                 std::to_string(internal::soup_index(t[0] == t[1] || t[0] == t[2] ? t[0] : t[1])));
    }
  }

  std::size_t number_of_vertices() const { return points_.size(); }
  std::size_t number_of_triangles() const { return triangles_.size(); }
  /// Point i: the position of vertex i.
  const std::vector<Point>& points() const { return points_; }
  /// The faces, as indices of points, in the order given.
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// Where the soup comes from (its name in messages, and the lines of a text file).
  const Triangle_soup_origin& origin() const { return origin_; }

private:
  std::vector<Point> points_;
  std::vector<Triangle> triangles_;
  Triangle_soup_origin origin_;
};

namespace internal {

/// The flat mesh of a soup, checked as a surface with the requirements `req` (vertex i is point
/// i, face f is triangle f), and its orientation checked (a soup, unlike a halfedge mesh, can
/// traverse an edge twice in the same direction). Messages name the soup's origin, or `name`
/// when the origin has the default name. `vertices_out`, when given, receives 0, 1, ..., n - 1.
inline Indexed_mesh make_soup_indexed_mesh(const Triangle_soup& soup, const Mesh_requirements& req,
                                           const std::string& name = "mesh",
                                           std::vector<std::size_t>* vertices_out = nullptr)
{
  const std::string& label = soup.origin().name == Triangle_soup_origin().name ? name : soup.origin().name;
  Indexed_mesh m;
  const std::size_t n = soup.number_of_vertices(), nf = soup.number_of_triangles();
  m.points.resize(Eigen::Index(n), 3);
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < 3; ++c) m.points(Eigen::Index(i), c) = soup.points()[i][std::size_t(c)];
  m.triangles.resize(Eigen::Index(nf), 3);
  for(std::size_t f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c) m.triangles(Eigen::Index(f), c) = soup.triangles()[f][std::size_t(c)];
  finalize_indexed_mesh(m, req, label);
  check_soup_orientation(m, mesh_label(label));
  if(vertices_out)
  {
    vertices_out->resize(n);
    for(std::size_t i = 0; i < n; ++i) (*vertices_out)[i] = i;
  }
  return m;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Checks that a triangle soup is a mesh the package can match: at least one vertex and one
/// face, finite coordinates, faces of three distinct vertices in range and of non-zero area, a
/// manifold (every edge in at most two faces, one fan of faces around every vertex),
/// consistently oriented surface with no isolated vertex and one connected component.
///
/// \tparam PointRange, PolygonRange as for Triangle_soup
/// \throws Invalid_mesh_error naming the first problem, the vertex or face, and where they come
///   from (`origin`: a name, and the lines of a text file)
template <typename PointRange, typename PolygonRange>
void check_triangle_soup(const PointRange& points, const PolygonRange& polygons,
                         const Triangle_soup_origin& origin = Triangle_soup_origin())
{
  internal::Mesh_requirements req;
  req.allow_isolated_vertices = false;
  req.allow_several_components = false;
  internal::make_soup_indexed_mesh(Triangle_soup(points, polygons, origin), req, origin.name);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Builds `mesh` (emptied first) from a triangle soup checked with check_triangle_soup(): vertex
/// i of `mesh` (in the order of `vertices(mesh)`) is `points[i]`, face f is `polygons[f]`, so
/// maps computed on `mesh` are maps between the soup's point indices.
///
/// \tparam PolygonMesh a model of `MutableFaceGraph` whose points can be built from the values of
///   `points`
/// \throws Invalid_mesh_error as check_triangle_soup()
template <typename PointRange, typename PolygonRange, typename PolygonMesh>
void triangle_soup_to_mesh(const PointRange& points, const PolygonRange& polygons, PolygonMesh& mesh,
                           const Triangle_soup_origin& origin = Triangle_soup_origin())
{
  check_triangle_soup(points, polygons, origin);
  clear(mesh);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if(std::size_t(num_vertices(mesh)) != points.size() || std::size_t(num_faces(mesh)) != polygons.size())
    throw Invalid_mesh_error(origin.name + ": the faces do not form a valid surface mesh");
  // Vertex i must be point i: maps refer to the soup's numbering.
  const auto vpm = get(CGAL::vertex_point, mesh);
  std::size_t i = 0;
  for(auto v : vertices(mesh))
  {
    const auto& p = get(vpm, v);
    const auto& q = points[i++];
    if(double(p.x()) != double(q[0]) || double(p.y()) != double(q[1]) || double(p.z()) != double(q[2]))
      throw Invalid_mesh_error(origin.name + ": the vertex order changed while building the mesh");
  }
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_TRIANGLE_SOUP_H
