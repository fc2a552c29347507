// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Distance oracles: geodesic distances between any two vertices of one mesh, answered in
// constant (dense) or logarithmic (local) time, for the pairwise terms of the coupled refinement
// (about 3n edges x m^2 queries per solve) and for evaluation.
//
// Concept DistanceOracle (a small documented concept; both classes below are models):
//   int   number_of_vertices() const;                       // n, vertices are 0..n-1
//   float distance(int k, int l) const;                     // d(k, l) >= 0, +infinity across components
//   void  distances(int k, const int* l, std::size_t count, float* out) const;
//                                                           // out[i] = distance(k, l[i]) (a row batch)
// Queries are const and thread-safe.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_DISTANCE_ORACLE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_DISTANCE_ORACLE_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/geodesic_distances.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/cgal_geodesics.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#include <CGAL/tags.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

namespace internal {

/// A pool of per-thread objects (workspaces, solvers) for parallel loops: a chunk of work
/// acquires one, uses it, and releases it; at most one object per concurrently running chunk is
/// ever created.
template <typename T>
class Object_pool
{
public:
  explicit Object_pool(std::function<std::unique_ptr<T>()> make) : make_(std::move(make)) {}
  std::unique_ptr<T> acquire()
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if(!free_.empty())
      {
        std::unique_ptr<T> p = std::move(free_.back());
        free_.pop_back();
        return p;
      }
    }
    return make_();
  }
  void release(std::unique_ptr<T> p)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(p));
  }

private:
  std::function<std::unique_ptr<T>()> make_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<T> > free_;
};

/// Calls row(i, ws) for every i in [0, sources.size()) in parallel, where the fast marching
/// workspace `ws` holds the (full) distance field from sources[i].
template <typename ConcurrencyTag, typename RowFunction>
void for_each_fast_marching_row(const Indexed_mesh& m, const std::vector<int>& sources,
                                const RowFunction& row, std::size_t grain = 8)
{
  Fast_marching_geometry g(m);
  Object_pool<Fast_marching_workspace> pool(
      [&g]() { return std::unique_ptr<Fast_marching_workspace>(new Fast_marching_workspace(g)); });
  parallel_for_ranges<ConcurrencyTag>(
      sources.size(),
      [&](std::size_t b, std::size_t e) {
        std::unique_ptr<Fast_marching_workspace> ws = pool.acquire();
        for(std::size_t i = b; i < e; ++i)
        {
          ws->run(sources[i]);
          row(i, *ws);
        }
        pool.release(std::move(ws));
      },
      grain);
}

/// Calls row(i, buffer) for every i in [0, sources.size()) in parallel, where `buffer` (n
/// doubles) holds the heat-method or exact distances from sources[i]. One solver per concurrent
/// chunk (each factorises or copies the mesh).
template <typename ConcurrencyTag, typename RowFunction>
void for_each_solver_row(const Indexed_mesh& m, const std::vector<int>& sources, Geodesic_method method,
                         const RowFunction& row, std::size_t grain = 1)
{
  struct Solver
  {
    std::unique_ptr<Heat_method_solver> heat;
    std::unique_ptr<Exact_geodesic_solver> exact;
    std::vector<double> buffer;
  };
  Object_pool<Solver> pool([&m, method]() {
    std::unique_ptr<Solver> s(new Solver);
    if(method == Geodesic_method::heat_method) s->heat.reset(new Heat_method_solver(m));
    else s->exact.reset(new Exact_geodesic_solver(m));
    return s;
  });
  parallel_for_ranges<ConcurrencyTag>(
      sources.size(),
      [&](std::size_t b, std::size_t e) {
        std::unique_ptr<Solver> s = pool.acquire();
        for(std::size_t i = b; i < e; ++i)
        {
          if(s->heat) s->heat->distances(sources[i], s->buffer);
          else s->exact->distances(sources[i], s->buffer);
          row(i, s->buffer);
        }
        pool.release(std::move(s));
      },
      grain);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// All-pairs geodesic distances of a mesh, stored as a dense symmetric n x n matrix of floats
/// (4 n^2 bytes: 100 MB at 5k vertices, 900 MB at 15k). A model of DistanceOracle.
///
/// Row i is the distance field from vertex i (fast marching by default, see Geodesic_method); the
/// matrix is symmetrised, \f$ D_{kl} = D_{lk} = (d_k(l) + d_l(k)) / 2 \f$.
class Dense_distance_oracle
{
public:
  Dense_distance_oracle() = default;

  int number_of_vertices() const { return n_; }
  /// \f$ D_{kl} \f$; +infinity across components. \pre 0 <= k, l < n
  float distance(int k, int l) const { return d_[static_cast<std::size_t>(k) * n_ + l]; }
  /// out[i] = distance(k, l[i]) for i < count.
  void distances(int k, const int* l, std::size_t count, float* out) const
  {
    const float* r = row(k);
    for(std::size_t i = 0; i < count; ++i) out[i] = r[l[i]];
  }
  /// out[1 + p] = distance(k, set[p]) for p < size (the interface of
  /// Local_distance_oracle::distances_to_set(); `slot` is not needed here).
  void distances_to_set(int k, const int* /*slot*/, const int* set, std::size_t size, float* out) const
  {
    distances(k, set, size, out + 1);
  }
  /// Row k of the matrix (n floats).
  const float* row(int k) const { return d_.data() + static_cast<std::size_t>(k) * n_; }
  std::size_t memory_bytes() const { return d_.size() * sizeof(float); }

  /// Builds the matrix on the flat mesh with `method`, rows in parallel with
  /// CGAL::Parallel_tag. Throws Invalid_parameter_error when n^2 floats do not fit in memory
  /// (std::bad_alloc otherwise propagates).
  template <typename ConcurrencyTag = CGAL::Sequential_tag>
  static Dense_distance_oracle build(const internal::Indexed_mesh& m,
                                     Geodesic_method method = Geodesic_method::fast_marching)
  {
    Dense_distance_oracle o;
    const int n = m.number_of_vertices();
    o.n_ = n;
    o.d_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n),
                std::numeric_limits<float>::infinity());
    std::vector<int> sources(n);
    std::iota(sources.begin(), sources.end(), 0);
    float* d = o.d_.data();
    const std::size_t nn = static_cast<std::size_t>(n);
    if(method == Geodesic_method::fast_marching)
      internal::for_each_fast_marching_row<ConcurrencyTag>(
          m, sources, [&](std::size_t i, const internal::Fast_marching_workspace& ws) {
            float* r = d + i * nn;
            for(int v : ws.accepted()) r[v] = static_cast<float>(ws.distance(v));
          });
    else
      internal::for_each_solver_row<ConcurrencyTag>(
          m, sources, method, [&](std::size_t i, const std::vector<double>& buffer) {
            float* r = d + i * nn;
            for(std::size_t v = 0; v < nn; ++v) r[v] = static_cast<float>(buffer[v]);
          },
          1);
    o.symmetrize<ConcurrencyTag>();
    return o;
  }

private:
  template <typename ConcurrencyTag>
  void symmetrize()
  {
    const std::size_t n = static_cast<std::size_t>(n_), tile = 64;
    const std::size_t tiles = (n + tile - 1) / tile;
    float* d = d_.data();
    internal::parallel_for<ConcurrencyTag>(tiles, [&](std::size_t bi) {
      const std::size_t i0 = bi * tile, i1 = std::min(n, i0 + tile);
      for(std::size_t bj = bi; bj < tiles; ++bj)
      {
        const std::size_t j0 = bj * tile, j1 = std::min(n, j0 + tile);
        for(std::size_t i = i0; i < i1; ++i)
          for(std::size_t j = std::max(j0, i + 1); j < j1; ++j)
          {
            const float a = d[i * n + j], b = d[j * n + i];
            const float s = 0.5f * (a + b);
            d[i * n + j] = d[j * n + i] = s;
          }
      }
    });
  }

  int n_ = 0;
  std::vector<float> d_;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Geodesic distances for large meshes, with memory linear in n. A model of DistanceOracle.
///
/// - Within the local radius \f$ R \f$: the fast-marching distance, stored exactly as sparse rows
///   (row k holds every l with \f$ d_k(l) \le R \f$, sorted by index, float values; 8 bytes per
///   entry), symmetrised where both rows hold the pair: \f$ (d_k(l) + d_l(k)) / 2 \f$.
/// - Beyond it: the landmark upper bound
///   \f[ \tilde d(k, l) = \max\Big(R, \min_{a \in A} \big(d_a(k) + d_a(l)\big)\Big), \f]
///   with \f$ A \f$ a farthest point sampling of the mesh (number_of_landmarks() vertices) and
///   \f$ d_a \f$ their fast-marching fields. By the triangle inequality
///   \f$ d(k,l) \le \min_a (d_a(k) + d_a(l)) \le d(k,l) + 2 \min_a d_a(k) \f$, so the far estimate
///   is at most \f$ 2\rho \f$ above the distance, \f$ \rho \f$ = covering_radius() (up to the
///   fast-marching error), and typically far less (\f$ \approx \rho^2 / d \f$ when a landmark lies
///   near the geodesic).
///
/// A query inside the radius is a binary search in row k (about 10 comparisons for 800 entries);
/// a far query is a loop over the landmarks.
class Local_distance_oracle
{
public:
  Local_distance_oracle() = default;

  int number_of_vertices() const { return n_; }

  /// The local distance if l is in row k, else the landmark estimate (>= local_radius()).
  float distance(int k, int l) const
  {
    if(k == l) return 0.f;
    const int* b = columns_.data() + offsets_[k];
    const int* e = columns_.data() + offsets_[k + 1];
    const int* it = std::lower_bound(b, e, l);
    if(it != e && *it == l) return values_[it - columns_.data()];
    return far_estimate(k, l);
  }

  /// out[i] = distance(k, l[i]) for i < count.
  void distances(int k, const int* l, std::size_t count, float* out) const
  {
    const int* b = columns_.data() + offsets_[k];
    const std::size_t size = offsets_[k + 1] - offsets_[k];
    for(std::size_t i = 0; i < count; ++i)
    {
      const int key = l[i];
      if(key == k)
      {
        out[i] = 0.f;
        continue;
      }
      // Branchless binary search (conditional moves): the rows are short and the keys random.
      const int* base = b;
      std::size_t length = size;
      while(length > 1)
      {
        const std::size_t half = length / 2;
        base = (base[half] <= key) ? base + half : base;
        length -= half;
      }
      out[i] = (size > 0 && *base == key) ? values_[base - columns_.data()] : far_estimate(k, key);
    }
  }

  /// The distances from k to every vertex of a set, equal to distance(k, set[p]), in one walk
  /// over row k instead of a search per vertex (faster when many sources share the set):
  /// `slot[l]` is 1 + the position of vertex l in `set`, 0 for the vertices outside it;
  /// `out` has size + 1 entries, out[1 + p] receives distance(k, set[p]) and out[0] is scratch.
  void distances_to_set(int k, const int* slot, const int* set, std::size_t size, float* out) const
  {
    for(std::size_t p = 1; p <= size; ++p) out[p] = -1.f;
    const int* c = row_vertices(k);
    const float* d = row_distances(k);
    for(std::size_t i = 0, r = row_size(k); i < r; ++i) out[slot[c[i]]] = d[i]; // misses write out[0]
    out[slot[k]] = 0.f;
    for(std::size_t p = 1; p <= size; ++p)
      if(out[p] < 0.f) out[p] = far_estimate(k, set[p - 1]);
  }

  /// True when l is in row k (its distance is a local fast-marching value).
  bool is_local(int k, int l) const
  {
    const int* b = columns_.data() + offsets_[k];
    const int* e = columns_.data() + offsets_[k + 1];
    const int* it = std::lower_bound(b, e, l);
    return it != e && *it == l;
  }

  /// The landmark estimate \f$ \max(R, \min_a d_a(k) + d_a(l)) \f$ (+infinity across components).
  float far_estimate(int k, int l) const
  {
    const float* a = landmark_distances_.data() + static_cast<std::size_t>(k) * number_of_landmarks_;
    const float* b = landmark_distances_.data() + static_cast<std::size_t>(l) * number_of_landmarks_;
    float best = std::numeric_limits<float>::infinity();
    for(int i = 0; i < number_of_landmarks_; ++i)
    {
      const float s = a[i] + b[i];
      best = s < best ? s : best;
    }
    return best > radius_ ? best : radius_;
  }

  /// Row k: `row_size(k)` vertex indices (sorted) and distances.
  std::size_t row_size(int k) const { return offsets_[k + 1] - offsets_[k]; }
  const int* row_vertices(int k) const { return columns_.data() + offsets_[k]; }
  const float* row_distances(int k) const { return values_.data() + offsets_[k]; }

  float local_radius() const { return radius_; }
  int number_of_landmarks() const { return number_of_landmarks_; }
  const std::vector<int>& landmarks() const { return landmarks_; }
  /// \f$ \rho = \max_v \min_a d_a(v) \f$: the far estimate is within \f$ 2\rho \f$ of the distance.
  float covering_radius() const { return covering_radius_; }
  std::size_t number_of_local_entries() const { return columns_.size(); }
  std::size_t memory_bytes() const
  {
    return columns_.capacity() * sizeof(int) + values_.capacity() * sizeof(float) +
           offsets_.capacity() * sizeof(std::size_t) + landmark_distances_.capacity() * sizeof(float) +
           landmarks_.capacity() * sizeof(int);
  }

  /// Builds the oracle on the flat mesh: truncated fast marching from every vertex (radius
  /// `radius` > 0) and `number_of_landmarks` (>= 1; raised to the number of components, capped
  /// at n) full fast-marching fields. Rows run in parallel with CGAL::Parallel_tag.
  template <typename ConcurrencyTag = CGAL::Sequential_tag>
  static Local_distance_oracle build(const internal::Indexed_mesh& m, double radius, int number_of_landmarks)
  {
    if(!(radius > 0) || !std::isfinite(radius))
      throw Invalid_parameter_error("Local_distance_oracle: the local radius must be positive and "
                                    "finite (got " + std::to_string(radius) + ")");
    if(number_of_landmarks < 1)
      throw Invalid_parameter_error("Local_distance_oracle: the number of landmarks must be >= 1 (got " +
                                    std::to_string(number_of_landmarks) + ")");
    Local_distance_oracle o;
    const int n = m.number_of_vertices();
    o.n_ = n;
    o.radius_ = static_cast<float>(radius);
    internal::Fast_marching_geometry g(m);
    internal::Object_pool<internal::Fast_marching_workspace> pool([&g]() {
      return std::unique_ptr<internal::Fast_marching_workspace>(new internal::Fast_marching_workspace(g));
    });

    // Local rows, block by block (so that only one block of rows is held twice).
    typedef std::pair<int, float> Entry;
    const int block = 4096;
    std::vector<std::vector<Entry> > rows(static_cast<std::size_t>(std::min(block, n)));
    o.offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
    {
      // Reserve from the mean size of evenly strided sample rows (+15%), so that the arrays
      // rarely grow (growing copies them: a transient 2x).
      const int samples = std::min(n, 256);
      std::unique_ptr<internal::Fast_marching_workspace> ws = pool.acquire();
      std::size_t total = 0;
      for(int i = 0; i < samples; ++i)
      {
        const int v = static_cast<int>((static_cast<long long>(i) * n) / samples);
        ws->run(&v, 1, radius);
        total += ws->accepted().size();
      }
      pool.release(std::move(ws));
      const std::size_t estimate = static_cast<std::size_t>(
          1.15 * static_cast<double>(total) * static_cast<double>(n) / static_cast<double>(samples));
      o.columns_.reserve(estimate);
      o.values_.reserve(estimate);
    }
    for(int b0 = 0; b0 < n; b0 += block)
    {
      const int b1 = std::min(n, b0 + block);
      internal::parallel_for_ranges<ConcurrencyTag>(
          static_cast<std::size_t>(b1 - b0),
          [&](std::size_t s, std::size_t e) {
            std::unique_ptr<internal::Fast_marching_workspace> ws = pool.acquire();
            for(std::size_t i = s; i < e; ++i)
            {
              const int v = b0 + static_cast<int>(i);
              ws->run(&v, 1, radius);
              std::vector<Entry>& row = rows[i];
              row.clear();
              for(int u : ws->accepted()) row.emplace_back(u, static_cast<float>(ws->distance(u)));
              std::sort(row.begin(), row.end(),
                        [](const Entry& x, const Entry& y) { return x.first < y.first; });
            }
            pool.release(std::move(ws));
          },
          16);
      std::size_t needed = o.columns_.size();
      for(int i = 0; i < b1 - b0; ++i) needed += rows[i].size();
      if(needed > o.columns_.capacity())
      {
        const std::size_t grown = std::max(needed, o.columns_.capacity() + o.columns_.capacity() / 4);
        o.columns_.reserve(grown);
        o.values_.reserve(grown);
      }
      for(int i = 0; i < b1 - b0; ++i)
      {
        for(const Entry& en : rows[i])
        {
          o.columns_.push_back(en.first);
          o.values_.push_back(en.second);
        }
        o.offsets_[b0 + i + 1] = o.offsets_[b0 + i] + rows[i].size();
      }
    }
    std::vector<std::vector<Entry> >().swap(rows);
    o.columns_.shrink_to_fit();
    o.values_.shrink_to_fit();
    o.symmetrize<ConcurrencyTag>();

    // Landmarks: farthest point sampling on the edge graph (every component gets one first),
    // then their fast-marching fields, computed landmark-major and transposed to vertex-major.
    const int L = std::min(n, std::max(number_of_landmarks, m.number_of_components));
    o.number_of_landmarks_ = L;
    {
      internal::Farthest_point_sampler sampler(g.graph);
      std::vector<int> all(n);
      std::iota(all.begin(), all.end(), 0);
      sampler.sample(all.data(), all.size(), nullptr, 0, L, o.landmarks_);
    }
    std::vector<float> fields(static_cast<std::size_t>(L) * n, std::numeric_limits<float>::infinity());
    internal::parallel_for_ranges<ConcurrencyTag>(
        static_cast<std::size_t>(L),
        [&](std::size_t s, std::size_t e) {
          std::unique_ptr<internal::Fast_marching_workspace> ws = pool.acquire();
          for(std::size_t a = s; a < e; ++a)
          {
            ws->run(o.landmarks_[a]);
            float* f = fields.data() + a * static_cast<std::size_t>(n);
            for(int u : ws->accepted()) f[u] = static_cast<float>(ws->distance(u));
          }
          pool.release(std::move(ws));
        },
        1);
    o.landmark_distances_.assign(static_cast<std::size_t>(L) * n, 0.f);
    float rho = 0;
    for(int v = 0; v < n; ++v)
    {
      float nearest = std::numeric_limits<float>::infinity();
      for(int a = 0; a < L; ++a)
      {
        const float x = fields[static_cast<std::size_t>(a) * n + v];
        o.landmark_distances_[static_cast<std::size_t>(v) * L + a] = x;
        nearest = std::min(nearest, x);
      }
      rho = std::max(rho, nearest);
    }
    o.covering_radius_ = rho;
    return o;
  }

private:
  template <typename ConcurrencyTag>
  void symmetrize()
  {
    // Pairs held by both rows get the mean of the two fast-marching values. The pair (k, l),
    // k < l, is only touched when processing k: no two threads write the same entry.
    internal::parallel_for<ConcurrencyTag>(
        static_cast<std::size_t>(n_),
        [&](std::size_t ks) {
          const int k = static_cast<int>(ks);
          for(std::size_t p = offsets_[k]; p < offsets_[k + 1]; ++p)
          {
            const int l = columns_[p];
            if(l <= k) continue;
            const int* b = columns_.data() + offsets_[l];
            const int* e = columns_.data() + offsets_[l + 1];
            const int* it = std::lower_bound(b, e, k);
            if(it == e || *it != k) continue;
            const std::size_t q = static_cast<std::size_t>(it - columns_.data());
            const float s = 0.5f * (values_[p] + values_[q]);
            values_[p] = values_[q] = s;
          }
        },
        64);
  }

  int n_ = 0;
  float radius_ = 0;
  std::vector<std::size_t> offsets_;
  std::vector<int> columns_;
  std::vector<float> values_;
  int number_of_landmarks_ = 0;
  std::vector<int> landmarks_;
  std::vector<float> landmark_distances_;  // n x L, vertex-major
  float covering_radius_ = 0;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Builds the dense all-pairs distance oracle of `tm` (for meshes up to about 15k vertices).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (rows in parallel, TBB)
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam NamedParameters a sequence of named parameters:
///   - `geodesic_method`: a Geodesic_method (default: `Geodesic_method::fast_marching`, the most
///     accurate and as fast as the heat method; `exact` is for small meshes and references);
///   - `vertex_point_map`, `vertex_index_map` (vertex i of the oracle is the vertex of index i).
/// \throws Invalid_mesh_error for a bad mesh.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Dense_distance_oracle make_dense_distance_oracle(const TriangleMesh& tm,
                                                 const NamedParameters& np = CGAL::parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const internal::Indexed_mesh m = internal::make_indexed_mesh(tm, np);
  const Geodesic_method method =
      choose_parameter(get_parameter(np, internal_np::geodesic_method), Geodesic_method::fast_marching);
  return Dense_distance_oracle::build<ConcurrencyTag>(m, method);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Builds the local distance oracle of `tm` (memory linear in n; for large meshes).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag`
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam NamedParameters a sequence of named parameters:
///   - `oracle_radius` (double, default 10): the radius \f$ R \f$ of the exact rows, in mean edge
///     lengths (about as many rings: every pair of candidates of two neighbouring source vertices
///     drawn from 4-ring neighbourhoods of nearby targets is local);
///   - `local_radius`: the radius in the mesh's length unit instead (overrides `oracle_radius`);
///   - `oracle_landmarks` (int, default 32): landmarks of the estimate beyond the radius;
///   - `vertex_point_map`, `vertex_index_map`.
/// The defaults are those of the settings registry (the shapes of match_shapes() use them).
/// \throws Invalid_mesh_error, Invalid_parameter_error (non-positive radius or landmark count).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Local_distance_oracle make_local_distance_oracle(const TriangleMesh& tm,
                                                 const NamedParameters& np = CGAL::parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const internal::Indexed_mesh m = internal::make_indexed_mesh(tm, np);
  const Matching_settings defaults;
  const double rings = choose_parameter(get_parameter(np, internal_np::oracle_radius), defaults.oracle_radius);
  double radius = 0;
  {
    internal::Edge_length_graph graph(m);
    radius = rings * graph.mean_edge_length;
  }
  radius = choose_parameter(get_parameter(np, internal_np::local_radius), radius);
  const int landmarks = choose_parameter(get_parameter(np, internal_np::oracle_landmarks), defaults.oracle_landmarks);
  return Local_distance_oracle::build<ConcurrencyTag>(m, radius, landmarks);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_DISTANCE_ORACLE_H
