// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Ground-truth-free diagnostics of a pair of maps, over each mesh and over regions of it: cycle
// consistency, the distortion of mid-range geodesic distances, the distance between the
// descriptors of matched vertices and the refinement's MRF energy. match_shapes() reports them for
// the maps that entered the refinement and for the maps it returns, so that a caller (and the
// benchmark) can tell where the refinement helped without knowing the true correspondence.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_DIAGNOSTICS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_DIAGNOSTICS_H

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_distortion.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_selection.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Ground-truth-free measures of a map x from a source mesh S to a target mesh T (with the
/// opposite map y from T to S), over all vertices of S or over one region of S. Lower is better
/// for every measure; distances are relative to the square root of each mesh's area.
struct Map_diagnostics
{
  /// Source vertices measured.
  std::size_t vertices = 0;
  /// The fraction of them with y(x(i)) != i (Eq. 4 of the paper, this direction).
  double inconsistent_fraction = 0;
  /// The mean Euclidean distance between i and y(x(i)).
  double cycle_error = 0;
  /// The mean mid-range geodesic distortion (see Selection_result) over the scored vertices among
  /// them: about 1000 per mesh, spread by index, and the centre of every region.
  double distortion = 0;
  /// The scored vertices among them.
  std::size_t distortion_samples = 0;
  /// The mean over pairs of far apart vertices (a, b) of |d_S(a, b) - d_T(x(a), x(b))|: the
  /// geodesic distances between the first 64 farthest point samples of the source and between
  /// their images (the pairs whose first vertex is in the region, for a region). Unlike
  /// `distortion`, it sees maps that are smooth but wrong as a whole (a part sent to another part).
  double global_distortion = 0;
  /// The mean squared distance |F_S(i) - F_T(x(i))|^2 between the descriptors (the refinement's
  /// descriptor stack) of i and of its match.
  double descriptor_distance = 0;
  /// The area-weighted fraction of the source triangles (with three distinct images) whose image
  /// is reversed on the target (its normal against the target's vertex normals): about 0 for an
  /// orientation-preserving map, 1 for a mirror map (a left-right flip), 1/2 for a scrambled one.
  /// Both meshes are taken to be oriented the same way (e.g. outwards). A region's triangles are
  /// those whose first corner is in the region.
  double orientation_reversal = 0;
  /// The same at the scale of the far apart samples (those of `global_distortion`): for each
  /// sample a and each two b, c of its four nearest samples, whether the turn from b to c around a
  /// (seen from the normal at a, in the tangent plane) and the turn between their images (seen
  /// from the target's normal at the image of a) have opposite signs; triples without a clear
  /// turn on either side are left out. Local noise of the map, which reverses small triangles at
  /// random, does not reverse these; a mirror map does.
  double global_orientation_reversal = 0;
  /// The refinement's MRF energy per vertex: mu |F_S(i) - F_T(x(i))|^2 + lambda d_S(i, y(x(i)))
  /// plus half the sum over the mesh edges (i, j) of |d_S(i, j) - d_T(x(i), x(j))|, with the mu
  /// and lambda the refinement used (so the energies of all vertices add up to the energy of the
  /// map on the MRF of Eq. 1 with the cycle term and edge pairwise terms).
  double energy = 0;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The diagnostics of the map of one direction: over the whole source mesh and per region of it.
struct Direction_diagnostics
{
  /// Over every vertex of the source mesh.
  Map_diagnostics whole;
  /// One entry per region of the source mesh (see Matching_diagnostics::regions_1; empty when
  /// `diagnostic_regions` is 0).
  std::vector<Map_diagnostics> regions;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The ground-truth-free diagnostics of match_shapes(), for the maps that entered the refinement
/// (`before`) and the returned maps (`after`); index 0 is the map 1 -> 2 (over the vertices and
/// regions of mesh 1), index 1 the map 2 -> 1.
struct Matching_diagnostics
{
  /// Whether they were computed (always by match_shapes()).
  bool computed = false;
  /// The region of each vertex of mesh 1 and of mesh 2 (in [0, number of regions)): the cells of
  /// `diagnostic_regions` farthest point samples, each vertex in the cell of its nearest sample
  /// along the edges. Empty when the diagnostics were not computed.
  std::vector<int> regions_1, regions_2;
  /// The maps that entered the refinement (`before`) and the returned maps (`after`).
  std::array<Direction_diagnostics, 2> before, after;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// How far match_shapes() trusts the maps it returns, without ground truth: maps that are wrong
/// as a whole (a mirror image, parts sent to other parts) reverse the orientation of the surface
/// or distort the distances between far apart points (see Map_diagnostics).
struct Matching_confidence
{
  /// In [0, 1]: the lower of the two directions' scores. The score of a map is
  /// 1 - (global_orientation_reversal / `orientation_reversal_scale` + global_distortion /
  /// `global_distortion_scale`) / 2, clamped to [0, 1]: 1 for a map that keeps the orientation
  /// and the far distances, 0.5 for a map that reverses `orientation_reversal_scale` of the far
  /// triples or distorts the far distances by `global_distortion_scale` (or a sum of parts of
  /// both), about 0.17 for a mirror map and 0 for a scrambled one. Both measures are noisy on
  /// good maps between different species (a sample whose neighbour's image lands far away turns
  /// at random), so each weighs the evidence of the other rather than deciding alone.
  double score = 1;
  /// The score of the map 1 -> 2 and of the map 2 -> 1.
  std::array<double, 2> direction_scores{{1, 1}};
  /// Whether `score` is below `confidence_threshold`: the maps are probably wrong as a whole.
  bool low = false;
  /// The measures of the direction that set the score, e.g. "map 1->2: orientation reversal
  /// 0.450, global distortion 0.080" (of the far apart samples).
  std::string reason;

  /// The global distortion that alone makes a map's score 0.5. Calibrated with
  /// `orientation_reversal_scale` on the maps of the TOSCA_nonIso, FAUST_r and TOSCA_r benchmark
  /// subsets (see doc/coupled_refinement.md).
  static constexpr double global_distortion_scale = 0.18;
  /// The far orientation reversal that alone makes a map's score 0.5.
  static constexpr double orientation_reversal_scale = 0.6;
};

namespace internal {

/// The turn from b to c around a, seen from the unit normal `n` at a: ((b - a) x (c - a)) . n
/// over |b - a| |c - a|, the sine of the angle between the two directions in the tangent plane
/// (shrunk when they leave it). Returns false when its magnitude is below 1/4: no clear turn.
inline bool tangent_turn(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const Eigen::Vector3d& n, double& turn)
{
  const Eigen::Vector3d u = b - a, v = c - a;
  const double lengths = u.norm() * v.norm();
  if(!(lengths > 0) || !(n.squaredNorm() > 0)) return false;
  turn = u.cross(v).dot(n) / lengths;
  return std::abs(turn) >= 0.25;
}

/// The confidence of the returned maps (`after`) of `d`.
inline Matching_confidence matching_confidence(const Matching_diagnostics& d, double threshold)
{
  Matching_confidence c;
  auto clamp01 = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  for(int direction = 0; direction < 2; ++direction)
  {
    const Map_diagnostics& m = d.after[std::size_t(direction)].whole;
    const double evidence = m.global_orientation_reversal / Matching_confidence::orientation_reversal_scale +
                            m.global_distortion / Matching_confidence::global_distortion_scale;
    const double score = clamp01(1 - evidence / 2);
    c.direction_scores[std::size_t(direction)] = score;
    if(direction == 0 || score < c.score)
    {
      c.score = score;
      std::ostringstream why;
      why.setf(std::ios::fixed);
      why.precision(3);
      why << (direction == 0 ? "map 1->2: " : "map 2->1: ") << "orientation reversal "
          << m.global_orientation_reversal << ", global distortion " << m.global_distortion;
      c.reason = why.str();
    }
  }
  c.low = c.score < threshold;
  return c;
}

/// The cells of `count` farthest point samples of `m` (edge-graph distances, the first sample at
/// vertex 0): region[v] is the index of the sample nearest to v along the edges (ties: the
/// smaller index), 0 for vertices no sample reaches. `centers` receives the samples.
inline std::vector<int> farthest_point_regions(const Indexed_mesh& m, int count, std::vector<int>& centers)
{
  const int n = m.number_of_vertices();
  std::vector<int> region(std::size_t(n), 0);
  centers.clear();
  if(n == 0 || count <= 0) return region;
  centers = farthest_samples(m, std::min(count, n));
  const Edge_length_graph g(m);
  std::vector<double> distance(std::size_t(n), std::numeric_limits<double>::infinity());
  std::vector<int> label(std::size_t(n), -1);
  typedef std::pair<double, std::pair<int, int> > Item;  // (distance, (label, vertex))
  std::priority_queue<Item, std::vector<Item>, std::greater<Item> > heap;
  for(std::size_t c = 0; c < centers.size(); ++c)
  {
    distance[std::size_t(centers[c])] = 0;
    heap.push({0.0, {int(c), centers[c]}});
  }
  while(!heap.empty())
  {
    const Item top = heap.top();
    heap.pop();
    const int v = top.second.second;
    if(label[std::size_t(v)] >= 0) continue;
    label[std::size_t(v)] = top.second.first;
    for(int k = m.neighbor_offsets[v]; k < m.neighbor_offsets[v + 1]; ++k)
    {
      const int w = m.neighbors[k];
      const double d = top.first + g.lengths[k];
      if(label[std::size_t(w)] < 0 && d <= distance[std::size_t(w)])
      {
        distance[std::size_t(w)] = d;
        heap.push({d, {top.second.first, w}});
      }
    }
  }
  for(int v = 0; v < n; ++v) region[std::size_t(v)] = std::max(0, label[std::size_t(v)]);
  return region;
}

/// The weights of the energy term (those of the refinement), the neighbourhoods of the
/// distortion term (those of the selection) and the number of regions.
struct Diagnostics_settings
{
  double unary_weight = 1, consistency_weight = 0;
  double radius = 0.06;
  int samples = 8;
  int regions = 16;

  static Diagnostics_settings from(const Refinement_settings& r, const Selection_settings& s)
  {
    return {r.unary_weight, r.use_coupling ? r.consistency_weight : 0.0, s.radius, s.samples, s.diagnostic_regions};
  }
};

/// The regions of one mesh, its scored vertices (every stride-th vertex and every region centre,
/// sorted), and its far apart samples with their geodesic distances (for `global_distortion`).
struct Diagnostics_layout
{
  static constexpr int global_samples = 64;
  /// The nearest samples of each sample whose turns `global_orientation_reversal` compares.
  static constexpr int orientation_neighbors = 4;
  std::vector<int> regions, centers, scored;
  int number_of_regions = 0;  ///< 0: the whole mesh only
  std::vector<int> samples;   ///< the first `global_samples` farthest point samples
  Vertex_set_distances sample_distances;  ///< between them, over the square root of the area
  /// The `orientation_neighbors` samples nearest to each sample, nearest first (fewer when there
  /// are fewer samples).
  std::vector<std::vector<int> > sample_neighbors;

  template <typename ConcurrencyTag>
  Diagnostics_layout(const Indexed_mesh& m, const Fast_marching_geometry& g, int count, ConcurrencyTag)
  {
    const int n = m.number_of_vertices();
    regions = farthest_point_regions(m, count, centers);
    number_of_regions = int(centers.size());
    samples = farthest_samples(m, std::min(n, global_samples));
    sample_distances.compute<ConcurrencyTag>(g, samples, std::sqrt(m.total_area));
    for(int a : samples)
    {
      std::vector<std::pair<double, int> > others;  // (distance, sample), in the samples' order
      for(int b : samples)
        if(b != a) others.emplace_back(sample_distances.distance(a, b), b);
      const std::size_t k = std::min(others.size(), std::size_t(orientation_neighbors));
      std::stable_sort(others.begin(), others.end(),
                       [](const std::pair<double, int>& x, const std::pair<double, int>& y) { return x.first < y.first; });
      std::vector<int> nearest;
      for(std::size_t i = 0; i < k; ++i) nearest.push_back(others[i].second);
      sample_neighbors.push_back(std::move(nearest));
    }
    const int stride = std::max(1, n / 1000);
    for(int v = 0; v < n; v += stride) scored.push_back(v);
    scored.insert(scored.end(), centers.begin(), centers.end());
    std::sort(scored.begin(), scored.end());
    scored.erase(std::unique(scored.begin(), scored.end()), scored.end());
  }
};

/// The diagnostics of the map `x` from `S` to `T` (opposite map `y`), over `S` and its regions.
template <typename ConcurrencyTag>
Direction_diagnostics direction_diagnostics(const Shape_data& S, const Fast_marching_geometry& gs, const Shape_data& T,
                                            const Fast_marching_geometry& gt, const std::vector<int>& x,
                                            const std::vector<int>& y, const Diagnostics_layout& layout,
                                            const Diagnostics_settings& settings)
{
  const int n = S.number_of_vertices();
  const double scale_s = std::sqrt(S.mesh.total_area);
  const double unit_s = 1.0 / S.scale, unit_t = 1.0 / T.scale;
  // Per vertex: inconsistent, cycle error, descriptor distance, energy.
  std::vector<std::array<double, 4> > values(static_cast<std::size_t>(n));
  std::visit(
      [&](const auto& source_oracle) {
        std::visit(
            [&](const auto& target_oracle) {
              parallel_for_ranges<ConcurrencyTag>(
                  std::size_t(n),
                  [&](std::size_t begin, std::size_t end) {
                    for(std::size_t u = begin; u < end; ++u)
                    {
                      const int i = int(u), xi = x[u], back = y[std::size_t(xi)];
                      const double descriptor = (S.descriptors.row(i) - T.descriptors.row(xi)).squaredNorm();
                      double pairwise = 0;
                      for(const int* j = S.mesh.neighbors_begin(i); j != S.mesh.neighbors_end(i); ++j)
                        pairwise += std::abs(source_oracle.distance(i, *j) * unit_s -
                                             target_oracle.distance(xi, x[std::size_t(*j)]) * unit_t);
                      const double cycle_term =
                          back == i ? 0.0 : settings.consistency_weight * source_oracle.distance(i, back) * unit_s;
                      values[u] = {double(back != i),
                                   (S.mesh.points.row(i) - S.mesh.points.row(back)).norm() / scale_s, descriptor,
                                   settings.unary_weight * descriptor + cycle_term + 0.5 * pairwise};
                    }
                  },
                  256);
            },
            T.oracle);
      },
      S.oracle);
  // Orientation: the reversed and the counted area of the source triangles, per region of their
  // first corner.
  const Indexed_mesh::Points target_normals = vertex_normals(T.mesh);
  std::vector<double> reversed_area(std::size_t(std::max(1, layout.number_of_regions)), 0.0),
      counted_area(reversed_area.size(), 0.0);
  double reversed_total = 0, counted_total = 0;
  for(int t = 0; t < S.mesh.number_of_triangles(); ++t)
  {
    const int orientation = image_orientation(S.mesh, T.mesh, target_normals, x, t);
    if(orientation < 0) continue;
    const double area = S.mesh.triangle_areas[std::size_t(t)];
    const std::size_t r = layout.number_of_regions > 0 ? std::size_t(layout.regions[std::size_t(S.mesh.triangles(t, 0))]) : 0;
    counted_area[r] += area;
    counted_total += area;
    if(orientation == 0)
    {
      reversed_area[r] += area;
      reversed_total += area;
    }
  }
  // Orientation at the samples' scale: each sample with each two of its nearest samples.
  const Indexed_mesh::Points source_normals = vertex_normals(S.mesh);
  std::vector<double> far_reversed(reversed_area.size(), 0.0), far_counted(reversed_area.size(), 0.0);
  double far_reversed_total = 0, far_counted_total = 0;
  for(std::size_t k = 0; k < layout.samples.size(); ++k)
  {
    const int a = layout.samples[k];
    const std::vector<int>& nearest = layout.sample_neighbors[k];
    for(std::size_t i = 0; i < nearest.size(); ++i)
      for(std::size_t j = i + 1; j < nearest.size(); ++j)
      {
        const int b = nearest[i], c = nearest[j];
        const int xa = x[std::size_t(a)], xb = x[std::size_t(b)], xc = x[std::size_t(c)];
        if(xa == xb || xb == xc || xa == xc) continue;
        // The turn from b to c seen from the normal at a, on each side; triples whose turn is not
        // clear on both (b and c nearly in line with a or on opposite sides of it, or off the
        // tangent plane, as around a limb) are left out.
        double turn_s, turn_t;
        if(!tangent_turn(S.mesh.point(a), S.mesh.point(b), S.mesh.point(c), source_normals.row(a).transpose(),
                         turn_s) ||
           !tangent_turn(T.mesh.point(xa), T.mesh.point(xb), T.mesh.point(xc), target_normals.row(xa).transpose(),
                         turn_t))
          continue;
        const bool reversed = (turn_s > 0) != (turn_t > 0);
        const std::size_t r = layout.number_of_regions > 0 ? std::size_t(layout.regions[std::size_t(a)]) : 0;
        far_counted[r] += 1;
        far_counted_total += 1;
        if(reversed)
        {
          far_reversed[r] += 1;
          far_reversed_total += 1;
        }
      }
  }
  // Global distortion: the samples' distances against their images'.
  std::vector<int> images;
  for(int a : layout.samples) images.push_back(x[std::size_t(a)]);
  Vertex_set_distances image_distances;
  image_distances.compute<ConcurrencyTag>(gt, images, std::sqrt(T.mesh.total_area));
  std::vector<double> global_sum(reversed_area.size(), 0.0), global_count(reversed_area.size(), 0.0);
  double global_total = 0;
  for(std::size_t a = 0; a < layout.samples.size(); ++a)
  {
    double sum = 0;
    for(std::size_t b = 0; b < layout.samples.size(); ++b)
      if(a != b)
        sum += std::abs(layout.sample_distances.distance(layout.samples[a], layout.samples[b]) -
                        image_distances.distance(images[a], images[b]));
    const std::size_t r =
        layout.number_of_regions > 0 ? std::size_t(layout.regions[std::size_t(layout.samples[a])]) : 0;
    global_sum[r] += sum;
    global_count[r] += double(layout.samples.size() - 1);
    global_total += sum;
  }
  const std::vector<double> distortion = midrange_distortion_at<ConcurrencyTag>(
      S.mesh, gs, T.mesh, gt, x, settings.radius, settings.samples, layout.scored);

  Direction_diagnostics out;
  out.regions.assign(std::size_t(layout.number_of_regions), Map_diagnostics());
  auto add = [](Map_diagnostics& d, const std::array<double, 4>& v) {
    ++d.vertices;
    d.inconsistent_fraction += v[0];
    d.cycle_error += v[1];
    d.descriptor_distance += v[2];
    d.energy += v[3];
  };
  const bool per_region = !out.regions.empty();
  for(int i = 0; i < n; ++i)
  {
    add(out.whole, values[std::size_t(i)]);
    if(per_region) add(out.regions[std::size_t(layout.regions[std::size_t(i)])], values[std::size_t(i)]);
  }
  for(std::size_t k = 0; k < layout.scored.size(); ++k)
  {
    out.whole.distortion += distortion[k];
    ++out.whole.distortion_samples;
    if(!per_region) continue;
    Map_diagnostics& r = out.regions[std::size_t(layout.regions[std::size_t(layout.scored[k])])];
    r.distortion += distortion[k];
    ++r.distortion_samples;
  }
  auto finish = [](Map_diagnostics& d) {
    const double c = d.vertices > 0 ? double(d.vertices) : 1.0;
    d.inconsistent_fraction /= c;
    d.cycle_error /= c;
    d.descriptor_distance /= c;
    d.energy /= c;
    if(d.distortion_samples > 0) d.distortion /= double(d.distortion_samples);
  };
  finish(out.whole);
  for(Map_diagnostics& r : out.regions) finish(r);
  auto fraction = [](double part, double whole) { return whole > 0 ? part / whole : 0.5; };
  out.whole.orientation_reversal = fraction(reversed_total, counted_total);
  out.whole.global_orientation_reversal = fraction(far_reversed_total, far_counted_total);
  const double pairs = double(layout.samples.size()) * double(layout.samples.size() - 1);
  out.whole.global_distortion = pairs > 0 ? global_total / pairs : 0.0;
  for(std::size_t r = 0; r < out.regions.size(); ++r)
  {
    out.regions[r].orientation_reversal = fraction(reversed_area[r], counted_area[r]);
    out.regions[r].global_orientation_reversal = fraction(far_reversed[r], far_counted[r]);
    out.regions[r].global_distortion = global_count[r] > 0 ? global_sum[r] / global_count[r] : 0.0;
  }
  return out;
}

/// The diagnostics of the maps before (`b12`, `b21`) and after (`a12`, `a21`) the refinement.
template <typename ConcurrencyTag>
Matching_diagnostics matching_diagnostics(const Shape_data& M1, const Fast_marching_geometry& g1, const Shape_data& M2,
                                          const Fast_marching_geometry& g2, const std::vector<int>& b12,
                                          const std::vector<int>& b21, const std::vector<int>& a12,
                                          const std::vector<int>& a21, const Diagnostics_settings& settings)
{
  Matching_diagnostics d;
  std::optional<Diagnostics_layout> l1, l2;
  invoke_both<ConcurrencyTag>([&] { l1.emplace(M1.mesh, g1, settings.regions, ConcurrencyTag()); },
                              [&] { l2.emplace(M2.mesh, g2, settings.regions, ConcurrencyTag()); });
  // The same maps before and after (no refinement, or nothing changed) are measured once.
  const bool same = b12 == a12 && b21 == a21;
  invoke_both<ConcurrencyTag>(
      [&] {
        d.before[0] = direction_diagnostics<ConcurrencyTag>(M1, g1, M2, g2, b12, b21, *l1, settings);
        d.after[0] =
            same ? d.before[0] : direction_diagnostics<ConcurrencyTag>(M1, g1, M2, g2, a12, a21, *l1, settings);
      },
      [&] {
        d.before[1] = direction_diagnostics<ConcurrencyTag>(M2, g2, M1, g1, b21, b12, *l2, settings);
        d.after[1] =
            same ? d.before[1] : direction_diagnostics<ConcurrencyTag>(M2, g2, M1, g1, a21, a12, *l2, settings);
      });
  d.regions_1 = std::move(l1->regions);
  d.regions_2 = std::move(l2->regions);
  d.computed = true;
  return d;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_DIAGNOSTICS_H
