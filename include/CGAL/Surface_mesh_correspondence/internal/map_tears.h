// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tears of a point-to-point map: source edges whose endpoints land far apart on the target. A map
// that swaps two limbs (or two feet) of a symmetric body is continuous on each part but jumps
// where the swapped part meets the rest; cutting the source along these jumps splits it into the
// consistently mapped regions. The largest one (the core) is where the map can be trusted.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_TEARS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_TEARS_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// The regions of a map's source between its tears.
struct Map_tears
{
  /// Per source vertex: its region, or -1 for a vertex on a torn edge.
  std::vector<int> region;
  /// Area of each region (a third of the incident triangle areas per vertex).
  std::vector<double> region_area;
  /// The region of largest area (-1 when every vertex lies on a tear).
  int core = -1;
  /// The number of torn source edges.
  std::size_t torn_edges = 0;
  /// Area fraction of the source in regions other than the core: the part of the map that is
  /// cut off from the core by tears (the vertices on the tears themselves are not counted).
  double torn_fraction = 0;
};

/// The tear threshold of a map into `target`: `relative_threshold` times sqrt(area of the target),
/// at least four mean edge lengths of the target (so that the discretisation of a continuous map
/// never counts as a tear on coarse meshes).
inline double tear_threshold(const Indexed_mesh& target, double relative_threshold)
{
  const Edge_length_graph g(target);
  return std::max(relative_threshold * std::sqrt(target.total_area), 4.0 * g.mean_edge_length);
}

/// Cuts the source of `map` (source vertex -> target vertex) along its tears: the edges (i, j)
/// whose images are at least `threshold` apart (Euclidean distance, a lower bound of the
/// geodesic one, so touching parts of the target can hide a tear but never make one). Vertices
/// on a torn edge belong to no region; the others are grouped by connectivity. `VertexMap`: a
/// random-access range of target vertex indices (std::vector<int> or std::vector<std::size_t>).
template <typename VertexMap>
Map_tears map_tears(const Indexed_mesh& source, const Indexed_mesh& target, const VertexMap& map, double threshold)
{
  const int n = source.number_of_vertices();
  Map_tears t;
  std::vector<char> on_tear(static_cast<std::size_t>(n), 0);
  const double t2 = threshold * threshold;
  for(const auto& e : source.edges)
    if((target.points.row(map[e[0]]) - target.points.row(map[e[1]])).squaredNorm() >= t2)
    {
      ++t.torn_edges;
      on_tear[e[0]] = on_tear[e[1]] = 1;
    }
  // Union-find over the edges between vertices off the tears.
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while(parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for(const auto& e : source.edges)
    if(!on_tear[e[0]] && !on_tear[e[1]])
    {
      const int a = find(e[0]), b = find(e[1]);
      if(a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<double> vertex_area(static_cast<std::size_t>(n), 0.0);
  for(int f = 0; f < source.number_of_triangles(); ++f)
    for(int c = 0; c < 3; ++c) vertex_area[source.triangles(f, c)] += source.triangle_areas[f] / 3.0;
  t.region.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> label(static_cast<std::size_t>(n), -1);
  double total = 0;
  for(int v = 0; v < n; ++v)
  {
    total += vertex_area[v];
    if(on_tear[v]) continue;
    const int r = find(v);
    if(label[r] < 0)
    {
      label[r] = static_cast<int>(t.region_area.size());
      t.region_area.push_back(0.0);
    }
    t.region[v] = label[r];
    t.region_area[label[r]] += vertex_area[v];
  }
  double core_area = 0, regions_area = 0;
  for(std::size_t r = 0; r < t.region_area.size(); ++r)
  {
    regions_area += t.region_area[r];
    if(t.region_area[r] > core_area)
    {
      core_area = t.region_area[r];
      t.core = static_cast<int>(r);
    }
  }
  t.torn_fraction = total > 0 ? (regions_area - core_area) / total : 0.0;
  return t;
}

/// `count` farthest-point samples of the core of `tears` (geodesic along the source's edges) with
/// their images under `map`, as (source vertex, target vertex) pairs; fewer when the core is
/// smaller. The samples keep away from the tears by `margin` (relative to sqrt(area) of the
/// source) where the core allows it: a tear often has a wrongly mapped band on its core side too
/// (the tear is where the map jumps, not necessarily where it goes wrong). Empty without a core.
template <typename VertexMap>
std::vector<std::pair<int, int> > core_correspondences(const Indexed_mesh& source, const Map_tears& tears,
                                                       const VertexMap& map, int count, double margin = 0.1)
{
  std::vector<std::pair<int, int> > pairs;
  if(tears.core < 0 || count <= 0) return pairs;
  const int n = source.number_of_vertices();
  const Edge_length_graph graph(source);
  std::vector<int> on_tear;
  for(int v = 0; v < n; ++v)
    if(tears.region[v] < 0) on_tear.push_back(v);
  std::vector<double> to_tear(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  if(!on_tear.empty()) dijkstra_distances(graph, on_tear, to_tear);
  // The core vertices at least `margin` from the tears; the margin is halved until they are
  // enough for the samples (or it reaches 0: the whole core).
  std::vector<int> core;
  for(double d = margin * std::sqrt(source.total_area);; d *= 0.5)
  {
    core.clear();
    for(int v = 0; v < n; ++v)
      if(tears.region[v] == tears.core && to_tear[v] >= d) core.push_back(v);
    if(static_cast<int>(core.size()) >= 4 * count || d < graph.mean_edge_length) break;
  }
  if(core.empty()) return pairs;
  Farthest_point_sampler sampler(graph);
  std::vector<int> samples;
  sampler.sample(core.data(), core.size(), nullptr, 0, std::min<int>(count, static_cast<int>(core.size())), samples);
  for(int v : samples) pairs.emplace_back(v, static_cast<int>(map[v]));
  return pairs;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_TEARS_H
