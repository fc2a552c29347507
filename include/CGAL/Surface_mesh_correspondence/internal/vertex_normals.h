// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Area-weighted vertex normals of an Indexed_mesh, oriented by the mesh's triangle orientation.
// On a non-manifold mesh, a vertex's normal comes from its triangles that have an orientation
// (oriented_triangles(): not on an edge of a fin or of touching sheets), and from all its triangles
// only when none has one (the tip of a fin).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_VERTEX_NORMALS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_VERTEX_NORMALS_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Unit vertex normals (n x 3, row v = normal of vertex v): the sum of the normals of the incident
/// triangles weighted by their areas, i.e. the normalised sum of the cross products
/// \f$ (p_b - p_a) \times (p_c - p_a) \f$ of the incident triangles (a, b, c). The normals point
/// to the side from which the triangles are seen counter-clockwise (outwards for an outward
/// oriented closed mesh). A vertex whose weighted sum vanishes (its fan folds back onto itself)
/// or that belongs to no triangle gets the zero vector.
inline Indexed_mesh::Points vertex_normals(const Indexed_mesh& m)
{
  const int n = m.number_of_vertices();
  Indexed_mesh::Points normals = Indexed_mesh::Points::Zero(n, 3);
  std::vector<char> oriented;
  if(!m.is_manifold()) oriented = oriented_triangles(m);
  // Whether the normal of v sums only oriented triangles: v has at least one.
  auto only_oriented = [&](int v) {
    if(oriented.empty()) return false;
    for(int k = m.triangle_offsets[v]; k < m.triangle_offsets[v + 1]; ++k)
      if(oriented[std::size_t(m.incident_triangles[k])]) return true;
    return false;
  };
  std::vector<char> restricted;  // empty when every triangle is oriented
  if(!oriented.empty())
  {
    restricted.resize(std::size_t(n));
    for(int v = 0; v < n; ++v) restricted[std::size_t(v)] = only_oriented(v);
  }
  for(int f = 0; f < m.number_of_triangles(); ++f)
  {
    const int a = m.triangles(f, 0), b = m.triangles(f, 1), c = m.triangles(f, 2);
    const Eigen::RowVector3d pa = m.points.row(a);
    const Eigen::RowVector3d twice_area_normal =
        (m.points.row(b) - pa).cross(m.points.row(c) - pa);
    const bool face_oriented = oriented.empty() || oriented[std::size_t(f)];
    for(int corner : {a, b, c})
      if(face_oriented || !restricted[std::size_t(corner)]) normals.row(corner) += twice_area_normal;
  }
  for(int v = 0; v < n; ++v)
  {
    const double length = normals.row(v).norm();
    // Relative test: the sum is tiny compared with the incident triangle areas when it cancels.
    double scale = 0;
    for(int k = m.triangle_offsets[v]; k < m.triangle_offsets[v + 1]; ++k)
      if(restricted.empty() || !restricted[std::size_t(v)] || oriented[std::size_t(m.incident_triangles[k])])
        scale += 2 * m.triangle_areas[m.incident_triangles[k]];
    if(length > 1e-12 * scale && length > 0)
      normals.row(v) /= length;
    else
      normals.row(v).setZero();
  }
  return normals;
}

/// How the image of triangle `t` of `source` under `map` lies on `target`: -1 when two of its
/// vertices have the same image, 1 when the image triangle has the orientation of `target` (its
/// normal agrees with the sum of the target's vertex normals `target_normals` at its corners), 0
/// when it is reversed (a mirror map reverses every triangle).
inline int image_orientation(const Indexed_mesh& source, const Indexed_mesh& target,
                             const Indexed_mesh::Points& target_normals, const std::vector<int>& map, int t)
{
  const int a = map[std::size_t(source.triangles(t, 0))], b = map[std::size_t(source.triangles(t, 1))],
            c = map[std::size_t(source.triangles(t, 2))];
  if(a == b || b == c || a == c) return -1;
  const Eigen::Vector3d normal = (target.point(b) - target.point(a)).cross(target.point(c) - target.point(a));
  const Eigen::Vector3d reference = (target_normals.row(a) + target_normals.row(b) + target_normals.row(c)).transpose();
  return normal.dot(reference) > 0 ? 1 : 0;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_VERTEX_NORMALS_H
