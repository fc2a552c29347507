// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Graph distances along mesh edges (Dijkstra) and farthest point sampling inside a vertex set.
//
// The farthest point sampling (FPS) of the coupled refinement runs for every source vertex in every
// step, on sets of a few hundred vertices, so it works with reusable workspaces (no allocation
// once warm) and the incremental, pruned Dijkstra update: after adding a sample s, only the
// vertices that are closer to s than to every previous sample are visited.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_DIJKSTRA_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_DIJKSTRA_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Throws Invalid_parameter_error when a vertex index is outside [0, n).
inline void check_vertex_index(int v, int n, const char* what)
{
  if(v < 0 || v >= n)
    throw Invalid_parameter_error(std::string(what) + ": vertex index " + std::to_string(v) +
                                  " is out of range [0, " + std::to_string(n) + ")");
}

/// The edge graph of a mesh: the one-ring adjacency of the Indexed_mesh with the Euclidean length
/// of every edge, stored twice (lengths[k] is the length of the edge from v to
/// mesh.neighbors[k], for k in [neighbor_offsets[v], neighbor_offsets[v+1])).
struct Edge_length_graph
{
  const Indexed_mesh* mesh = nullptr;
  std::vector<double> lengths;
  double mean_edge_length = 0;

  Edge_length_graph() = default;
  explicit Edge_length_graph(const Indexed_mesh& m) : mesh(&m)
  {
    const int n = m.number_of_vertices();
    lengths.resize(m.neighbors.size());
    double sum = 0;
    for(int v = 0; v < n; ++v)
      for(int k = m.neighbor_offsets[v]; k < m.neighbor_offsets[v + 1]; ++k)
      {
        lengths[k] = (m.points.row(v) - m.points.row(m.neighbors[k])).norm();
        sum += lengths[k];
      }
    mean_edge_length = lengths.empty() ? 0 : sum / static_cast<double>(lengths.size());
  }
  int number_of_vertices() const { return mesh->number_of_vertices(); }
};

/// Dijkstra distances along edges from `sources` (distance 0) to every vertex (infinity when
/// unreachable). When `allowed` is not null, only vertices v with allowed[v] != 0 are visited.
/// Used as an independent reference in tests and for small jobs; it allocates.
inline void dijkstra_distances(const Edge_length_graph& g, const std::vector<int>& sources,
                               std::vector<double>& distances,
                               const std::vector<char>* allowed = nullptr)
{
  const Indexed_mesh& m = *g.mesh;
  const int n = m.number_of_vertices();
  distances.assign(n, std::numeric_limits<double>::infinity());
  typedef std::pair<double, int> Item;
  std::vector<Item> heap;
  for(int s : sources)
  {
    check_vertex_index(s, n, "dijkstra_distances");
    if(allowed && !(*allowed)[s]) continue;
    distances[s] = 0;
    heap.emplace_back(0.0, s);
  }
  std::make_heap(heap.begin(), heap.end(), std::greater<Item>());
  while(!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end(), std::greater<Item>());
    const Item it = heap.back();
    heap.pop_back();
    if(it.first > distances[it.second]) continue;
    const int v = it.second;
    for(int k = m.neighbor_offsets[v]; k < m.neighbor_offsets[v + 1]; ++k)
    {
      const int w = m.neighbors[k];
      if(allowed && !(*allowed)[w]) continue;
      const double d = it.first + g.lengths[k];
      if(d < distances[w])
      {
        distances[w] = d;
        heap.emplace_back(d, w);
        std::push_heap(heap.begin(), heap.end(), std::greater<Item>());
      }
    }
  }
}

/// Farthest point sampling inside a vertex set, with the Dijkstra distance along the mesh edges
/// whose two endpoints are both in the set (paths may not leave the set).
///
/// Given the set S, seeds s_1..s_q (all in S) and a count m, the samples are
///   p_1..p_q = the distinct seeds in the given order, then
///   p_{j+1} = argmax_{v in S \ {p_1..p_j}} min_{i <= j} d_S(v, p_i),
/// ties broken by the smallest vertex index; a vertex unreachable from every sample has distance
/// +infinity, so it is taken before any reachable one (every component of S gets a sample early).
/// When S has at most m vertices (or every vertex has been taken), all of S is returned, in the
/// same greedy order. Without seeds the first sample is the smallest vertex index of S.
///
/// The distances min_i d_S(v, p_i) are maintained incrementally: adding p runs a Dijkstra from p
/// that stops expanding wherever it does not improve the current value (exact: the vertices that
/// improve form a shortest-path tree rooted at p). The set's adjacency is first copied into a
/// small local CSR (local indices and edge lengths), and the Dijkstra uses an indexed binary heap
/// on local indices. One object per thread; no allocation once the internal buffers have grown to
/// the largest set seen.
class Farthest_point_sampler
{
public:
  Farthest_point_sampler() = default;
  explicit Farthest_point_sampler(const Edge_length_graph& g) { attach(g); }

  void attach(const Edge_length_graph& g)
  {
    graph_ = &g;
    local_.assign(static_cast<std::size_t>(g.number_of_vertices()), -1);
  }

  /// Samples into `samples` (cleared first). `set` may list a vertex several times (duplicates
  /// are ignored); seeds repeated are taken once. Throws Invalid_parameter_error for a vertex out
  /// of range, a seed outside the set, or number_of_samples <= 0.
  void sample(const int* set, std::size_t set_size, const int* seeds, std::size_t number_of_seeds,
              int number_of_samples, std::vector<int>& samples)
  {
    samples.clear();
    if(number_of_samples <= 0)
      throw Invalid_parameter_error("farthest_point_sampling: the number of samples must be "
                                    "positive (got " + std::to_string(number_of_samples) + ")");
    const Indexed_mesh& m = *graph_->mesh;
    const int n = m.number_of_vertices();
    // Local numbering of the set.
    members_.clear();
    for(std::size_t i = 0; i < set_size; ++i)
    {
      const int v = set[i];
      if(v < 0 || v >= n)
      {
        clear_local();
        check_vertex_index(v, n, "farthest_point_sampling (vertex set)");
      }
      if(local_[v] >= 0) continue;
      local_[v] = static_cast<int>(members_.size());
      members_.push_back(v);
    }
    const int size = static_cast<int>(members_.size());
    // Local adjacency.
    offsets_.resize(static_cast<std::size_t>(size) + 1);
    adjacent_.clear();
    lengths_.clear();
    offsets_[0] = 0;
    for(int i = 0; i < size; ++i)
    {
      const int v = members_[i];
      for(int k = m.neighbor_offsets[v]; k < m.neighbor_offsets[v + 1]; ++k)
      {
        const int lw = local_[m.neighbors[k]];
        if(lw < 0) continue;
        adjacent_.push_back(lw);
        lengths_.push_back(graph_->lengths[k]);
      }
      offsets_[i + 1] = static_cast<int>(adjacent_.size());
    }
    min_distance_.assign(static_cast<std::size_t>(size), std::numeric_limits<double>::infinity());
    heap_position_.assign(static_cast<std::size_t>(size), -1);
    heap_key_.resize(static_cast<std::size_t>(size));
    heap_vertex_.resize(static_cast<std::size_t>(size));
    const std::size_t wanted =
        std::min<std::size_t>(static_cast<std::size_t>(number_of_samples), static_cast<std::size_t>(size));

    for(std::size_t i = 0; i < number_of_seeds && samples.size() < wanted; ++i)
    {
      const int s = seeds[i];
      if(s < 0 || s >= n || local_[s] < 0)
      {
        clear_local();
        throw Invalid_parameter_error("farthest_point_sampling: seed vertex " + std::to_string(s) +
                                      " is not in the vertex set");
      }
      if(min_distance_[local_[s]] < 0) continue;  // already taken
      add_sample(local_[s], samples);
    }
    clear_local();
    const double* md = min_distance_.data();
    while(samples.size() < wanted)
    {
      // argmax of the current distance among the vertices not taken (taken ones hold -1),
      // ties -> smallest vertex index.
      int best = 0;
      double best_d = md[0];
      for(int i = 1; i < size; ++i)
      {
        const double d = md[i];
        if(d > best_d || (d == best_d && members_[i] < members_[best]))
        {
          best_d = d;
          best = i;
        }
      }
      add_sample(best, samples);
    }
  }

  /// After sample(): for each member of the last set (last_members(), duplicates removed, in
  /// input order), its distance to the nearest sample, or -1 for the samples themselves.
  const std::vector<double>& last_min_distances() const { return min_distance_; }
  const std::vector<int>& last_members() const { return members_; }

private:
  void clear_local()
  {
    for(int v : members_) local_[v] = -1;
  }

  // Adds the member of local index ls and updates the distances with a pruned Dijkstra from it.
  void add_sample(int ls, std::vector<int>& samples)
  {
    samples.push_back(members_[ls]);
    double* md = min_distance_.data();
    int* position = heap_position_.data();
    double* key = heap_key_.data();
    int* vertex = heap_vertex_.data();
    const int* offsets = offsets_.data();
    const int* adjacent = adjacent_.data();
    const double* lengths = lengths_.data();
    int size = 0;
    auto sift_up = [&](int i, double k, int v) {
      while(i > 0)
      {
        const int parent = (i - 1) >> 1;
        if(!(k < key[parent])) break;
        key[i] = key[parent];
        vertex[i] = vertex[parent];
        position[vertex[i]] = i;
        i = parent;
      }
      key[i] = k;
      vertex[i] = v;
      position[v] = i;
    };
    md[ls] = 0;
    sift_up(size++, 0.0, ls);
    while(size > 0)
    {
      const int v = vertex[0];
      const double dv = key[0];
      position[v] = -1;
      --size;
      if(size > 0)
      {
        const double k = key[size];
        const int w = vertex[size];
        int i = 0;
        for(;;)
        {
          int child = 2 * i + 1;
          if(child >= size) break;
          if(child + 1 < size && key[child + 1] < key[child]) ++child;
          if(!(key[child] < k)) break;
          key[i] = key[child];
          vertex[i] = vertex[child];
          position[vertex[i]] = i;
          i = child;
        }
        key[i] = k;
        vertex[i] = w;
        position[w] = i;
      }
      for(int e = offsets[v]; e < offsets[v + 1]; ++e)
      {
        const int w = adjacent[e];
        const double d = dv + lengths[e];
        if(!(d < md[w])) continue;  // also skips the taken vertices (their value is -1 or 0)
        md[w] = d;
        sift_up(position[w] >= 0 ? position[w] : size++, d, w);
      }
    }
    md[ls] = -1;  // taken
  }

  const Edge_length_graph* graph_ = nullptr;
  std::vector<int> local_;            // n entries: position of a vertex in members_, or -1
  std::vector<int> members_;          // the set, duplicates removed, in input order
  std::vector<int> offsets_, adjacent_;  // local CSR adjacency
  std::vector<double> lengths_;
  std::vector<double> min_distance_;  // per member: distance to the nearest sample (-1: taken)
  std::vector<int> heap_position_;
  std::vector<double> heap_key_;
  std::vector<int> heap_vertex_;
};

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_DIJKSTRA_H
