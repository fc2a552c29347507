// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Evaluation toolkit: geodesic error of a point-to-point map against ground-truth
// correspondences (the protocol of Kim, Lipman and Funkhouser 2011 used by the shape-matching
// literature), its symmetry-tolerant variant, cycle consistency of a map and its inverse, and
// coverage. Geodesic distances come from our fast marching with early termination: a sample whose
// map is right costs almost nothing, so evaluating 5000 samples of a good map is fast.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_EVALUATION_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_EVALUATION_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Summary of a set of normalised errors (geodesic errors of a map, or cycle-consistency
/// distances), as reported by shape-matching benchmarks.
struct Error_statistics
{
  std::vector<double> errors;      ///< one value per sample, in sample order
  double mean = 0;                 ///< mean of `errors`
  double median = 0;               ///< median of `errors`
  double maximum = 0;              ///< largest error
  std::vector<double> thresholds;  ///< thresholds t of the cumulative curve, from 0 to 0.25
  std::vector<double> cumulative;  ///< fraction of samples with error <= thresholds[i]

  /// Fraction of samples whose error is at most `t`.
  double fraction_below(double t) const
  {
    if(errors.empty()) return 0;
    const std::size_t k = static_cast<std::size_t>(
        std::count_if(errors.begin(), errors.end(), [t](double e) { return e <= t; }));
    return static_cast<double>(k) / static_cast<double>(errors.size());
  }
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes mean, median, maximum and the cumulative curve of `errors` over
/// `number_of_thresholds` thresholds evenly spaced in [0, `max_threshold`].
inline Error_statistics error_statistics(std::vector<double> errors, double max_threshold = 0.25,
                                         int number_of_thresholds = 101)
{
  if(number_of_thresholds < 2 || !(max_threshold > 0))
    throw Invalid_parameter_error("error_statistics: need at least 2 thresholds and a positive maximum");
  Error_statistics s;
  s.errors = std::move(errors);
  const std::size_t n = s.errors.size();
  s.thresholds.resize(static_cast<std::size_t>(number_of_thresholds));
  s.cumulative.assign(static_cast<std::size_t>(number_of_thresholds), 0.0);
  for(int k = 0; k < number_of_thresholds; ++k)
    s.thresholds[static_cast<std::size_t>(k)] = max_threshold * k / (number_of_thresholds - 1);
  if(n == 0) return s;
  std::vector<double> sorted = s.errors;
  std::sort(sorted.begin(), sorted.end());
  s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(n);
  s.median = (n % 2 == 1) ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  s.maximum = sorted.back();
  for(std::size_t k = 0; k < s.thresholds.size(); ++k)
  {
    const std::size_t below = static_cast<std::size_t>(
        std::upper_bound(sorted.begin(), sorted.end(), s.thresholds[k]) - sorted.begin());
    s.cumulative[k] = static_cast<double>(below) / static_cast<double>(n);
  }
  return s;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Cycle consistency of a map `T12` and a map `T21` back: for every vertex x of the source,
/// \f$ d_1(T_{21}(T_{12}(x)), x) / \sqrt{\mathrm{area}(M_1)} \f$.
struct Cycle_consistency
{
  Error_statistics distances;        ///< the normalised distances, one per source vertex
  double fixed_point_fraction = 0;   ///< fraction of vertices with T21(T12(x)) = x exactly
};

namespace internal {

/// Geodesic distances between vertex pairs of one mesh, by fast marching with early termination
/// (one run per pair, stopped as soon as the other vertex is final), one workspace per thread.
class Pair_geodesic_distances
{
public:
  explicit Pair_geodesic_distances(const Indexed_mesh& m) : mesh_(&m), geometry_(m) {}

  const Indexed_mesh& mesh() const { return *mesh_; }
  const Fast_marching_geometry& geometry() const { return geometry_; }

  /// The distance from `source` to the nearest of `targets[0 .. count)`: an early-terminated run
  /// to the first target, then runs truncated at the best distance so far for the others (each
  /// costs no more than the first). Vertices in another connected component are at infinite
  /// distance.
  static double nearest_distance(Fast_marching_workspace& ws, int source, const int* targets, std::size_t count)
  {
    double best = std::numeric_limits<double>::infinity();
    for(std::size_t i = 0; i < count; ++i)
    {
      if(targets[i] == source) return 0.0;
      if(targets[i] < 0) continue;
      ws.run(&source, 1, best, targets + i, 1);
      best = std::min(best, ws.distance(targets[i]));
    }
    return best;
  }

  /// For every pair k, the distance from `sources[k]` to the nearest of
  /// `targets[k * per_pair .. (k + 1) * per_pair)`, divided by `scale`. Runs in parallel with
  /// Parallel_tag.
  template <typename ConcurrencyTag>
  void nearest_distances(const std::vector<int>& sources, const std::vector<int>& targets, std::size_t per_pair,
                         double scale, std::vector<double>& out) const
  {
    out.assign(sources.size(), 0.0);
    internal::parallel_for_ranges<ConcurrencyTag>(
        sources.size(),
        [&](std::size_t b, std::size_t e) {
          Fast_marching_workspace ws(geometry_);
          for(std::size_t k = b; k < e; ++k)
            out[k] = nearest_distance(ws, sources[k], targets.data() + k * per_pair, per_pair) / scale;
        },
        256);
  }

private:
  const Indexed_mesh* mesh_;
  Fast_marching_geometry geometry_;
};

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Evaluates maps into one target mesh against ground truth, reusing the mesh's precomputed
/// fast-marching geometry: build it once per target and evaluate many maps.
///
/// The geodesic error of a map \f$T\f$ at sample \f$k\f$ with ground truth
/// \f$(a_k, b_k)\f$ is \f$ e_k = d_2(T(a_k), b_k) / \sqrt{\mathrm{area}(M_2)} \f$ (Kim et al. 2011).
/// Distances are computed by fast marching (first order, about 1% of the distance on regular
/// meshes, exact along mesh edges).
///
/// \tparam TriangleMesh a model of `FaceGraph` (triangles only)
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (samples in parallel)
template <typename ConcurrencyTag = CGAL::Sequential_tag>
class Map_evaluator
{
public:
  /// Builds the evaluator for meshes given as a flat copy.
  explicit Map_evaluator(const internal::Indexed_mesh& mesh)
      : mesh_(std::make_shared<internal::Indexed_mesh>(mesh)), distances_(*mesh_)
  {}

  /// Builds the evaluator for a triangle soup (vertex i is point i).
  explicit Map_evaluator(const Triangle_soup& soup)
      : Map_evaluator(internal::make_soup_indexed_mesh(soup, lenient_requirements(), "mesh"))
  {}

  /// Builds the evaluator for `tm`.
  /// \param tm the mesh the maps go to (or come from)
  /// \param np optional `vertex_point_map`, `vertex_index_map` (vertex numbering of the maps)
  template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
  explicit Map_evaluator(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
      : Map_evaluator(internal::make_indexed_mesh(tm, np, lenient_requirements(), "mesh"))
  {}

  /// Number of vertices of the mesh.
  std::size_t number_of_vertices() const { return static_cast<std::size_t>(mesh_->number_of_vertices()); }
  /// \f$\sqrt{\mathrm{area}}\f$, the normalisation of every distance.
  double scale() const { return std::sqrt(mesh_->total_area); }

  /// Geodesic errors of `map` (from a source mesh to this mesh) at the ground-truth samples:
  /// sample k says that source vertex `gt_source[k]` corresponds to vertex `gt_target[k]` of this
  /// mesh.
  /// \throws Invalid_map_error when a map entry or ground-truth entry is out of range, or the two
  /// ground-truth lists have different lengths
  Error_statistics geodesic_errors(const Vertex_index_map_vector& map, const Vertex_index_map_vector& gt_source,
                                   const Vertex_index_map_vector& gt_target) const
  {
    std::vector<int> sources, targets;
    prepare(map, gt_source, gt_target, nullptr, sources, targets);
    std::vector<double> d;
    distances_.template nearest_distances<ConcurrencyTag>(sources, targets, 1, scale(), d);
    return error_statistics(std::move(d));
  }

  /// Symmetry-tolerant geodesic errors: per sample the smaller of the errors against
  /// `gt_target` and against the mirrored ground truth `gt_target_symmetric`.
  Error_statistics symmetric_geodesic_errors(const Vertex_index_map_vector& map,
                                             const Vertex_index_map_vector& gt_source,
                                             const Vertex_index_map_vector& gt_target,
                                             const Vertex_index_map_vector& gt_target_symmetric) const
  {
    std::vector<int> sources, targets;
    prepare(map, gt_source, gt_target, &gt_target_symmetric, sources, targets);
    std::vector<double> d;
    distances_.template nearest_distances<ConcurrencyTag>(sources, targets, 2, scale(), d);
    return error_statistics(std::move(d));
  }

  /// Cycle consistency of `map_12` (from this mesh to another) and `map_21` (back to this mesh):
  /// the normalised distance between x and T21(T12(x)) for every vertex x of this mesh.
  /// \throws Invalid_map_error when the maps do not fit the meshes
  Cycle_consistency cycle_consistency(const Vertex_index_map_vector& map_12,
                                      const Vertex_index_map_vector& map_21) const
  {
    const std::size_t n = number_of_vertices();
    check_vertex_map(map_12, n, map_21.size(), "map 1->2");
    check_vertex_map(map_21, map_21.size(), n, "map 2->1");
    std::vector<int> sources(n), targets(n);
    std::size_t fixed = 0;
    for(std::size_t x = 0; x < n; ++x)
    {
      sources[x] = static_cast<int>(x);
      targets[x] = static_cast<int>(map_21[map_12[x]]);
      fixed += targets[x] == static_cast<int>(x);
    }
    std::vector<double> d;
    distances_.template nearest_distances<ConcurrencyTag>(sources, targets, 1, scale(), d);
    Cycle_consistency c;
    c.distances = error_statistics(std::move(d));
    c.fixed_point_fraction = static_cast<double>(fixed) / static_cast<double>(n);
    return c;
  }

private:
  static internal::Mesh_requirements lenient_requirements()
  {
    internal::Mesh_requirements r;
    r.allow_isolated_vertices = true;
    r.allow_non_manifold = true;
    r.allow_degenerate_faces = true;
    return r;
  }

  void prepare(const Vertex_index_map_vector& map, const Vertex_index_map_vector& gt_source,
               const Vertex_index_map_vector& gt_target, const Vertex_index_map_vector* gt_symmetric,
               std::vector<int>& sources, std::vector<int>& targets) const
  {
    const std::size_t n = number_of_vertices();
    if(gt_source.size() != gt_target.size())
      throw Invalid_map_error("ground truth: " + std::to_string(gt_source.size()) + " source samples but " +
                              std::to_string(gt_target.size()) + " target samples");
    if(gt_symmetric && gt_symmetric->size() != gt_target.size())
      throw Invalid_map_error("symmetric ground truth has " + std::to_string(gt_symmetric->size()) +
                              " samples, the direct one " + std::to_string(gt_target.size()));
    check_vertex_indices(map, n, "map");
    check_vertex_indices(gt_source, map.size(), "ground truth on the source");
    check_vertex_indices(gt_target, n, "ground truth on the target");
    if(gt_symmetric) check_vertex_indices(*gt_symmetric, n, "symmetric ground truth on the target");
    const std::size_t per = gt_symmetric ? 2 : 1;
    sources.resize(gt_source.size());
    targets.resize(gt_source.size() * per);
    for(std::size_t k = 0; k < gt_source.size(); ++k)
    {
      // Marching from the mapped vertex reaches both ground-truth vertices in one run.
      sources[k] = static_cast<int>(map[gt_source[k]]);
      targets[k * per] = static_cast<int>(gt_target[k]);
      if(gt_symmetric) targets[k * per + 1] = static_cast<int>((*gt_symmetric)[k]);
    }
  }

  std::shared_ptr<internal::Indexed_mesh> mesh_;
  internal::Pair_geodesic_distances distances_;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Geodesic error of a map from a source mesh to `target` against ground truth (see
/// `Map_evaluator::geodesic_errors()`). Vertex indices are those of the target's vertex index map.
/// \param target the target mesh
/// \param map the vertex of `target` matched to each source vertex
/// \param gt_source, gt_target the ground truth: source vertex `gt_source[k]` corresponds to
///   target vertex `gt_target[k]`
/// \param np optional `vertex_point_map`, `vertex_index_map` of `target`
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Error_statistics map_geodesic_errors(const TriangleMesh& target, const Vertex_index_map_vector& map,
                                     const Vertex_index_map_vector& gt_source,
                                     const Vertex_index_map_vector& gt_target,
                                     const NamedParameters& np = parameters::default_values())
{
  return Map_evaluator<ConcurrencyTag>(target, np).geodesic_errors(map, gt_source, gt_target);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Symmetry-tolerant geodesic error (see `Map_evaluator::symmetric_geodesic_errors()`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Error_statistics symmetric_map_geodesic_errors(const TriangleMesh& target, const Vertex_index_map_vector& map,
                                               const Vertex_index_map_vector& gt_source,
                                               const Vertex_index_map_vector& gt_target,
                                               const Vertex_index_map_vector& gt_target_symmetric,
                                               const NamedParameters& np = parameters::default_values())
{
  return Map_evaluator<ConcurrencyTag>(target, np)
      .symmetric_geodesic_errors(map, gt_source, gt_target, gt_target_symmetric);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Cycle consistency of `map_12` from `source` to another mesh and `map_21` back (see
/// `Map_evaluator::cycle_consistency()`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Cycle_consistency cycle_consistency(const TriangleMesh& source, const Vertex_index_map_vector& map_12,
                                    const Vertex_index_map_vector& map_21,
                                    const NamedParameters& np = parameters::default_values())
{
  return Map_evaluator<ConcurrencyTag>(source, np).cycle_consistency(map_12, map_21);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Coverage of a map: the fraction of the `target_size` target vertices that some source vertex
/// is mapped to. \throws Invalid_map_error when an entry is out of range.
inline double map_coverage(const Vertex_index_map_vector& map, std::size_t target_size)
{
  if(target_size == 0) throw Invalid_map_error("map coverage: the target mesh has no vertex");
  check_vertex_indices(map, target_size, "map");
  std::vector<char> hit(target_size, 0);
  for(std::size_t v : map) hit[v] = 1;
  return static_cast<double>(std::count(hit.begin(), hit.end(), 1)) / static_cast<double>(target_size);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The number of source vertices x with T21(T12(x)) != x, summed over both directions: up to a
/// factor 2, the cycle-consistency measure \f$ \sum \| X_{ba} X_{ab} - I \|_F^2 \f$ of the paper's
/// Eq. (4).
inline std::size_t number_of_inconsistent_vertices(const Vertex_index_map_vector& map_12,
                                                   const Vertex_index_map_vector& map_21)
{
  std::size_t count = 0;
  for(std::size_t x = 0; x < map_12.size(); ++x) count += map_21[map_12[x]] != x;
  for(std::size_t y = 0; y < map_21.size(); ++y) count += map_12[map_21[y]] != y;
  return count;
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_EVALUATION_H
