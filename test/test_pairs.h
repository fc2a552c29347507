// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shape pairs with known ground truth for the matching tests: a bumpy capsule and a bent,
// independently remeshed copy of it (near-isometric, different connectivity), ground-truth maps
// from the construction, and perturbations of maps.

#ifndef SMC_TEST_PAIRS_H
#define SMC_TEST_PAIRS_H

#include "test_meshes.h"

#include <random>
#include <vector>

namespace smc_test {

/// A capsule (radius 1, length `length`) with bumps that break its symmetries.
inline Mesh bumpy_capsule(int nu = 24, int n_cap = 6, int n_body = 16, double length = 4.0)
{
  return transformed(capsule(nu, n_cap, n_body, 1.0, length), [](const Point& p) {
    const double a = std::atan2(p.y(), p.x());
    const double s = 1.0 + 0.12 * std::sin(3 * p.z() + 0.5) * std::cos(2 * a + 0.3 * p.z()) +
                     0.06 * std::cos(5 * a - 1.1 * p.z());
    return Point(s * p.x(), s * p.y(), p.z());
  });
}

/// A pair (M1, M2) with ground truth: M2 is M1 bent by `angle` around the y axis (near-isometric
/// for this thick tube) and, when `remesh` is true, isotropically remeshed (different
/// connectivity). gt_12[v] is the vertex of M2 nearest to the image of vertex v of M1; gt_21[w] is
/// the vertex of M1 whose image is nearest to w.
struct Shape_pair
{
  Mesh m1, m2;
  std::vector<std::size_t> gt_12, gt_21;
};

/// A pair (M1, M2) with ground truth: M2 is the image of M1 under `deform` and, when `remesh` is
/// true, isotropically remeshed (different connectivity). gt_12 and gt_21 as for bent_pair().
/// Compiled once, in test_pairs.cpp (the remeshing and the AABB tree compile slowly).
Shape_pair deformed_pair(const Mesh& m1, const std::function<Point(const Point&)>& deform, bool remesh,
                         double target_edge = 0.0);

inline Shape_pair bent_pair(const Mesh& m1, double length, double angle, bool remesh, double target_edge = 0.0)
{
  return deformed_pair(m1, [length, angle](const Point& q) { return bend_point(q, length, angle); }, remesh,
                       target_edge);
}

/// Moves the matches of a random fraction of the vertices by a random walk of `steps` edges on
/// the target mesh (a jump of up to `steps` rings).
inline std::vector<std::size_t> perturbed(const std::vector<std::size_t>& map, const Mesh& target, double fraction,
                                          int steps, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0, 1);
  std::vector<std::size_t> out = map;
  for(std::size_t& t : out)
  {
    if(coin(rng) >= fraction) continue;
    Vertex v(static_cast<Mesh::size_type>(t));
    for(int s = 0; s < steps; ++s)
    {
      std::vector<Vertex> nb;
      for(Vertex w : CGAL::vertices_around_target(target.halfedge(v), target)) nb.push_back(w);
      v = nb[std::uniform_int_distribution<std::size_t>(0, nb.size() - 1)(rng)];
    }
    t = v.idx();
  }
  return out;
}

/// Replaces the matches inside a few geodesic patches of the source by a consistent shift: every
/// vertex of a patch is sent to the match of a vertex `shift` rings away (a region that slid).
inline std::vector<std::size_t> patch_shifted(const std::vector<std::size_t>& map, const Mesh& source, int patches,
                                              int radius, int shift, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<std::size_t> out = map;
  const std::size_t n = num_vertices(source);
  for(int p = 0; p < patches; ++p)
  {
    const Vertex centre(static_cast<Mesh::size_type>(std::uniform_int_distribution<std::size_t>(0, n - 1)(rng)));
    // A fixed direction: walk `shift` steps always taking the neighbour of largest z.
    std::vector<int> depth(n, -1);
    std::vector<Vertex> queue = {centre};
    depth[centre.idx()] = 0;
    for(std::size_t h = 0; h < queue.size(); ++h)
      if(depth[queue[h].idx()] < radius)
        for(Vertex w : CGAL::vertices_around_target(source.halfedge(queue[h]), source))
          if(depth[w.idx()] < 0)
          {
            depth[w.idx()] = depth[queue[h].idx()] + 1;
            queue.push_back(w);
          }
    for(Vertex v : queue)
    {
      Vertex u = v;
      for(int s = 0; s < shift; ++s)
      {
        Vertex best = u;
        for(Vertex w : CGAL::vertices_around_target(source.halfedge(u), source))
          if(source.point(w).z() > source.point(best).z()) best = w;
        u = best;
      }
      out[v.idx()] = map[u.idx()];
    }
  }
  return out;
}

/// Identity correspondence list 0..n-1 (every vertex is a ground-truth sample).
inline std::vector<std::size_t> all_vertices(std::size_t n)
{
  std::vector<std::size_t> v(n);
  for(std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

/// Fraction of the entries where two maps of the same size agree.
inline double fraction_equal(const std::vector<std::size_t>& a, const std::vector<std::size_t>& b)
{
  if(a.size() != b.size() || a.empty())
    throw std::invalid_argument("fraction_equal: maps of sizes " + std::to_string(a.size()) + " and " +
                                std::to_string(b.size()));
  std::size_t same = 0;
  for(std::size_t i = 0; i < a.size(); ++i)
    same += a[i] == b[i];
  return double(same) / double(a.size());
}

} // namespace smc_test

#endif // SMC_TEST_PAIRS_H
