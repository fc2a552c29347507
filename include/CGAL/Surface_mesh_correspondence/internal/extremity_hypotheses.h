// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Hypotheses for pairs far from isometric: the extremities of both shapes (the tips of limbs,
// head, tail), their assignments that best preserve the proportions of their geodesic distances,
// and a pass of the initialisation from each assignment as anchor landmarks; the hypothesis whose
// maps best keep the local shape (SHOT) and the sample distances is kept, unless its maps distort
// the sample distances much more than the descriptor-based maps.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_EXTREMITY_HYPOTHESES_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_EXTREMITY_HYPOTHESES_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/candidate_maps.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_distortion.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/shot_impl.h>
#include <CGAL/Surface_mesh_correspondence/internal/tear_repair.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iostream>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// The extremities of a shape and the geodesic distances between them (divided by the square
/// root of the area).
struct Shape_extremities
{
  std::vector<int> vertices;
  Eigen::MatrixXd distances;
};

/// The mean geodesic distance from every vertex to `sources` (fast marching), divided by
/// `scale`: the average geodesic distance, largest at the tips of a shape.
inline std::vector<double> mean_geodesic_distances(const Fast_marching_geometry& g, const std::vector<int>& sources,
                                                   double scale)
{
  const int n = g.number_of_vertices();
  std::vector<double> mean(std::size_t(n), 0.0);
  Fast_marching_workspace w(g);
  for(int s : sources)
  {
    w.run(s);
    for(int v = 0; v < n; ++v) mean[std::size_t(v)] += w.distance(v);
  }
  for(double& x : mean) x /= double(sources.size()) * scale;
  return mean;
}

/// The extremities of mesh `m`: the vertices whose mean geodesic distance to `sources` is the
/// largest within geodesic distance `radius` (relative to the square root of the area), by
/// decreasing mean distance, at most `max_count`. Each is at least `radius` from the others. On a
/// humanoid they are the hands, the feet and the head; they do not depend on the pose, and their
/// geodesic distances keep their proportions on shapes that are not isometric.
inline Shape_extremities shape_extremities(const Indexed_mesh& m, const Fast_marching_geometry& g,
                                           const std::vector<int>& sources, double radius, int max_count)
{
  const int n = m.number_of_vertices();
  const double scale = std::sqrt(m.total_area);
  const std::vector<double> mean = mean_geodesic_distances(g, sources, scale);
  // Local maxima among the neighbours, by decreasing mean distance.
  std::vector<int> order;
  for(int v = 0; v < n; ++v)
  {
    bool maximum = std::isfinite(mean[std::size_t(v)]);
    for(const int* w = m.neighbors_begin(v); maximum && w != m.neighbors_end(v); ++w)
      maximum = mean[std::size_t(*w)] <= mean[std::size_t(v)];
    if(maximum) order.push_back(v);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return mean[std::size_t(a)] > mean[std::size_t(b)]; });
  Shape_extremities out;
  std::vector<std::vector<double> > rows;  // distances from each extremity
  Fast_marching_workspace w(g);
  for(int v : order)
  {
    if(int(out.vertices.size()) >= max_count) break;
    bool far = true;
    for(const std::vector<double>& row : rows) far = far && row[std::size_t(v)] >= radius * scale;
    if(!far) continue;
    // A maximum within the radius: no vertex of the geodesic ball is farther from the sources.
    w.run(v, radius * scale);
    bool maximum = true;
    for(int u : w.accepted()) maximum = maximum && mean[std::size_t(u)] <= mean[std::size_t(v)];
    if(!maximum) continue;
    out.vertices.push_back(v);
    w.run(v);
    rows.emplace_back();
    w.copy_distances(rows.back());
  }
  const Eigen::Index k = Eigen::Index(out.vertices.size());
  out.distances.resize(k, k);
  for(Eigen::Index i = 0; i < k; ++i)
    for(Eigen::Index j = 0; j < k; ++j)
      out.distances(i, j) = rows[std::size_t(i)][std::size_t(out.vertices[std::size_t(j)])] / scale;
  return out;
}

/// An assignment of extremities (pairs of indices into the extremities of mesh 1 and mesh 2) and
/// its score.
struct Extremity_assignment
{
  std::vector<std::pair<int, int> > pairs;
  double score = 0;
};

/// The proportion distortion of matching extremities `a` of one shape to `b` of the other (same
/// length, indices into the distance matrices): the mean over the pairs of matched extremities of
/// |log(d1 / mean d1) - log(d2 / mean d2)|, the distances divided by their mean over the matched
/// pairs. Invariant to the scale of each shape, so that a gorilla's long arms and short legs can
/// match a man's, whose absolute distances differ by a third.
inline double proportion_distortion(const Eigen::MatrixXd& D1, const Eigen::MatrixXd& D2, const std::vector<int>& a,
                                    const std::vector<int>& b)
{
  const std::size_t k = a.size();
  double mean1 = 0, mean2 = 0;
  for(std::size_t i = 0; i < k; ++i)
    for(std::size_t j = i + 1; j < k; ++j)
    {
      mean1 += D1(a[i], a[j]);
      mean2 += D2(b[i], b[j]);
    }
  if(!(mean1 > 0) || !(mean2 > 0)) return std::numeric_limits<double>::infinity();
  double total = 0;
  std::size_t count = 0;
  for(std::size_t i = 0; i < k; ++i)
    for(std::size_t j = i + 1; j < k; ++j, ++count)
    {
      const double x = D1(a[i], a[j]) / mean1, y = D2(b[i], b[j]) / mean2;
      total += (x > 0 && y > 0) ? std::abs(std::log(x / y)) : std::numeric_limits<double>::infinity();
    }
  return total / double(count);
}

/// The `count` assignments of lowest score among the injective assignments of every extremity of
/// the shape with fewer extremities to those of the other (all of them are enumerated: 7! = 5040
/// for seven extremities on each shape), by increasing score (ties in enumeration order). The
/// score is proportion_distortion(), plus `descriptor_weight` times the mean of
/// `descriptor_distances(i, j)` over the matched pairs (i of mesh 1, j of mesh 2) when that matrix
/// is given (not empty). When `unmatched_penalty` is finite, the assignments that leave one
/// extremity of the smaller shape unmatched compete too, at this cost added to their score, as
/// long as they match at least `minimum_pairs` extremities: a shape may have a tip the other has
/// not (a gorilla's jaw beside its head, the buttocks of a woman standing straight), and matched
/// to anything it distorts the proportions of every pair it belongs to. Empty when either shape
/// has fewer than three extremities.
inline std::vector<Extremity_assignment> extremity_assignments(
    const Eigen::MatrixXd& D1, const Eigen::MatrixXd& D2, std::size_t count,
    const Eigen::MatrixXd& descriptor_distances = {}, double descriptor_weight = 0,
    double unmatched_penalty = std::numeric_limits<double>::infinity(), int minimum_pairs = 5)
{
  std::vector<Extremity_assignment> out;
  const int n1 = int(D1.rows()), n2 = int(D2.rows());
  if(std::min(n1, n2) < 3 || count == 0) return out;
  const bool forward = n1 <= n2;  // the extremities of mesh 1 are the ones matched (or left out)
  const int m = std::min(n1, n2), l = std::max(n1, n2);
  // With a finite penalty, one extremity of the smaller shape may stay unmatched.
  const bool leave_one_out = std::isfinite(unmatched_penalty) && m - 1 >= std::max(3, minimum_pairs);
  std::vector<int> fixed, chosen;
  std::vector<char> used(std::size_t(l), 0);
  std::vector<Extremity_assignment> all;
  // Depth-first enumeration of the k-permutations of the l extremities, for the extremities
  // `fixed` of the smaller shape.
  auto enumerate = [&](auto&& self) -> void {
    const std::size_t k = fixed.size();
    if(chosen.size() == k)
    {
      Extremity_assignment a;
      a.score = forward ? proportion_distortion(D1, D2, fixed, chosen) : proportion_distortion(D1, D2, chosen, fixed);
      for(std::size_t i = 0; i < k; ++i)
        a.pairs.emplace_back(forward ? fixed[i] : chosen[i], forward ? chosen[i] : fixed[i]);
      if(descriptor_distances.size() > 0)
      {
        double total = 0;
        for(const auto& p : a.pairs) total += descriptor_distances(p.first, p.second);
        a.score += descriptor_weight * total / double(k);
      }
      if(int(k) < m) a.score += unmatched_penalty * double(m - int(k));
      all.push_back(std::move(a));
      return;
    }
    for(int j = 0; j < l; ++j)
      if(!used[std::size_t(j)])
      {
        used[std::size_t(j)] = 1;
        chosen.push_back(j);
        self(self);
        chosen.pop_back();
        used[std::size_t(j)] = 0;
      }
  };
  // Every extremity of the smaller shape, then (when allowed) all of them but one.
  fixed.resize(std::size_t(m));
  std::iota(fixed.begin(), fixed.end(), 0);
  enumerate(enumerate);
  for(int left_out = 0; leave_one_out && left_out < m; ++left_out)
  {
    fixed.clear();
    for(int i = 0; i < m; ++i)
      if(i != left_out) fixed.push_back(i);
    enumerate(enumerate);
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const Extremity_assignment& x, const Extremity_assignment& y) { return x.score < y.score; });
  all.resize(std::min(all.size(), count));
  return all;
}

/// The descriptor distances between the rows of `F1` (the extremities of one mesh) and those of
/// `F2` (the other's): for non-negative descriptors u and v such as the WKS, sum |u - v| over
/// sum (|u| + |v|), in [0, 1].
inline Eigen::MatrixXd extremity_descriptor_distances(const Eigen::MatrixXd& F1, const Eigen::MatrixXd& F2)
{
  Eigen::MatrixXd out(F1.rows(), F2.rows());
  for(Eigen::Index i = 0; i < F1.rows(); ++i)
    for(Eigen::Index j = 0; j < F2.rows(); ++j)
    {
      const auto u = F1.row(i), v = F2.row(j);
      const double sum = u.cwiseAbs().sum() + v.cwiseAbs().sum();
      out(i, j) = sum > 0 ? (u - v).cwiseAbs().sum() / sum : 0.0;
    }
  return out;
}

/// SHOT descriptors (shot_descriptors(), unit norm) of some vertices of a mesh.
struct Shot_samples
{
  std::vector<int> vertices;
  Eigen::MatrixXd descriptors;
};

/// The SHOT descriptors of `vertices` of `m` (all vertices when empty).
template <typename ConcurrencyTag>
Shot_samples shot_samples(const Indexed_mesh& m, const std::vector<int>& vertices, const Shot_options& options)
{
  Shot_samples out;
  out.vertices = vertices;
  if(out.vertices.empty())
  {
    out.vertices.resize(std::size_t(m.number_of_vertices()));
    std::iota(out.vertices.begin(), out.vertices.end(), 0);
  }
  out.descriptors = shot_descriptors<ConcurrencyTag>(m, out.vertices.data(), out.vertices.size(), options);
  return out;
}

/// The SHOT disagreement of a map from the mesh of `from` to `to`: the mean over the vertices of
/// `from` of the Euclidean distance between their SHOT descriptor and that of their image (both
/// of unit norm, so in [0, 2]). SHOT describes the local shape around a point in a frame of its
/// own: it is not intrinsic, so it tells the front of a body from its back (toes from heels, a
/// face from the back of a head) where intrinsic descriptors and geodesic distances cannot.
template <typename ConcurrencyTag>
double shot_disagreement(const Shot_samples& from, const Indexed_mesh& to, const std::vector<std::size_t>& map,
                         const Shot_options& options)
{
  if(from.vertices.empty()) return 0;
  std::vector<int> images;
  images.reserve(from.vertices.size());
  for(int v : from.vertices) images.push_back(int(map[std::size_t(v)]));
  const Eigen::MatrixXd at_images = shot_descriptors<ConcurrencyTag>(to, images.data(), images.size(), options);
  double total = 0;
  for(Eigen::Index r = 0; r < at_images.rows(); ++r) total += (from.descriptors.row(r) - at_images.row(r)).norm();
  return total / double(at_images.rows());
}

/// The settings of one extremity hypothesis: the landmarks of `assignment` (indices into the
/// extremities `e1` and `e2`) added to the user's, the fits of the repair passes
/// (Initialization_settings::repair_candidates; those of `s` when empty) in the orientation of the
/// meshes. Without anchors among the user's landmarks the extremities are anchors (their geodesic
/// distance fields guide ZoomOut, see landmark_distance_fields()); otherwise the user's landmarks
/// stay the only anchors: the tips of two species' limbs and heads do not correspond exactly, and
/// their fields would pull the maps away from the user's.
inline Initialization_settings extremity_hypothesis_settings(const Initialization_settings& s,
                                                             const Shape_extremities& e1, const Shape_extremities& e2,
                                                             const Extremity_assignment& assignment)
{
  Initialization_settings hypothesis = s;
  hypothesis.landmark_orientation = 1;
  // The anchors constrain the fits as a repair pass's landmarks do: its fewer fits suffice.
  if(!s.repair_candidates.empty()) hypothesis.candidates = s.repair_candidates;
  // The extremities are anchors only when the user's landmarks hold none.
  const bool extremities_are_anchors = std::min(s.anchor_landmarks, s.landmarks.size()) == 0;
  for(const auto& p : assignment.pairs)
  {
    const std::size_t v1 = std::size_t(e1.vertices[std::size_t(p.first)]),
                      v2 = std::size_t(e2.vertices[std::size_t(p.second)]);
    if(extremities_are_anchors)
      hypothesis.add_anchor_landmark(v1, v2);
    else
      hypothesis.add_landmark(v1, v2);
  }
  return hypothesis;
}

/// The extremity hypotheses of automatic_initial_maps(): when the sample distortion of the maps
/// (pair_distortion(), stored in the result) is above `extremity_hypothesis_threshold`, a pass
/// (single_pass_initial_maps() with all the fits, in the orientation of the meshes) runs from each
/// of the `extremity_hypotheses` best assignments of the extremities of both shapes
/// (extremity_assignments()) as anchor landmarks, added to the user's, and then, for some of them,
/// the tear repair (repair_torn_maps()).
/// A hypothesis's criterion is the SHOT disagreement of its maps (shot_disagreement(), both
/// directions, on the ZoomOut samples, SHOT radius `shot_radius`) plus
/// `extremity_hypothesis_distortion_weight` times their sample distortion; the tear repair runs
/// only for the hypotheses whose pass ends at most `extremity_hypothesis_repair_margin` above the
/// lowest criterion. Among the repaired hypotheses whose maps distort the samples at most
/// `extremity_hypothesis_tolerance` (relatively) more than the given (descriptor-based) maps, the
/// one of lowest criterion replaces them.
/// Descriptor-based functional maps assume a near-isometry: on a gorilla and a man they match the
/// gorilla's long arms to the man's legs, and every fit does so; the extremities and the
/// proportions of their distances survive the change of species. Such a swap of limbs can keep
/// the sample distances better than the true map (the gorilla's arms are as long as the man's
/// legs), hence the tolerance. The best assignments are mostly the true one, its mirror twin (left
/// and right limbs swapped) and those with one pair of limbs swapped, in some order: pinned at the
/// extremities and held to the orientation of the meshes (by the chirality features of the
/// anchors, see landmark_chirality_fields()), the twin's maps turn the body front to back, which
/// keeps the geodesic distances about as well on a body whose front and back are alike, but not
/// the local shape of the toes, the heels and the face; the others twist the body at the waist.
///
/// Returns whether the hypotheses ran (the distortion was above the threshold). `repaired` says
/// whether the given maps come out of the tear repair, whose result then holds the torn fraction
/// of the first maps; otherwise the given maps are the first maps, and their torn fraction is
/// reported when a hypothesis replaces them.
template <typename ConcurrencyTag>
bool try_extremity_hypotheses(const Initialization_shape& shape1, const Initialization_shape& shape2,
                              const Initialization_settings& s, std::vector<std::size_t>& map_12,
                              std::vector<std::size_t>& map_21, Automatic_initialization_result& result,
                              Initialization_pass_cache& cache, bool repaired)
{
  if(s.extremity_hypotheses <= 0) return false;
  prepare_distortion_samples<ConcurrencyTag>(shape1, shape2, s, cache);
  double distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21);
  result.sample_distortion = distortion;
  if(result.distortion_repair_passes == 0) result.sample_distortion_before = distortion;
  if(distortion <= s.extremity_hypothesis_threshold) return false;
  const auto start = std::chrono::steady_clock::now();
  Shape_extremities e1, e2;
  auto extremities = [&](const Initialization_shape& shape, const Initialization_sampling& sampling,
                         Shape_extremities& out) {
    const std::vector<int>& samples = sampling.samples.distortion_vertices;
    const std::vector<int> sources(samples.begin(),
                                   samples.begin() + std::min<std::ptrdiff_t>(std::ptrdiff_t(samples.size()),
                                                                              s.extremity_sources));
    out = shape_extremities(*shape.mesh, sampling.geodesics, sources, s.extremity_radius, s.maximum_extremities);
  };
  invoke_both<ConcurrencyTag>([&] { extremities(shape1, cache.first, e1); },
                              [&] { extremities(shape2, cache.second, e2); });
  // The WKS of the whole initialisation spectrum, at the extremities only.
  const std::vector<Extremity_assignment> assignments = extremity_assignments(
      e1.distances, e2.distances, std::size_t(s.extremity_hypotheses),
      extremity_descriptor_distances(wave_kernel_signature_rows(*shape1.spectrum, e1.vertices),
                                     wave_kernel_signature_rows(*shape2.spectrum, e2.vertices)),
      s.extremity_descriptor_weight, s.unmatched_extremity_penalty, s.minimum_extremity_pairs);
  result.extremities_1 = int(e1.vertices.size());
  result.extremities_2 = int(e2.vertices.size());
  if(s.verbose)
  {
    std::cerr << "automatic_initial_maps: sample distortion " << distortion << ": " << e1.vertices.size() << " and "
              << e2.vertices.size() << " extremities, " << assignments.size() << " hypotheses\n";
    for(const Extremity_assignment& a : assignments)
    {
      std::cerr << "  score " << a.score << ":";
      for(const auto& p : a.pairs)
        std::cerr << " " << e1.vertices[std::size_t(p.first)] << "-" << e2.vertices[std::size_t(p.second)];
      std::cerr << "\n";
    }
  }
  // From each hypothesis, a pass with all the fits of the first one, in the orientation of the
  // meshes; then, for the hypotheses whose maps are not far behind the best ones, the tear repair,
  // whose landmarks from the core of its maps pin the body between the extremities. With
  // Parallel_tag the hypotheses run concurrently (the serial parts of one pass overlap the
  // other's), each on a pass cache of its own that reads the fast marching rows of the given one,
  // unchanged until all are done (one after the other they all use the given cache): the cached
  // rows give the values of a new run, so the maps do not depend on it. Progress is then notified
  // on the calling thread once all are done (step_done may throw a stop request).
  struct Hypothesis_maps
  {
    std::vector<std::size_t> map_12, map_21;
    Automatic_initialization_result result;
    double distortion = 0, disagreement = std::numeric_limits<double>::quiet_NaN();
  };
  const std::size_t count = assignments.size();
  std::vector<Hypothesis_maps> runs(count);
  const bool concurrent = Is_parallel<ConcurrencyTag>::value && count > 1 && !s.verbose;
  std::vector<Initialization_pass_cache> caches;
  for(std::size_t h = 0; concurrent && h < count; ++h) caches.push_back(cache.copy_sharing_rows());
  Initialization_settings quiet = s;
  if(concurrent) quiet.step_done = nullptr;
  std::vector<Initialization_settings> settings;
  for(const Extremity_assignment& a : assignments) settings.push_back(extremity_hypothesis_settings(quiet, e1, e2, a));
  // The SHOT descriptors of the ZoomOut samples, by which the maps of the hypotheses are compared.
  Shot_options shot;
  shot.relative_radius = s.shot_radius;
  Shot_samples samples1, samples2;
  if(count > 1)
    invoke_both<ConcurrencyTag>(
        [&] { samples1 = shot_samples<ConcurrencyTag>(*shape1.mesh, cache.first.samples.rows, shot); },
        [&] { samples2 = shot_samples<ConcurrencyTag>(*shape2.mesh, cache.second.samples.rows, shot); });
  auto score = [&](std::size_t h, Initialization_pass_cache& pass_cache) {
    Hypothesis_maps& r = runs[h];
    r.distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, pass_cache, r.map_12, r.map_21);
    if(count > 1)
      r.disagreement = (shot_disagreement<ConcurrencyTag>(samples1, *shape2.mesh, r.map_12, shot) +
                        shot_disagreement<ConcurrencyTag>(samples2, *shape1.mesh, r.map_21, shot)) / 2;
  };
  auto for_each_hypothesis = [&](const std::vector<std::size_t>& which,
                                 const std::function<void(std::size_t, Initialization_pass_cache&)>& f) {
    if(concurrent)
      parallel_for_in_order<ConcurrencyTag>(which.size(), [&](std::size_t i) { f(which[i], caches[which[i]]); });
    else
      for(std::size_t h : which) f(h, cache);
  };
  std::vector<std::size_t> all(count);
  std::iota(all.begin(), all.end(), std::size_t(0));
  for_each_hypothesis(all, [&](std::size_t h, Initialization_pass_cache& pass_cache) {
    runs[h].result = single_pass_initial_maps<ConcurrencyTag>(shape1, shape2, settings[h], runs[h].map_12,
                                                              runs[h].map_21, &pass_cache);
    score(h, pass_cache);
  });
  // The SHOT disagreement plus extremity_hypothesis_distortion_weight times the sample distortion:
  // a hypothesis and its mirror twin (the left and right limbs swapped, which the orientation
  // turns into a map from front to back) keep the proportions alike, but not the SHOT descriptors;
  // a hypothesis with one pair of limbs swapped twists the body, which mostly distorts the samples
  // more.
  auto criterion = [&](std::size_t h) {
    return runs[h].disagreement + s.extremity_hypothesis_distortion_weight * runs[h].distortion;
  };
  // The tear repair mends the maps between the extremities, not the assignment: only the
  // hypotheses whose first maps are within extremity_hypothesis_repair_margin of the best
  // criterion are repaired and compared; the others are left out. On the 24 TOSCA_nonIso pairs of
  // the benchmark, the kept hypothesis started at most 0.033 above the best one, and 23 of the 72
  // hypotheses were more than 0.05 behind.
  std::vector<std::size_t> competing;
  double best = std::numeric_limits<double>::infinity();
  for(std::size_t h = 0; h < count; ++h) best = std::min(best, criterion(h));
  for(std::size_t h = 0; h < count; ++h)
    if(count == 1 || criterion(h) <= best + s.extremity_hypothesis_repair_margin) competing.push_back(h);
  for_each_hypothesis(competing, [&](std::size_t h, Initialization_pass_cache& pass_cache) {
    Hypothesis_maps& r = runs[h];
    r.result = repair_torn_maps<ConcurrencyTag>(shape1, shape2, settings[h], r.map_12, r.map_21, r.result, &pass_cache);
    if(r.result.repair_passes > 0) score(h, pass_cache);  // repaired maps were kept
  });
  if(concurrent)
    for(std::size_t h = 0; h < count; ++h) s.notify_step();
  // Among the repaired hypotheses whose maps distort the samples at most the tolerance more than
  // the descriptor maps, the one of lowest criterion. The maps are compared at the pass size: only
  // the kept ones grow (grow_initial_maps()). Grown to the final size first, they followed the
  // shapes more closely but were chosen alike (the same hypothesis on all 24 TOSCA_nonIso pairs
  // checked), for about a second per pair.
  std::optional<std::size_t> kept;
  for(std::size_t h : competing)
    if(runs[h].distortion <= (1 + s.extremity_hypothesis_tolerance) * distortion &&
       (!kept || criterion(h) < criterion(*kept)))
      kept = h;
  if(s.verbose)
    for(std::size_t h = 0; h < assignments.size(); ++h)
    {
      const bool competed = std::find(competing.begin(), competing.end(), h) != competing.end();
      std::cerr << "automatic_initial_maps: extremity hypothesis " << h + 1 << " (score " << assignments[h].score
                << ", " << (competed ? std::to_string(runs[h].result.repair_passes) : "no")
                << " tear repair passes): distortion " << runs[h].distortion << ", SHOT disagreement "
                << runs[h].disagreement << ", criterion " << criterion(h)
                << (kept && *kept == h ? " (kept)" : competed ? " (discarded)" : " (not repaired)") << "\n";
    }
  double functional_map_seconds = result.functional_map_seconds, zoomout_seconds = result.zoomout_seconds;
  int passes = result.passes;
  for(const Hypothesis_maps& run : runs)
  {
    passes += run.result.passes;
    functional_map_seconds += run.result.functional_map_seconds;
    zoomout_seconds += run.result.zoomout_seconds;
  }
  if(kept)
  {
    const std::size_t h = *kept;
    Automatic_initialization_result& r = runs[h].result;
    r.spectra_seconds = result.spectra_seconds;
    // The torn fraction of the first maps (still in map_12 and map_21).
    r.torn_fraction_before = repaired ? result.torn_fraction_before
                                      : pair_tears(*shape1.mesh, *shape2.mesh, map_12, map_21, s.tear_threshold)
                                            .torn_fraction();
    r.repair_passes += result.repair_passes;
    r.distortion_repair_passes = result.distortion_repair_passes;
    r.sample_distortion_before = result.sample_distortion_before;
    r.extremities_1 = result.extremities_1;
    r.extremities_2 = result.extremities_2;
    r.sample_distortion = runs[h].distortion;
    r.extremity_hypothesis = int(h) + 1;
    result = r;
    map_12.swap(runs[h].map_12);
    map_21.swap(runs[h].map_21);
  }
  result.extremity_hypotheses = int(assignments.size());
  result.functional_map_seconds = functional_map_seconds;
  result.zoomout_seconds = zoomout_seconds;
  result.passes = passes;
  result.extremity_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

/// The core of automatic_initial_maps() on precomputed shapes (see single_pass_initial_maps()):
/// one pass, then the tear repair (repair_torn_maps()), the distortion repair
/// (repair_distorted_maps()) and the extremity hypotheses (try_extremity_hypotheses()), then the
/// growth to the final size (grow_initial_maps()) unless `grow` is false (the maps then stay at the
/// pass size, for a comparison before the growth). When the first pass's maps already distort the
/// sample distances more than `extremity_hypothesis_threshold`, the hypotheses run first, against
/// those maps, and the repairs only when no hypothesis replaces them: on such pairs (far from
/// isometric) every descriptor fit is wrong as a whole, the repairs cannot mend that, and they
/// cost about one pass each. No pair of the FAUST_r and TOSCA_r subsets has a first pass above
/// 0.094; every pair of the TOSCA_nonIso subset is above 0.165.
template <typename ConcurrencyTag>
Automatic_initialization_result automatic_initial_maps(const Initialization_shape& shape1,
                                                       const Initialization_shape& shape2,
                                                       const Initialization_settings& s,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       Initialization_pass_cache* pass_cache = nullptr,
                                                       bool grow = true)
{
  const auto start = std::chrono::steady_clock::now();
  Initialization_pass_cache own_cache;
  Initialization_pass_cache& cache = pass_cache ? *pass_cache : own_cache;
  Automatic_initialization_result result =
      single_pass_initial_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, &cache);
  const bool hypotheses_ran =
      try_extremity_hypotheses<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, result, cache, false);
  if(result.extremity_hypothesis == 0)
  {
    result = repair_torn_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, result, &cache);
    if(s.distortion_repair_passes > 0)
      result = repair_distorted_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, result, &cache);
    if(!hypotheses_ran)
      try_extremity_hypotheses<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, result, cache, true);
  }
  if(grow) grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, result);
  result.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_EXTREMITY_HYPOTHESES_H
