// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The geodesic distortion of maps on farthest-point samples, by which the automatic initialisation
// chooses its fits and judges its repairs: the samples, their pairwise geodesic distances, cached
// fast marching rows, the distortion and the isometric core of a map, and the samplings of a pass.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DISTORTION_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DISTORTION_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Farthest point samples (edge-graph distances) of the whole mesh, starting from vertex 0.
inline std::vector<int> farthest_samples(const Indexed_mesh& m, int count)
{
  std::vector<int> samples;
  Edge_length_graph graph(m);
  Farthest_point_sampler sampler(graph);
  std::vector<int> all(m.number_of_vertices());
  for(int v = 0; v < m.number_of_vertices(); ++v) all[v] = v;
  sampler.sample(all.data(), all.size(), nullptr, 0, count, samples);
  return samples;
}

/// The ZoomOut samples of one mesh (sorted; empty: every vertex) and the `distortion_count`
/// samples of the distortion score (the first farthest-point samples, so a subset of the ZoomOut
/// samples), as vertices and as positions in the ZoomOut rows.
struct Initialization_samples
{
  std::vector<int> rows;
  std::vector<int> distortion_vertices, distortion_rows;
};

inline Initialization_samples initialization_samples(const Indexed_mesh& m, int count, int distortion_count)
{
  Initialization_samples out;
  const int n = m.number_of_vertices();
  const bool all_rows = count <= 0 || count >= n;
  const int q = std::min(distortion_count, n);
  if(all_rows && q <= 0) return out;  // nothing to sample
  std::vector<int> fps = farthest_samples(m, all_rows ? q : std::max(count, q));
  out.distortion_vertices.assign(fps.begin(), fps.begin() + std::max(q, 0));
  if(!all_rows)
  {
    out.rows = fps;
    std::sort(out.rows.begin(), out.rows.end());
  }
  for(int v : out.distortion_vertices)
    out.distortion_rows.push_back(all_rows ? v : int(std::lower_bound(out.rows.begin(), out.rows.end(), v) -
                                                     out.rows.begin()));
  return out;
}

/// Geodesic distances (fast marching) between the given vertices, divided by `scale`.
inline Eigen::MatrixXd pairwise_geodesic_distances(const Fast_marching_geometry& g, const std::vector<int>& vertices,
                                                   double scale)
{
  const Eigen::Index q = Eigen::Index(vertices.size());
  Eigen::MatrixXd d(q, q);
  Fast_marching_workspace w(g);
  for(Eigen::Index i = 0; i < q; ++i)
  {
    w.run(&vertices[i], 1, std::numeric_limits<double>::infinity(), vertices.data(), vertices.size());
    for(Eigen::Index j = 0; j < q; ++j) d(i, j) = w.distance(vertices[j]) / scale;
  }
  return d;
}

/// Fast-marching rows kept across the passes of one initialisation. The repair passes and the
/// distortion checks score maps whose sample images are often images of earlier passes (40-70% of
/// them on TOSCA_r pairs with two repair passes), so their runs are looked up instead of repeated.
/// A row holds the distances its run accepted (+infinity elsewhere); accepted values are final,
/// so a row answers later queries on its accepted vertices exactly as a new run would. Rows are
/// kept up to a memory budget (by default 48 MB per mesh: about 1200 rows of a 5000-vertex mesh),
/// so that memory stays linear in the mesh size.
class Fast_marching_row_cache
{
public:
  explicit Fast_marching_row_cache(std::size_t budget_bytes = std::size_t(48) << 20) : budget_(budget_bytes) {}

  /// The row of a run from `source`, or null: a row of this cache, else one of the shared cache.
  const std::vector<double>* find(int source) const
  {
    const auto it = rows_.find(source);
    if(it != rows_.end()) return &it->second;
    return shared_ ? shared_->find(source) : nullptr;
  }
  /// Whether this cache itself (not the shared one) holds a row of `source`.
  bool holds(int source) const { return rows_.count(source) > 0; }
  /// Looks up the rows of `shared` too (null: none), which must outlive this cache and not change
  /// while it is in use: the caches of concurrent passes each keep their new rows and share the
  /// rows of the passes before them, read-only.
  void share(const Fast_marching_row_cache* shared) { shared_ = shared; }
  /// Whether a new row of `n` distances fits in the budget.
  bool has_room(std::size_t n) const { return bytes_ + n * sizeof(double) <= budget_; }
  /// Keeps `row` as the run from `source` (replacing an older row of that source in this cache).
  void store(int source, std::vector<double>&& row)
  {
    auto it = rows_.find(source);
    if(it != rows_.end())
    {
      it->second = std::move(row);
      return;
    }
    if(!has_room(row.size())) return;
    bytes_ += row.size() * sizeof(double);
    rows_.emplace(source, std::move(row));
  }
  std::size_t size() const { return rows_.size(); }
  std::size_t memory_bytes() const { return bytes_; }

private:
  std::unordered_map<int, std::vector<double> > rows_;
  std::size_t bytes_ = 0, budget_;
  const Fast_marching_row_cache* shared_ = nullptr;
};

/// Geodesic distances between the vertices of a set (fast marching from each one, stopped when
/// the whole set is accepted), divided by `scale`. The distortion scores of many maps whose sample
/// images are drawn from the set are then lookups: the fits of one pass share most of their images,
/// so this needs far fewer fast marching runs than one run per image and map. Accepted values are
/// final, so the distances equal those of separate runs. With a row cache, runs whose row is
/// cached and covers the set are not repeated, and new rows are cached while the budget allows.
class Vertex_set_distances
{
public:
  template <typename ConcurrencyTag>
  void compute(const Fast_marching_geometry& g, std::vector<int> vertices, double scale,
               Fast_marching_row_cache* cache = nullptr)
  {
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    vertices_ = std::move(vertices);
    const std::size_t q = vertices_.size();
    distances_.resize(Eigen::Index(q), Eigen::Index(q));
    // Columns answered by cached rows; the others are run (and their rows kept when there is room).
    std::vector<const std::vector<double>*> cached(q, nullptr);
    std::vector<std::size_t> runs;
    for(std::size_t i = 0; i < q; ++i)
    {
      const std::vector<double>* row = cache ? cache->find(vertices_[i]) : nullptr;
      const auto accepted = [row](int v) { return std::isfinite((*row)[std::size_t(v)]); };
      if(row && std::all_of(vertices_.begin(), vertices_.end(), accepted))
        cached[i] = row;
      else
        runs.push_back(i);
    }
    const std::size_t n = std::size_t(g.number_of_vertices());
    std::vector<std::vector<double> > new_rows(cache ? runs.size() : 0);
    std::size_t room = 0;  // how many new rows the cache can take
    if(cache)
      while(room < runs.size() && cache->has_room((room + 1) * n)) ++room;
    parallel_for_ranges<ConcurrencyTag>(runs.size(), [&](std::size_t begin, std::size_t end) {
      Fast_marching_workspace w(g);
      for(std::size_t r = begin; r < end; ++r)
      {
        const std::size_t i = runs[r];
        w.run(&vertices_[i], 1, std::numeric_limits<double>::infinity(), vertices_.data(), q);
        for(std::size_t j = 0; j < q; ++j) distances_(Eigen::Index(j), Eigen::Index(i)) = w.distance(vertices_[j]) / scale;
        if(cache && (r < room || cache->holds(vertices_[i]))) w.copy_distances(new_rows[r]);
      }
    });
    for(std::size_t i = 0; i < q; ++i)
      if(cached[i])
        for(std::size_t j = 0; j < q; ++j)
          distances_(Eigen::Index(j), Eigen::Index(i)) = (*cached[i])[std::size_t(vertices_[j])] / scale;
    if(cache)
      for(std::size_t r = 0; r < runs.size(); ++r)
        if(!new_rows[r].empty()) cache->store(vertices_[runs[r]], std::move(new_rows[r]));
  }

  std::size_t size() const { return vertices_.size(); }

  /// The distance from `from` to `to` (fast marching started at `from`), both in the set.
  double distance(int from, int to) const { return distances_(position(to), position(from)); }

private:
  Eigen::Index position(int v) const
  {
    const auto it = std::lower_bound(vertices_.begin(), vertices_.end(), v);
    CGAL_assertion(it != vertices_.end() && *it == v);
    return Eigen::Index(it - vertices_.begin());
  }

  std::vector<int> vertices_;
  Eigen::MatrixXd distances_;  // column i: the run from vertices_[i]
};

/// Mean geodesic distortion of a map on samples: the mean over pairs (i, j) of
/// |d_S(s_i, s_j) - d_T(T(s_i), T(s_j))|, distances divided by the square roots of the areas.
/// `source_distances` are the source's (pairwise_geodesic_distances()), `images` the T(s_i), all
/// in `target_distances`.
inline double map_distortion(const Eigen::MatrixXd& source_distances, const Vertex_set_distances& target_distances,
                             const std::vector<int>& images)
{
  const Eigen::Index q = Eigen::Index(images.size());
  Eigen::MatrixXd d(q, q);
  for(Eigen::Index i = 0; i < q; ++i)
    for(Eigen::Index j = 0; j < q; ++j) d(i, j) = target_distances.distance(images[i], images[j]);
  return q < 2 ? 0.0 : (d - source_distances).cwiseAbs().sum() / double(q * (q - 1));
}

/// The isometric core of a map on the distortion samples: two samples agree when the map changes
/// their geodesic distance by less than `tolerance`; starting from all samples, the one that agrees
/// with the smallest fraction of the others still in the set is removed (the first on ties) until
/// every remaining sample agrees with at least `agreement` of them. A map that is right on one
/// part of the shape and mirrored or turned on another (a half-body flip: continuous and without
/// tears) keeps the samples of one part. Returns the positions of the core samples, in the
/// samples' order (farthest-point order, so any prefix is spread out).
inline std::vector<int> distortion_core(const Eigen::MatrixXd& source_distances, const Vertex_set_distances& target,
                                        const std::vector<int>& images, double tolerance, double agreement)
{
  const int q = int(images.size());
  std::vector<std::vector<char> > agree(std::size_t(q), std::vector<char>(std::size_t(q), 0));
  std::vector<int> count(std::size_t(q), 0);  // agreeing samples still in the set
  for(int i = 0; i < q; ++i)
    for(int j = 0; j < q; ++j)
      if(std::abs(target.distance(images[i], images[j]) - source_distances(i, j)) < tolerance)
      {
        agree[i][j] = 1;
        ++count[i];
      }
  std::vector<char> in(std::size_t(q), 1);
  int size = q;
  while(size > 1)
  {
    int worst = -1;
    for(int i = 0; i < q; ++i)
      if(in[i] && (worst < 0 || count[i] < count[worst])) worst = i;
    if(double(count[worst]) >= agreement * double(size)) break;
    in[worst] = 0;
    --size;
    for(int i = 0; i < q; ++i)
      if(agree[i][worst]) --count[i];
  }
  std::vector<int> core;
  for(int i = 0; i < q; ++i)
    if(in[i]) core.push_back(i);
  return core;
}

/// The samples of one mesh that every pass of the initialisation uses (they do not depend on the
/// landmarks): the ZoomOut and distortion samples, the fast marching geometry and the pairwise
/// distances of the distortion samples.
struct Initialization_sampling
{
  Initialization_samples samples;
  Fast_marching_geometry geodesics;
  Eigen::MatrixXd sample_distances;
  /// Runs of the distortion scores, shared by all passes (see Fast_marching_row_cache).
  mutable Fast_marching_row_cache rows;

  /// A copy for a pass that runs concurrently with others: its row cache starts empty and reads
  /// the rows of this one (Fast_marching_row_cache::share()), which must then stay as they are
  /// until the copy is gone.
  Initialization_sampling copy_sharing_rows() const
  {
    Initialization_sampling c;
    c.samples = samples;
    c.geodesics = geodesics;
    c.sample_distances = sample_distances;
    c.rows.share(&rows);
    return c;
  }
};

/// The samplings of both meshes, computed by the first pass and reused by the repair passes
/// (recomputed when the sample counts change).
struct Initialization_pass_cache
{
  bool ready = false;
  int number_of_samples = 0, distortion_count = 0;
  Initialization_sampling first, second;

  /// A copy for a pass that runs concurrently with others: the samplings, and row caches of its
  /// own that read the rows of this one (see Initialization_sampling::copy_sharing_rows()).
  Initialization_pass_cache copy_sharing_rows() const
  {
    Initialization_pass_cache c;
    c.ready = ready;
    c.number_of_samples = number_of_samples;
    c.distortion_count = distortion_count;
    c.first = first.copy_sharing_rows();
    c.second = second.copy_sharing_rows();
    return c;
  }
};

/// Fills `cache` with the samplings of both shapes, unless it holds them for these settings.
template <typename ConcurrencyTag>
void prepare_pass_cache(const Initialization_shape& shape1, const Initialization_shape& shape2,
                        const Initialization_settings& s, Initialization_pass_cache& cache)
{
  const int distortion_count = s.select_by_distortion || s.distortion_repair_passes > 0 ? s.distortion_samples : 0;
  if(cache.ready && cache.number_of_samples == s.zoomout_number_of_samples && cache.distortion_count == distortion_count)
    return;
  auto prepare_samples = [&](const Initialization_shape& shape, Initialization_sampling& out) {
    out.samples = initialization_samples(*shape.mesh, s.zoomout_number_of_samples, distortion_count);
    out.rows = Fast_marching_row_cache();
    if(distortion_count <= 0) return;
    out.geodesics.build(*shape.mesh);
    out.sample_distances = pairwise_geodesic_distances(out.geodesics, out.samples.distortion_vertices,
                                                       std::sqrt(shape.spectrum->total_area()));
  };
  invoke_both<ConcurrencyTag>([&] { prepare_samples(shape1, cache.first); },
                              [&] { prepare_samples(shape2, cache.second); });
  cache.ready = true;
  cache.number_of_samples = s.zoomout_number_of_samples;
  cache.distortion_count = distortion_count;
}

/// Fills `cache` as prepare_pass_cache() does, with the distortion samples even when the settings
/// would not need them (select_by_distortion off and no distortion repair).
template <typename ConcurrencyTag>
void prepare_distortion_samples(const Initialization_shape& shape1, const Initialization_shape& shape2,
                                const Initialization_settings& s, Initialization_pass_cache& cache)
{
  Initialization_settings sampling = s;
  sampling.distortion_repair_passes = std::max(1, s.distortion_repair_passes);
  prepare_pass_cache<ConcurrencyTag>(shape1, shape2, sampling, cache);
}

/// The geodesic distortion of a pair of maps on the distortion samples of both meshes (the mean of
/// both directions, see map_distortion()); with `core_12` and `core_21` not null, also the
/// isometric cores of both maps (distortion_core()).
template <typename ConcurrencyTag>
double pair_distortion(const Initialization_shape& shape1, const Initialization_shape& shape2,
                       const Initialization_settings& s, const Initialization_pass_cache& cache,
                       const std::vector<std::size_t>& map_12, const std::vector<std::size_t>& map_21,
                       std::vector<int>* core_12 = nullptr, std::vector<int>* core_21 = nullptr)
{
  std::vector<int> images12, images21;
  for(int v : cache.first.samples.distortion_vertices) images12.push_back(int(map_12[std::size_t(v)]));
  for(int v : cache.second.samples.distortion_vertices) images21.push_back(int(map_21[std::size_t(v)]));
  Vertex_set_distances d2, d1;
  invoke_both<ConcurrencyTag>(
      [&] {
        d2.compute<ConcurrencyTag>(cache.second.geodesics, images12, std::sqrt(shape2.spectrum->total_area()),
                                   &cache.second.rows);
      },
      [&] {
        d1.compute<ConcurrencyTag>(cache.first.geodesics, images21, std::sqrt(shape1.spectrum->total_area()),
                                   &cache.first.rows);
      });
  if(core_12)
    *core_12 = distortion_core(cache.first.sample_distances, d2, images12, s.distortion_core_tolerance,
                               s.distortion_core_agreement);
  if(core_21)
    *core_21 = distortion_core(cache.second.sample_distances, d1, images21, s.distortion_core_tolerance,
                               s.distortion_core_agreement);
  return 0.5 * (map_distortion(cache.first.sample_distances, d2, images12) +
                map_distortion(cache.second.sample_distances, d1, images21));
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DISTORTION_H
