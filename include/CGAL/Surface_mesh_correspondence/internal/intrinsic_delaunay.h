// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Intrinsic triangulations described by edge lengths only, and the edge-flip algorithm that makes
// them intrinsic Delaunay:
//   M. Fisher, B. Springborn, A. I. Bobenko, P. Schroeder, "An algorithm for the construction of
//   intrinsic Delaunay triangulations with applications to digital geometry processing", 2007;
//   A. I. Bobenko, B. A. Springborn, "A discrete Laplace-Beltrami operator for simplicial
//   surfaces", 2007.
// The surface (a piecewise-flat metric) never changes: a flip replaces the diagonal of the
// quadrilateral made of the two triangles of an edge by the other diagonal, whose length is found
// by unfolding the two triangles into the plane. After the flips, every interior edge satisfies
// the Delaunay condition (its two opposite angles sum to at most pi), so every cotangent weight
// is non-negative. Triangulations are Delta-complexes: after flips two edges may join the same
// two vertices, and a triangle may use a vertex twice; the halfedge structure below handles that.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INTRINSIC_DELAUNAY_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INTRINSIC_DELAUNAY_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Area of a triangle with side lengths a, b, c (Kahan's numerically stable form of Heron's
/// formula); 0 when the lengths violate the triangle inequality.
inline double triangle_area_from_lengths(double a, double b, double c)
{
  // Sort a >= b >= c.
  if(a < b) std::swap(a, b);
  if(b < c) std::swap(b, c);
  if(a < b) std::swap(a, b);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p > 0 ? 0.25 * std::sqrt(p) : 0.0;
}

/// Cotangent of the angle opposite the side of length a in the triangle with sides a, b, c:
/// cot = (b^2 + c^2 - a^2) / (4 area).
inline double cotangent_from_lengths(double a, double b, double c)
{
  return (b * b + c * c - a * a) / (4.0 * triangle_area_from_lengths(a, b, c));
}

/// A triangulation given by its combinatorics and edge lengths. Halfedge h = 3 f + c is the c-th
/// halfedge of triangle f; it goes from origin[h] to origin[next(h)], and the triangle is
/// (origin[3f], origin[3f+1], origin[3f+2]), counter-clockwise.
struct Intrinsic_triangulation
{
  int number_of_vertices = 0;
  std::vector<int> origin;     ///< per halfedge: its source vertex
  std::vector<int> twin;       ///< per halfedge: the opposite halfedge, -1 on the boundary
  std::vector<double> length;  ///< per halfedge: the length of its edge (equal on both twins)

  int number_of_halfedges() const { return static_cast<int>(origin.size()); }
  int number_of_triangles() const { return number_of_halfedges() / 3; }
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  static int face(int h) { return h / 3; }
  int target(int h) const { return origin[next(h)]; }

  /// Cotangent of the angle opposite halfedge h in its triangle.
  double cotangent_opposite(int h) const
  {
    return cotangent_from_lengths(length[h], length[next(h)], length[prev(h)]);
  }
  /// Area of triangle f.
  double triangle_area(int f) const
  {
    return triangle_area_from_lengths(length[3 * f], length[3 * f + 1], length[3 * f + 2]);
  }
  /// The cotangent weight of the edge of h: (cot alpha + cot beta) / 2 with alpha, beta the
  /// angles opposite the edge (only alpha on the boundary).
  double cotangent_weight(int h) const
  {
    double w = cotangent_opposite(h);
    if(twin[h] >= 0) w += cotangent_opposite(twin[h]);
    return 0.5 * w;
  }
};

/// The triangulation of `m` with its Euclidean edge lengths.
/// \pre `m` passed `finalize_indexed_mesh()` (manifold, triangles only).
inline Intrinsic_triangulation make_intrinsic_triangulation(const Indexed_mesh& m)
{
  Intrinsic_triangulation t;
  const int nf = m.number_of_triangles();
  t.number_of_vertices = m.number_of_vertices();
  t.origin.resize(3 * static_cast<std::size_t>(nf));
  t.twin.assign(3 * static_cast<std::size_t>(nf), -1);
  t.length.resize(3 * static_cast<std::size_t>(nf));
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int h = 3 * f + c;
      const int a = m.triangles(f, c), b = m.triangles(f, (c + 1) % 3);
      t.origin[h] = a;
      t.length[h] = (m.point(b) - m.point(a)).norm();
    }
  // Twins: the halfedge b -> a is in a triangle incident to b (manifold: at most one).
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int h = 3 * f + c;
      if(t.twin[h] >= 0) continue;
      const int a = t.origin[h], b = m.triangles(f, (c + 1) % 3);
      for(int k = m.triangle_offsets[b]; k < m.triangle_offsets[b + 1]; ++k)
      {
        const int g = m.incident_triangles[k];
        if(g == f) continue;
        int cb = 0;
        while(m.triangles(g, cb) != b) ++cb;
        if(m.triangles(g, (cb + 1) % 3) == a)
        {
          t.twin[h] = 3 * g + cb;
          t.twin[3 * g + cb] = h;
          break;
        }
      }
    }
  return t;
}

/// Flips the interior edge of halfedge h (whose two triangles must differ). Triangles
/// f0 = (i, j, k) of h = i -> j and f1 = (j, i, l) of its twin become (k, l, j) and (l, k, i);
/// the new edge k - l is stored at halfedges 3 f0 and 3 f1.
inline void flip_edge(Intrinsic_triangulation& t, int h)
{
  typedef Intrinsic_triangulation T;
  const int h0 = h, h1 = T::next(h0), h2 = T::next(h1);
  const int t0 = t.twin[h0], t1 = T::next(t0), t2 = T::next(t1);
  const int f0 = T::face(h0), f1 = T::face(t0);
  const int k = t.origin[h2], l = t.origin[t2];
  const double lij = t.length[h0], ljk = t.length[h1], lki = t.length[h2];
  const double lil = t.length[t1], llj = t.length[t2];

  // Unfold: i at the origin, j on the positive x axis, k above, l below.
  const double xk = (lij * lij + lki * lki - ljk * ljk) / (2 * lij);
  const double yk = 2 * triangle_area_from_lengths(lij, ljk, lki) / lij;
  const double xl = (lij * lij + lil * lil - llj * llj) / (2 * lij);
  const double yl = -2 * triangle_area_from_lengths(lij, llj, lil) / lij;
  const double lkl = std::hypot(xk - xl, yk - yl);

  // Saved halfedges that move: (origin, twin, length) of h1 (j->k), h2 (k->i), t1 (i->l),
  // t2 (l->j), and their new positions.
  const int moved_old[4] = {h1, h2, t1, t2};
  const int moved_new[4] = {3 * f0 + 2, 3 * f1 + 1, 3 * f1 + 2, 3 * f0 + 1};
  int saved_origin[4], saved_twin[4];
  double saved_length[4];
  for(int q = 0; q < 4; ++q)
  {
    saved_origin[q] = t.origin[moved_old[q]];
    saved_twin[q] = t.twin[moved_old[q]];
    saved_length[q] = t.length[moved_old[q]];
  }
  auto remap = [&](int old) {
    if(old < 0) return old;
    for(int q = 0; q < 4; ++q)
      if(moved_old[q] == old) return moved_new[q];
    return old;  // h0 and t0 are never the twin of a moved halfedge
  };
  // The new edge k - l.
  const int a = 3 * f0, b = 3 * f1;
  t.origin[a] = k;
  t.origin[b] = l;
  t.twin[a] = b;
  t.twin[b] = a;
  t.length[a] = t.length[b] = lkl;
  for(int q = 0; q < 4; ++q)
  {
    const int p = moved_new[q];
    t.origin[p] = saved_origin[q];
    t.length[p] = saved_length[q];
  }
  for(int q = 0; q < 4; ++q)
  {
    const int p = moved_new[q];
    const int tw = remap(saved_twin[q]);
    t.twin[p] = tw;
    if(tw >= 0) t.twin[tw] = p;
  }
}

/// Whether the interior edge of h violates the Delaunay condition: cot alpha + cot beta < -tol.
inline bool is_non_delaunay(const Intrinsic_triangulation& t, int h, double tolerance)
{
  if(t.twin[h] < 0) return false;
  if(Intrinsic_triangulation::face(h) == Intrinsic_triangulation::face(t.twin[h])) return false;
  return t.cotangent_opposite(h) + t.cotangent_opposite(t.twin[h]) < -tolerance;
}

/// Flips edges until every interior edge is (intrinsic) Delaunay, i.e. every cotangent weight is
/// at least -tolerance / 2 (the tolerance is on the dimensionless cot alpha + cot beta and keeps
/// rounding from cycling through co-circular configurations). Boundary edges are never flipped.
/// Returns the number of flips. Throws Numerical_error if the flips do not terminate (they do in
/// exact arithmetic: Bobenko and Springborn 2007).
inline int make_intrinsic_delaunay(Intrinsic_triangulation& t, double tolerance = 1e-12)
{
  const int nh = t.number_of_halfedges();
  std::vector<int> stack;
  std::vector<char> queued(static_cast<std::size_t>(nh), 0);
  stack.reserve(static_cast<std::size_t>(nh) / 2);
  for(int h = 0; h < nh; ++h)
    if(t.twin[h] > h)
    {
      stack.push_back(h);
      queued[h] = 1;
    }
  const long long max_flips = 100LL * nh + 1000;
  long long flips = 0;
  while(!stack.empty())
  {
    const int h = stack.back();
    stack.pop_back();
    queued[h] = 0;
    if(!is_non_delaunay(t, h, tolerance)) continue;
    if(++flips > max_flips)
      throw Numerical_error("intrinsic Delaunay flips do not terminate (more than " +
                            std::to_string(max_flips) + " flips)");
    const int f0 = Intrinsic_triangulation::face(h), f1 = Intrinsic_triangulation::face(t.twin[h]);
    flip_edge(t, h);
    // The four outer edges of the quadrilateral may have become non-Delaunay.
    const int outer[4] = {3 * f0 + 1, 3 * f0 + 2, 3 * f1 + 1, 3 * f1 + 2};
    for(int p : outer)
    {
      if(t.twin[p] < 0 || queued[p] || queued[t.twin[p]]) continue;
      stack.push_back(p);
      queued[p] = 1;
    }
  }
  return static_cast<int>(flips);
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INTRINSIC_DELAUNAY_H
