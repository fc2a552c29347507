// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The tufted cover of a triangle mesh and the Laplacian built on it, after Sharp and Crane, "A
// Laplacian for Nonmanifold Triangle Meshes" (SGP 2020): a Laplace-Beltrami operator that is valid
// on meshes with edges shared by more than two triangles (fins, touching sheets) and pinched
// vertices, where a halfedge structure cannot be built.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TUFTED_COVER_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TUFTED_COVER_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/intrinsic_delaunay.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// The tufted cover of `m` as an intrinsic triangulation with its Euclidean edge lengths: every
/// triangle f twice, once per side (triangle 2f is f as given, triangle 2f + 1 is f reversed),
/// and around each edge of `m` the incident triangles ordered by their angle about the edge, the
/// two sides that face each wedge between consecutive triangles glued together. A boundary
/// edge's one triangle is glued to its own other side. The cover is closed and every edge of it
/// has exactly two sides, whatever the number of triangles around the edges of `m` (a fin, two
/// sheets touching along an edge); its vertices are those of `m`. On a closed manifold mesh it is
/// two copies of the mesh, one per orientation (Sharp and Crane 2020, section 4).
/// \pre `m` has triangles of three distinct vertices (finalize_indexed_mesh()); a triangle of zero
///   area takes the place of its third vertex's projection on each of its edges.
inline Intrinsic_triangulation tufted_cover(const Indexed_mesh& m)
{
  const int nf = m.number_of_triangles();
  Intrinsic_triangulation t;
  t.number_of_vertices = m.number_of_vertices();
  t.origin.resize(6 * std::size_t(nf));
  t.twin.assign(6 * std::size_t(nf), -1);
  t.length.resize(6 * std::size_t(nf));
  // The side halfedge of corner c of f: on side 0, from corner c to corner c + 1; on side 1 (the
  // triangle (a0, a2, a1)), the reversed edge, at position 2 - c.
  auto side_halfedge = [](int f, int side, int c) { return side == 0 ? 6 * f + c : 6 * f + 3 + (2 - c); };
  std::vector<std::array<int, 4> > edges;  // (lower vertex, upper vertex, triangle, corner)
  edges.reserve(3 * std::size_t(nf));
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int a = m.triangles(f, c), b = m.triangles(f, (c + 1) % 3);
      const double length = (m.point(b) - m.point(a)).norm();
      const int h0 = side_halfedge(f, 0, c), h1 = side_halfedge(f, 1, c);
      t.origin[std::size_t(h0)] = a;
      t.origin[std::size_t(h1)] = b;
      t.length[std::size_t(h0)] = t.length[std::size_t(h1)] = length;
      edges.push_back({{std::min(a, b), std::max(a, b), f, c}});
    }
  std::sort(edges.begin(), edges.end());
  struct Sheet
  {
    double angle;
    int up, down;  // the halfedges of the sides facing increasing and decreasing angles
  };
  std::vector<Sheet> sheets;
  std::vector<Eigen::Vector3d> directions;
  for(std::size_t begin = 0; begin < edges.size();)
  {
    std::size_t end = begin;
    while(end < edges.size() && edges[end][0] == edges[begin][0] && edges[end][1] == edges[begin][1]) ++end;
    const int i = edges[begin][0], j = edges[begin][1];
    const Eigen::Vector3d pi = m.point(i);
    const Eigen::Vector3d e = (m.point(j) - pi).normalized();
    sheets.clear();
    // The direction of each triangle about the edge: its third vertex, off the edge's line. The
    // angles are measured from the triangle farthest from the line (a triangle of zero area, its
    // third vertex on the line, has no direction).
    directions.clear();
    std::size_t reference = begin;
    for(std::size_t q = begin; q < end; ++q)
    {
      Eigen::Vector3d d = m.point(m.triangles(edges[q][2], (edges[q][3] + 2) % 3)) - pi;
      d -= d.dot(e) * e;
      directions.push_back(d);
      if(d.squaredNorm() > directions[reference - begin].squaredNorm()) reference = q;
    }
    const Eigen::Vector3d u = directions[reference - begin].normalized();
    const Eigen::Vector3d w = e.cross(u);
    for(std::size_t q = begin; q < end; ++q)
    {
      const int f = edges[q][2], c = edges[q][3];
      const Eigen::Vector3d& d = directions[q - begin];
      const double angle = std::atan2(d.dot(w), d.dot(u));
      // Side 0 traverses i -> j when corner c is i; its normal is then e x d, which points to
      // increasing angles.
      const bool forward = m.triangles(f, c) == i;
      const int h0 = side_halfedge(f, 0, c), h1 = side_halfedge(f, 1, c);
      sheets.push_back({angle, forward ? h0 : h1, forward ? h1 : h0});
    }
    std::stable_sort(sheets.begin(), sheets.end(), [](const Sheet& a, const Sheet& b) { return a.angle < b.angle; });
    // The wedge between consecutive triangles (the last and the first close the turn).
    for(std::size_t q = 0; q < sheets.size(); ++q)
    {
      const Sheet& a = sheets[q];
      const Sheet& b = sheets[(q + 1) % sheets.size()];
      t.twin[std::size_t(a.up)] = b.down;
      t.twin[std::size_t(b.down)] = a.up;
    }
    begin = end;
  }
  return t;
}

/// Intrinsic mollification (Sharp and Crane 2020, section 4.5): adds the same length epsilon to
/// every edge of `t`, the smallest that gives every triangle a margin of at least `delta` in each
/// of its triangle inequalities (l_a + l_b - l_c >= delta), and returns epsilon (0 when every
/// triangle already has the margin). Triangles of zero or nearly zero area (collinear vertices,
/// slivers) then get a small positive area and finite cotangents, while the other triangles
/// change by about epsilon / their edge lengths.
inline double mollify_edge_lengths(Intrinsic_triangulation& t, double delta)
{
  double epsilon = 0;
  for(int f = 0; f < t.number_of_triangles(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const double a = t.length[std::size_t(3 * f + c)], b = t.length[std::size_t(3 * f + (c + 1) % 3)],
                   third = t.length[std::size_t(3 * f + (c + 2) % 3)];
      epsilon = std::max(epsilon, delta - (a + b - third));
    }
  if(epsilon > 0)
    for(double& l : t.length) l += epsilon;
  return epsilon;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TUFTED_COVER_H
