// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fast marching on triangle meshes, after R. Kimmel and J. A. Sethian, "Computing geodesic paths
// on manifolds", PNAS 95(15), 1998.
//
// The distance T solves |grad T| = 1 with T = 0 at the sources. Vertices are accepted in
// increasing order of T (Dijkstra-like, with a 4-ary heap: a shallower tree than a binary heap,
// 14% faster full runs on 5000-vertex TOSCA_r meshes). When a vertex is accepted, its neighbours
// get
//   - the one-point update  T(C) <= T(X) + |CX| along every mesh edge (C, X), and
//   - the two-point update of every triangle (C; A, B) whose supports A and B are both accepted.
// Two update rules (Fast_marching_update):
//   - planar (the paper): T is linear in the triangle with |grad T| = 1 (a planar wave front).
//     With b = |CA|, a = |CB|, theta the angle at C, T(A) <= T(B), u = T(B) - T(A), t = T(C) - T(A),
//       (a^2 + b^2 - 2ab cos theta) t^2 + 2 b u (a cos theta - b) t + b^2 (u^2 - a^2 sin^2 theta) = 0,
//     the larger root t is accepted when the wave comes from inside the triangle (upwind
//     condition): the propagation direction -grad T at C lies in the cone spanned by CA and CB,
//       t a - (t - u) b cos theta >= 0   and   (t - u) b - t a cos theta >= 0   (then t >= u),
//     which is the paper's  u < t,  a cos theta < b (t - u) / t < a / cos theta.
//   - circular (the default): the same scheme with a circular wave front, i.e. a virtual point
//     source S in the plane of the triangle with |SA| = T(A), |SB| = T(B); T(C) = |SC| when SC
//     crosses AB and |SC| >= max(T(A), T(B)). Exact for one source on a flat mesh, and far more
//     accurate at short range (doc/geodesics.md).
// Obtuse angles break the monotonicity of the scheme (the supporting vertices of C may be accepted
// after C). As in the paper, an obtuse angle at C in triangle (C, A, B) is split: the neighbouring
// triangles beyond the edge AB are unfolded into the plane of (C, A, B) until a vertex V appears
// in the "section" of C (the directions making an angle of at most 90 degrees with both CA and CB);
// the virtual triangles (C; A, V) and (C; V, B), both acute at C, are added to the two-point
// updates, and so is the one-point update along the unfolded segment CV (a path on the surface:
// it crosses every unfolded edge). The obtuse triangle itself is kept, with its upwind and
// causality checks. When no such vertex is found within `max_unfolding_steps` unfoldings (or the
// unfolding reaches a boundary edge), only the checked obtuse triangle is used (documented
// fallback; counted in Fast_marching_geometry::number_of_fallbacks).
//
// Fast_marching_geometry precomputes, for every vertex X, its corners (the two other vertices of
// each incident triangle and their corner geometry) and the list of virtual triangles in which X
// is a support, so that accepting X reads contiguous arrays. Fast_marching_workspace holds the
// per-run arrays and resets only the vertices touched by the previous run: thousands of
// (truncated) runs allocate nothing.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FAST_MARCHING_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FAST_MARCHING_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Two-point update of T(C) in the triangle (C; X, Y) (see the file comment). `tx`, `ty`: the
/// accepted values at the supports; `lx` = |CX|, `ly` = |CY|; `cos_angle` = cos of the angle XCY.
/// Returns +infinity when the planar front does not reach C from inside the triangle.
inline double fast_marching_two_point_update(double tx, double ty, double lx, double ly, double cos_angle)
{
  // A = the support with the smaller value.
  double ta, b, a, u;
  if(tx <= ty)
  {
    ta = tx;
    u = ty - tx;
    b = lx;
    a = ly;
  }
  else
  {
    ta = ty;
    u = tx - ty;
    b = ly;
    a = lx;
  }
  const double sin2 = 1.0 - cos_angle * cos_angle;
  const double qa = a * a + b * b - 2.0 * a * b * cos_angle;  // = |AB|^2
  const double qb = 2.0 * b * u * (a * cos_angle - b);
  const double qc = b * b * (u * u - a * a * sin2);
  const double disc = qb * qb - 4.0 * qa * qc;
  if(!(disc >= 0)) return std::numeric_limits<double>::infinity();
  const double t = (-qb + std::sqrt(disc)) / (2.0 * qa);
  if(!(t > u)) return std::numeric_limits<double>::infinity();
  // Relative tolerance: a front arriving exactly along CA or CB is upwind.
  const double eps = 1e-12 * t * (a + b);
  if(t * a - (t - u) * b * cos_angle < -eps || (t - u) * b - t * a * cos_angle < -eps)
    return std::numeric_limits<double>::infinity();
  return ta + t;
}

/// Two-point update of T(C) in the triangle (C; X, Y) with a circular wave front (a point source,
/// the variant of Novotni and Klein 2002): the virtual source S lies in the plane of the triangle,
/// on the other side of XY than C, with |SX| = tx and |SY| = ty; then T(C) = |SC| when the
/// segment SC crosses the edge XY (upwind) and |SC| >= max(tx, ty) (causality), +infinity
/// otherwise. Exact for one source on a flat mesh; the same inputs as the planar update.
/// `sin_angle`, `edge_length` = |XY| and its inverse are precomputed by the caller.
inline double fast_marching_circular_update(double tx, double ty, double lx, double ly, double cos_angle,
                                            double sin_angle, double edge_length, double inverse_edge_length)
{
  // C at the origin, X = (lx, 0), Y = ly (cos, sin).
  const double xx = lx, xy = 0.0, yx = ly * cos_angle, yy = ly * sin_angle;
  const double L = edge_length;
  const double ux = (yx - xx) * inverse_edge_length, uy = (yy - xy) * inverse_edge_length;
  // Along XY from X: s = (tx^2 - ty^2 + L^2) / (2L), without cancellation.
  const double s = 0.5 * ((tx - ty) * (tx + ty) * inverse_edge_length + L);
  const double h2 = (tx - s) * (tx + s);
  if(!(h2 >= 0)) return std::numeric_limits<double>::infinity();
  const double h = std::sqrt(h2);
  // The normal to XY pointing away from C (C is at the origin, on the left of X->Y since the
  // angle XCY is in (0, pi)): the right-hand normal.
  const double nx = uy, ny = -ux;
  const double sx = xx + s * ux + h * nx, sy = xy + s * uy + h * ny;
  // Upwind: the direction C->S lies in the cone spanned by CX and CY (with a relative tolerance:
  // a source seen exactly along CX or CY, e.g. the unfolded vertex itself, is upwind).
  const double t = std::sqrt(sx * sx + sy * sy);
  if(sy < -1e-12 * t || sx * yy - sy * yx < -1e-12 * t * ly) return std::numeric_limits<double>::infinity();
  if(t < std::max(tx, ty)) return std::numeric_limits<double>::infinity();
  return t;
}

/// Same, computing sin_angle and |XY| from the other inputs.
inline double fast_marching_circular_update(double tx, double ty, double lx, double ly, double cos_angle)
{
  const double sin_angle = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle));
  const double edge = std::sqrt(std::max(0.0, lx * lx + ly * ly - 2.0 * lx * ly * cos_angle));
  return fast_marching_circular_update(tx, ty, lx, ly, cos_angle, sin_angle, edge, 1.0 / edge);
}

/// The two-point update rule of fast marching.
enum class Fast_marching_update
{
  planar,   ///< Kimmel-Sethian: linear T in the triangle, |grad T| = 1
  circular  ///< virtual point source in the plane of the triangle
};

/// Precomputed update stencils of fast marching on one mesh (immutable, shareable by threads).
///
/// Mesh triangles are visited from the accepted vertex through `vertex_corners`: for the corner
/// of X in triangle (X, A, B), if exactly one of A and B is accepted the other one is updated,
/// with the precomputed geometry of its corner. Virtual triangles (from unfolding obtuse angles)
/// and the one-point updates along unfolded segments are listed per support in `entries`.
struct Fast_marching_geometry
{
  /// Geometry of corner c of triangle f (vertex C = triangles(f, c), next N = triangles(f, c+1),
  /// previous P = triangles(f, c+2)).
  struct Corner
  {
    double length_next;  ///< |C N|
    double length_prev;  ///< |C P|
    double cos_angle;    ///< cos of the angle N C P
    double sin_angle;
    double edge_length;          ///< |N P|
    double inverse_edge_length;  ///< 1 / |N P|
  };
  /// A virtual triangle (target; X, other) seen from its support X, or a one-point update.
  struct Entry
  {
    int target;           ///< C, the vertex being updated
    int other;            ///< Y, the other support; -1 for a one-point update along the
                          ///< unfolded segment XC (of length `length`)
    double length;        ///< |C X| (X = the vertex owning this entry)
    double other_length;  ///< |C Y|
    double cos_angle;     ///< cos of the angle X C Y
    double sin_angle;     ///< sin of the angle X C Y
    double edge_length;   ///< |X Y|
    double inverse_edge_length;
  };

  /// The corner of a vertex X in one of its triangles (X, A, B), A next and B previous.
  struct Incident_corner
  {
    int next;         ///< A
    int previous;     ///< B
    int next_corner;  ///< index of A's corner in `corners` (its next vertex is B, previous X)
    int previous_corner;  ///< index of B's corner (its next vertex is X, previous A)
  };

  const Indexed_mesh* mesh = nullptr;
  Edge_length_graph graph;               ///< one-point updates along edges
  std::vector<Corner> corners;           ///< 3 per triangle, index 3 f + c
  std::vector<int> corner_offsets;       ///< corners of vertex v: vertex_corners[corner_offsets[v] ..)
  std::vector<Incident_corner> vertex_corners;
  std::vector<int> entry_offsets;        ///< virtual entries of X: entries[entry_offsets[X] .. entry_offsets[X+1])
  std::vector<Entry> entries;
  int number_of_obtuse_angles = 0;       ///< obtuse corners found
  int number_of_fallbacks = 0;           ///< obtuse corners whose unfolding failed (kept as they are)
  Fast_marching_update update_rule = Fast_marching_update::circular;

  Fast_marching_geometry() = default;
  explicit Fast_marching_geometry(const Indexed_mesh& m,
                                  Fast_marching_update rule = Fast_marching_update::circular,
                                  int max_unfolding_steps = 20)
  {
    build(m, rule, max_unfolding_steps);
  }

  int number_of_vertices() const { return mesh->number_of_vertices(); }
  std::size_t memory_bytes() const
  {
    return corners.size() * sizeof(Corner) + vertex_corners.size() * sizeof(Incident_corner) +
           (corner_offsets.size() + entry_offsets.size()) * sizeof(int) +
           entries.size() * sizeof(Entry) + graph.lengths.size() * sizeof(double);
  }

  void build(const Indexed_mesh& m, Fast_marching_update rule = Fast_marching_update::circular,
             int max_unfolding_steps = 20)
  {
    mesh = &m;
    update_rule = rule;
    graph = Edge_length_graph(m);
    const int n = m.number_of_vertices();
    const int nf = m.number_of_triangles();
    number_of_obtuse_angles = 0;
    number_of_fallbacks = 0;

    // Corners of every vertex, in the order of its incident triangles.
    corner_offsets.assign(m.triangle_offsets.begin(), m.triangle_offsets.end());
    vertex_corners.resize(m.incident_triangles.size());
    for(int v = 0; v < n; ++v)
      for(int k = m.triangle_offsets[v]; k < m.triangle_offsets[v + 1]; ++k)
      {
        const int f = m.incident_triangles[k];
        int c = 0;
        while(m.triangles(f, c) != v) ++c;
        const int cn = (c + 1) % 3, cp = (c + 2) % 3;
        vertex_corners[k] = Incident_corner{m.triangles(f, cn), m.triangles(f, cp), 3 * f + cn, 3 * f + cp};
      }

    struct Raw
    {
      int owner;
      Entry e;
    };
    std::vector<Raw> raw;
    auto add_virtual = [&](int c, int x, int y, double lx, double ly, double cos_angle) {
      const double sin_angle = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle));
      const double edge = std::sqrt(std::max(0.0, lx * lx + ly * ly - 2.0 * lx * ly * cos_angle));
      raw.push_back(Raw{x, Entry{c, y, lx, ly, cos_angle, sin_angle, edge, 1.0 / edge}});
      raw.push_back(Raw{y, Entry{c, x, ly, lx, cos_angle, sin_angle, edge, 1.0 / edge}});
    };

    corners.resize(static_cast<std::size_t>(nf) * 3);
    for(int f = 0; f < nf; ++f)
      for(int corner = 0; corner < 3; ++corner)
      {
        const int c = m.triangles(f, corner), a = m.triangles(f, (corner + 1) % 3),
                  b = m.triangles(f, (corner + 2) % 3);
        const Eigen::Vector3d ca = m.point(a) - m.point(c), cb = m.point(b) - m.point(c);
        const double la = ca.norm(), lb = cb.norm();
        const double cos_angle = std::max(-1.0, std::min(1.0, ca.dot(cb) / (la * lb)));
        Corner& k = corners[3 * static_cast<std::size_t>(f) + corner];
        k.length_next = la;
        k.length_prev = lb;
        k.cos_angle = cos_angle;
        k.sin_angle = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle));
        k.edge_length = (m.point(a) - m.point(b)).norm();
        k.inverse_edge_length = 1.0 / k.edge_length;
        if(cos_angle >= 0) continue;
        // Obtuse: the triangle itself stays (its update is checked for upwindness and
        // causality, and it helps where V is accepted after C); the unfolding adds virtual ones.
        ++number_of_obtuse_angles;
        int v = -1;
        Eigen::Vector2d pv;
        if(unfold(m, f, c, a, b, la, lb, cos_angle, max_unfolding_steps, v, pv))
        {
          const double lv = pv.norm();
          // A is on the x axis at distance la; B at angle theta.
          const double cos_av = pv.x() / lv;
          const double sin_theta = k.sin_angle;
          const double cos_vb = (pv.x() * cos_angle + pv.y() * sin_theta) / lv;
          add_virtual(c, a, v, la, lv, std::min(1.0, cos_av));
          add_virtual(c, v, b, lv, lb, std::min(1.0, cos_vb));
          // The segment CV crosses every unfolded edge (each spans the section), so it is a path
          // on the surface: one-point updates T(C) <= T(V) + |CV| and T(V) <= T(C) + |CV|.
          raw.push_back(Raw{v, Entry{c, -1, lv, 0.0, 1.0, 0.0, 0.0, 0.0}});
          raw.push_back(Raw{c, Entry{v, -1, lv, 0.0, 1.0, 0.0, 0.0, 0.0}});
        }
        else
          ++number_of_fallbacks;
      }

    // Counting sort of the virtual entries by owner.
    entry_offsets.assign(n + 1, 0);
    for(const Raw& r : raw) ++entry_offsets[r.owner + 1];
    std::partial_sum(entry_offsets.begin(), entry_offsets.end(), entry_offsets.begin());
    entries.resize(raw.size());
    std::vector<int> fill(entry_offsets.begin(), entry_offsets.end() - 1);
    for(const Raw& r : raw) entries[fill[r.owner]++] = r.e;
  }

private:
  // The triangle other than f that contains the edge (p, q), or -1 on a boundary.
  static int opposite_triangle(const Indexed_mesh& m, int f, int p, int q)
  {
    for(int k = m.triangle_offsets[p]; k < m.triangle_offsets[p + 1]; ++k)
    {
      const int g = m.incident_triangles[k];
      if(g == f) continue;
      if(m.triangles(g, 0) == q || m.triangles(g, 1) == q || m.triangles(g, 2) == q) return g;
    }
    return -1;
  }

  static double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& w)
  {
    return u.x() * w.y() - u.y() * w.x();
  }

  // Kimmel-Sethian splitting of the obtuse angle at c in triangle f = (c, a, b): unfolds the
  // triangles beyond ab into the plane (c at the origin, a on the positive x axis, b above it)
  // until a vertex falls in the section {d : d.a > 0, d.b > 0}.
  static bool unfold(const Indexed_mesh& m, int f, int c, int a, int b, double la, double lb,
                     double cos_angle, int max_steps, int& v_out, Eigen::Vector2d& pv_out)
  {
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle));
    const Eigen::Vector2d pa(la, 0.0), pb(lb * cos_angle, lb * sin_theta);
    // Current strip edge (p, q) with p on a's side of the section and q on b's side, and r the
    // third vertex of the current triangle (on c's side of pq).
    int p = a, q = b, r = c, face = f;
    Eigen::Vector2d xp = pa, xq = pb, xr(0.0, 0.0);
    for(int step = 0; step < max_steps; ++step)
    {
      const int g = opposite_triangle(m, face, p, q);
      if(g < 0) return false;
      int w = -1;
      for(int k = 0; k < 3; ++k)
        if(m.triangles(g, k) != p && m.triangles(g, k) != q) w = m.triangles(g, k);
      if(w == c || w == a || w == b || w < 0) return false;
      // Place w in the plane: |w p| and |w q| from 3D, on the side of pq opposite to r.
      const double dp = (m.point(w) - m.point(p)).norm(), dq = (m.point(w) - m.point(q)).norm();
      const Eigen::Vector2d e = xq - xp;
      const double le = e.norm();
      const Eigen::Vector2d ex = e / le, ey(-ex.y(), ex.x());
      const double x = (dp * dp - dq * dq + le * le) / (2.0 * le);
      const double y = std::sqrt(std::max(0.0, dp * dp - x * x));
      const double side_r = cross2(e, xr - xp);
      const Eigen::Vector2d xw = xp + x * ex + (side_r > 0 ? -y : y) * ey;
      const double da = xw.dot(pa), db = xw.dot(pb);
      if(da > 0 && db > 0)
      {
        v_out = w;
        pv_out = xw;
        return true;
      }
      if(da <= 0 && db <= 0) return false;
      if(db <= 0)
      {  // w on a's side: continue through the edge (w, q)
        r = p;
        xr = xp;
        p = w;
        xp = xw;
      }
      else
      {  // w on b's side: continue through the edge (p, w)
        r = q;
        xr = xq;
        q = w;
        xq = xw;
      }
      face = g;
    }
    (void)r;
    return false;
  }
};

/// Per-run state of fast marching on one Fast_marching_geometry. Not thread-safe: one workspace
/// per thread. A run resets only what the previous run touched. All arrays have their final size
/// after attach(), so runs never allocate.
class Fast_marching_workspace
{
public:
  Fast_marching_workspace() = default;
  explicit Fast_marching_workspace(const Fast_marching_geometry& g) { attach(g); }

  void attach(const Fast_marching_geometry& g)
  {
    geometry_ = &g;
    const std::size_t n = static_cast<std::size_t>(g.number_of_vertices());
    distance_.assign(n, std::numeric_limits<double>::infinity());
    state_.assign(n, FAR);
    heap_position_.assign(n, -1);
    is_target_.assign(n, 0);
    heap_.assign(n, Heap_node{0.0, 0});
    touched_.assign(2 * n, 0);
    accepted_.clear();
    accepted_.reserve(n);
    number_touched_ = 0;
  }

  const Fast_marching_geometry& geometry() const { return *geometry_; }

  /// Runs fast marching from `sources` (distance 0). Stops when the smallest tentative distance
  /// exceeds `max_distance` (truncation), or, when `number_of_targets` > 0, as soon as every
  /// target is accepted (early termination). Accepted values are final and identical to those of
  /// a full run. Throws Invalid_parameter_error for an index out of range or no source.
  void run(const int* sources, std::size_t number_of_sources,
           double max_distance = std::numeric_limits<double>::infinity(),
           const int* targets = nullptr, std::size_t number_of_targets = 0)
  {
    reset();
    const int n = geometry_->number_of_vertices();
    if(number_of_sources == 0)
      throw Invalid_parameter_error("fast marching: no source vertex given");
    if(std::isnan(max_distance) || max_distance < 0)
      throw Invalid_parameter_error("fast marching: the maximum distance must be >= 0 (got " +
                                    std::to_string(max_distance) + ")");
    for(std::size_t i = 0; i < number_of_sources; ++i)
      check_vertex_index(sources[i], n, "fast marching source");
    for(std::size_t i = 0; i < number_of_targets; ++i)
      check_vertex_index(targets[i], n, "fast marching target");

    // Raw pointers: the compiler cannot keep vector internals in registers across stores.
    double* const distance = distance_.data();
    unsigned char* const state = state_.data();
    int* const position = heap_position_.data();
    unsigned char* const is_target = is_target_.data();
    Heap_node* const heap = heap_.data();
    int* const touched = touched_.data();
    int heap_size = 0, number_touched = 0;

    std::size_t remaining = 0;
    for(std::size_t i = 0; i < number_of_targets; ++i)
    {
      const int t = targets[i];
      if(!is_target[t])
      {
        is_target[t] = 1;
        touched[number_touched++] = t;
        ++remaining;
      }
    }
    const bool early = number_of_targets > 0;

    auto sift_up = [&](int i, double key, int v) {
      while(i > 0)
      {
        const int parent = (i - 1) >> 2;
        if(!(key < heap[parent].key)) break;
        heap[i] = heap[parent];
        position[heap[i].vertex] = i;
        i = parent;
      }
      heap[i].key = key;
      heap[i].vertex = v;
      position[v] = i;
    };
    auto relax = [&](int w, double value) {
      // The caller has checked that w is not accepted.
      if(!(value < distance[w])) return;
      distance[w] = value;
      if(state[w] == FAR)
      {
        state[w] = TRIAL;
        touched[number_touched++] = w;
        sift_up(heap_size++, value, w);
      }
      else
        sift_up(position[w], value, w);
    };
    auto pop = [&]() {
      position[heap[0].vertex] = -1;
      --heap_size;
      if(heap_size == 0) return;
      const double key = heap[heap_size].key;
      const int v = heap[heap_size].vertex;
      int i = 0;
      for(;;)
      {
        const int first = 4 * i + 1;
        if(first >= heap_size) break;
        int child = first;
        double best = heap[first].key;
        const int last = std::min(first + 4, heap_size);
        for(int c = first + 1; c < last; ++c)
          if(heap[c].key < best)
          {
            best = heap[c].key;
            child = c;
          }
        if(!(best < key)) break;
        heap[i] = heap[child];
        position[heap[i].vertex] = i;
        i = child;
      }
      heap[i].key = key;
      heap[i].vertex = v;
      position[v] = i;
    };

    for(std::size_t i = 0; i < number_of_sources; ++i)
      if(state[sources[i]] != ACCEPTED) relax(sources[i], 0.0);

    const Indexed_mesh& m = *geometry_->mesh;
    const int* neighbor_offsets = m.neighbor_offsets.data();
    const int* neighbors = m.neighbors.data();
    const double* lengths = geometry_->graph.lengths.data();
    const Fast_marching_geometry::Entry* entries = geometry_->entries.data();
    const int* entry_offsets = geometry_->entry_offsets.data();
    const Fast_marching_geometry::Corner* corners = geometry_->corners.data();
    const int* corner_offsets = geometry_->corner_offsets.data();
    const Fast_marching_geometry::Incident_corner* vertex_corners = geometry_->vertex_corners.data();
    const bool circular = geometry_->update_rule == Fast_marching_update::circular;
    auto update = [circular](double tx, double ty, double lx, double ly, double cos_angle, double sin_angle,
                             double edge, double inverse_edge) {
      return circular ? fast_marching_circular_update(tx, ty, lx, ly, cos_angle, sin_angle, edge, inverse_edge)
                      : fast_marching_two_point_update(tx, ty, lx, ly, cos_angle);
    };
    while(heap_size > 0)
    {
      const int v = heap[0].vertex;
      const double d = heap[0].key;
      if(d > max_distance) break;
      pop();
      state[v] = ACCEPTED;
      accepted_.push_back(v);
      if(early && is_target[v] && --remaining == 0) break;
      // Two-point updates in the incident triangles (v, a, b): update the one of a, b that is not
      // accepted when the other one is.
      for(int k = corner_offsets[v], e = corner_offsets[v + 1]; k < e; ++k)
      {
        const Fast_marching_geometry::Incident_corner& ic = vertex_corners[k];
        const int a = ic.next, b = ic.previous;
        const bool accepted_a = state[a] == ACCEPTED, accepted_b = state[b] == ACCEPTED;
        if(accepted_a == accepted_b) continue;
        if(accepted_a)
        {
          // Update b: its next vertex is v, its previous a.
          const Fast_marching_geometry::Corner& g = corners[ic.previous_corner];
          relax(b, update(d, distance[a], g.length_next, g.length_prev, g.cos_angle, g.sin_angle,
                          g.edge_length, g.inverse_edge_length));
        }
        else
        {
          // Update a: its next vertex is b, its previous v.
          const Fast_marching_geometry::Corner& g = corners[ic.next_corner];
          relax(a, update(d, distance[b], g.length_prev, g.length_next, g.cos_angle, g.sin_angle,
                          g.edge_length, g.inverse_edge_length));
        }
      }
      // Virtual triangles and one-point updates along unfolded segments.
      for(int k = entry_offsets[v], e = entry_offsets[v + 1]; k < e; ++k)
      {
        const Fast_marching_geometry::Entry& en = entries[k];
        if(state[en.target] == ACCEPTED) continue;
        if(en.other < 0)
          relax(en.target, d + en.length);
        else if(state[en.other] == ACCEPTED)
          relax(en.target, update(d, distance[en.other], en.length, en.other_length, en.cos_angle,
                                  en.sin_angle, en.edge_length, en.inverse_edge_length));
      }
      // One-point updates along edges (last: most are then no improvement, and cost no heap work).
      for(int k = neighbor_offsets[v], e = neighbor_offsets[v + 1]; k < e; ++k)
      {
        const int w = neighbors[k];
        if(state[w] != ACCEPTED) relax(w, d + lengths[k]);
      }
    }
    number_touched_ = number_touched;
  }

  /// Single-source convenience.
  void run(int source, double max_distance = std::numeric_limits<double>::infinity())
  {
    run(&source, 1, max_distance);
  }

  /// Final distance of `v` after the last run, +infinity if `v` was not accepted (beyond the
  /// truncation radius, not reached before early termination, or in another component).
  double distance(int v) const
  {
    return state_[v] == ACCEPTED ? distance_[v] : std::numeric_limits<double>::infinity();
  }
  /// The accepted vertices of the last run, by increasing distance.
  const std::vector<int>& accepted() const { return accepted_; }

  /// Writes the distances of the last run into `out` (size n; +infinity where not accepted).
  void copy_distances(std::vector<double>& out) const
  {
    out.assign(distance_.size(), std::numeric_limits<double>::infinity());
    for(int v : accepted_) out[v] = distance_[v];
  }

private:
  enum State : unsigned char { FAR = 0, TRIAL = 1, ACCEPTED = 2 };

  void reset()
  {
    for(int i = 0; i < number_touched_; ++i)
    {
      const int v = touched_[i];
      distance_[v] = std::numeric_limits<double>::infinity();
      state_[v] = FAR;
      heap_position_[v] = -1;
      is_target_[v] = 0;
    }
    number_touched_ = 0;
    accepted_.clear();
  }

  const Fast_marching_geometry* geometry_ = nullptr;
  std::vector<double> distance_;
  std::vector<unsigned char> state_;
  std::vector<int> heap_position_;
  std::vector<unsigned char> is_target_;
  struct Heap_node
  {
    double key;
    int vertex;
  };
  std::vector<Heap_node> heap_;  // 4-ary heap of the trial vertices, size heap_size in run()
  std::vector<int> touched_;       // vertices to reset (each at most twice: as target, as trial)
  int number_touched_ = 0;
  std::vector<int> accepted_;
};

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FAST_MARCHING_H
