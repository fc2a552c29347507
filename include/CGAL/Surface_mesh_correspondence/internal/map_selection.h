// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The selection stage: where refined maps replace their input, decided without ground truth.
// Refined maps that are more consistent than their input (Eq. 4 of the paper) replace it whole;
// otherwise each vertex keeps the match of the map that distorts the mid-range geodesic distances
// around it less (scores smoothed over the mesh, so whole regions switch together).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_SELECTION_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_SELECTION_H

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// What the selection stage of match_shapes() decided (see Refinement_selection).
struct Selection_result
{
  /// Whether the refined maps were more consistent than their input (Eq. 4: fewer vertices x
  /// with T21(T12(x)) != x, both directions).
  bool refined_more_consistent = false;
  /// The fraction of the vertices of mesh 1 (map 1 -> 2) and of mesh 2 (map 2 -> 1) whose match
  /// comes from the refined maps (1: the refined maps whole, 0: the input maps).
  double refined_fraction_12 = 0, refined_fraction_21 = 0;
  /// The mean mid-range distortion of the input, refined and selected maps (both directions): the
  /// mean over the vertices of their distortion scores (relative to the square roots of the areas;
  /// estimated on about 1000 vertices per mesh when the maps are taken whole).
  double input_distortion = 0, refined_distortion = 0, selected_distortion = 0;
  /// Inconsistent vertices (Eq. 4, both directions) of the input, the refined and the selected maps.
  std::size_t inconsistent_input = 0, inconsistent_refined = 0, inconsistent_selected = 0;
};

namespace internal {

/// Settings of the selection stage (the registry's `refinement_selection`, `selection_radius`,
/// `selection_samples`, `selection_smoothing`) and of the diagnostics and confidence that follow
/// it (`diagnostic_regions`, `confidence_threshold`).
struct Selection_settings
{
  Refinement_selection mode = matching_defaults().refinement_selection;
  double radius = matching_defaults().selection_radius;
  int samples = matching_defaults().selection_samples;
  int smoothing = matching_defaults().selection_smoothing;
  int diagnostic_regions = matching_defaults().diagnostic_regions;
  double confidence_threshold = matching_defaults().confidence_threshold;

  static Selection_settings from(const Matching_settings& m)
  {
    return {m.refinement_selection, m.selection_radius, m.selection_samples, m.selection_smoothing,
            m.diagnostic_regions, m.confidence_threshold};
  }
};

inline std::size_t inconsistent_vertices(const std::vector<int>& x12, const std::vector<int>& x21)
{
  std::size_t c = 0;
  for(std::size_t i = 0; i < x12.size(); ++i) c += x21[std::size_t(x12[i])] != int(i);
  for(std::size_t k = 0; k < x21.size(); ++k) c += x12[std::size_t(x21[k])] != int(k);
  return c;
}

/// The mid-range distortion of the map `x` from `S` to `T` at the source vertices `vertices`
/// (one value per listed vertex): for a vertex i, the vertices j at geodesic distance `radius` / 2
/// to `radius` from i (relative to the square root of the area; up to `samples` of them, spread
/// over the ring by their order of acceptance) and the mean of |d_S(i, j) - d_T(x(i), x(j))|
/// (both relative to the square roots of the areas; a target distance beyond 3 `radius` counts as
/// 3 `radius`; 0 when the ring is empty). Distances are exact fast marching distances.
template <typename ConcurrencyTag>
std::vector<double> midrange_distortion_at(const Indexed_mesh& S, const Fast_marching_geometry& gs,
                                           const Indexed_mesh& T, const Fast_marching_geometry& gt,
                                           const std::vector<int>& x, double radius, int samples,
                                           const std::vector<int>& vertices)
{
  const double scale_s = std::sqrt(S.total_area), scale_t = std::sqrt(T.total_area);
  const double cap = 3 * radius;
  std::vector<double> out(vertices.size(), 0.0);
  parallel_for_ranges<ConcurrencyTag>(
      vertices.size(),
      [&](std::size_t begin, std::size_t end) {
        Fast_marching_workspace ws(gs), wt(gt);
        std::vector<int> ring, picked, images;
        for(std::size_t k = begin; k < end; ++k)
        {
          const int i = vertices[k];
          ws.run(i, radius * scale_s);
          ring.clear();
          for(int v : ws.accepted())
            if(ws.distance(v) >= 0.5 * radius * scale_s) ring.push_back(v);
          if(ring.empty()) continue;
          picked.clear();
          const std::size_t step = std::max<std::size_t>(1, ring.size() / std::size_t(samples));
          for(std::size_t a = 0; a < ring.size() && picked.size() < std::size_t(samples); a += step)
            picked.push_back(ring[a]);
          images.clear();
          for(int j : picked) images.push_back(x[std::size_t(j)]);
          const int source = x[std::size_t(i)];
          wt.run(&source, 1, cap * scale_t, images.data(), images.size());
          double sum = 0;
          for(std::size_t a = 0; a < picked.size(); ++a)
          {
            const double dt = wt.distance(images[a]);
            sum += std::abs(ws.distance(picked[a]) / scale_s - (std::isfinite(dt) ? dt / scale_t : cap));
          }
          out[k] = sum / double(picked.size());
        }
      },
      64);
  return out;
}

/// midrange_distortion_at() at every source vertex. With `stride` > 1, only every stride-th
/// vertex is scored (the others get 0): an estimate of the mean for reports.
template <typename ConcurrencyTag>
std::vector<double> midrange_distortion(const Indexed_mesh& S, const Fast_marching_geometry& gs, const Indexed_mesh& T,
                                        const Fast_marching_geometry& gt, const std::vector<int>& x, double radius,
                                        int samples, std::size_t stride = 1)
{
  const std::size_t n = std::size_t(S.number_of_vertices());
  std::vector<int> vertices;
  for(std::size_t u = 0; u < n; u += stride) vertices.push_back(int(u));
  const std::vector<double> scored = midrange_distortion_at<ConcurrencyTag>(S, gs, T, gt, x, radius, samples, vertices);
  std::vector<double> out(n, 0.0);
  for(std::size_t k = 0; k < vertices.size(); ++k) out[std::size_t(vertices[k])] = scored[k];
  return out;
}

/// `rounds` rounds of averaging every value with those of its neighbours.
inline std::vector<double> smoothed(const Indexed_mesh& m, std::vector<double> values, int rounds)
{
  std::vector<double> next(values.size());
  for(int r = 0; r < rounds; ++r)
  {
    for(int v = 0; v < m.number_of_vertices(); ++v)
    {
      double sum = values[std::size_t(v)];
      int count = 1;
      for(const int* w = m.neighbors_begin(v); w != m.neighbors_end(v); ++w, ++count) sum += values[std::size_t(*w)];
      next[std::size_t(v)] = sum / count;
    }
    values.swap(next);
  }
  return values;
}

/// The mean of every stride-th value.
inline double mean_of(const std::vector<double>& v, std::size_t stride = 1)
{
  double s = 0;
  std::size_t count = 0;
  for(std::size_t i = 0; i < v.size(); i += stride, ++count) s += v[i];
  return count == 0 ? 0.0 : s / double(count);
}

/// The mid-range distortion scores of the input and refined maps of one direction.
struct Direction_scores
{
  std::vector<double> input, refined;
};

/// Per vertex of `S`, the match of `input` or of `refined` whose smoothed mid-range distortion is
/// lower (ties keep the refined match); writes the result in `refined` and returns the fraction of
/// refined matches kept and, in `selected`, the mean score of the result.
inline double select_regions(const Indexed_mesh& S, const std::vector<int>& input, std::vector<int>& refined,
                             const Direction_scores& scores, int smoothing, double& selected)
{
  const std::vector<double> a = smoothed(S, scores.input, smoothing);
  const std::vector<double> b = smoothed(S, scores.refined, smoothing);
  std::size_t kept = 0;
  selected = 0;
  for(std::size_t i = 0; i < refined.size(); ++i)
  {
    if(a[i] < b[i])
    {
      refined[i] = input[i];
      selected += scores.input[i];
    }
    else
    {
      ++kept;
      selected += scores.refined[i];
    }
  }
  if(refined.empty()) return 1.0;
  selected /= double(refined.size());
  return double(kept) / double(refined.size());
}

/// The selection stage: `x12` and `x21` (the refined maps) are replaced, as `settings` says, by
/// the input maps `input12` and `input21` whole or region by region. The mid-range distortions
/// of the input and refined maps are measured in every mode (they are part of the result).
/// The fast marching geometries `g1` and `g2` are those of the meshes of `M1` and `M2`.
template <typename ConcurrencyTag>
Selection_result select_refined_maps(const Shape_data& M1, const Fast_marching_geometry& g1, const Shape_data& M2,
                                     const Fast_marching_geometry& g2, const std::vector<int>& input12,
                                     const std::vector<int>& input21, std::vector<int>& x12, std::vector<int>& x21,
                                     const Selection_settings& settings)
{
  Selection_result r;
  r.inconsistent_input = inconsistent_vertices(input12, input21);
  r.inconsistent_refined = inconsistent_vertices(x12, x21);
  r.refined_more_consistent = r.inconsistent_refined < r.inconsistent_input;
  // The scores of every vertex are needed only to choose region by region; for the report alone,
  // the means are estimated on at most about 1000 vertices of each mesh.
  const bool whole = settings.mode != Refinement_selection::regions || r.refined_more_consistent;
  const std::size_t stride1 = whole ? std::max<std::size_t>(1, x12.size() / 1000) : 1;
  const std::size_t stride2 = whole ? std::max<std::size_t>(1, x21.size() / 1000) : 1;
  Direction_scores d12, d21;
  auto scores = [&](const Indexed_mesh& S, const Fast_marching_geometry& gs, const Indexed_mesh& T,
                    const Fast_marching_geometry& gt, const std::vector<int>& x, std::size_t stride) {
    return midrange_distortion<ConcurrencyTag>(S, gs, T, gt, x, settings.radius, settings.samples, stride);
  };
  d12.input = scores(M1.mesh, g1, M2.mesh, g2, input12, stride1);
  d12.refined = scores(M1.mesh, g1, M2.mesh, g2, x12, stride1);
  d21.input = scores(M2.mesh, g2, M1.mesh, g1, input21, stride2);
  d21.refined = scores(M2.mesh, g2, M1.mesh, g1, x21, stride2);
  r.input_distortion = 0.5 * (mean_of(d12.input, stride1) + mean_of(d21.input, stride2));
  r.refined_distortion = 0.5 * (mean_of(d12.refined, stride1) + mean_of(d21.refined, stride2));
  r.refined_fraction_12 = r.refined_fraction_21 = 1;
  if(settings.mode == Refinement_selection::refined || r.refined_more_consistent)
  {
    r.selected_distortion = r.refined_distortion;
    r.inconsistent_selected = r.inconsistent_refined;
    return r;
  }
  if(settings.mode == Refinement_selection::consistency)
  {
    x12 = input12;
    x21 = input21;
    r.refined_fraction_12 = r.refined_fraction_21 = 0;
    r.selected_distortion = r.input_distortion;
    r.inconsistent_selected = r.inconsistent_input;
    return r;
  }
  double s12 = 0, s21 = 0;
  r.refined_fraction_12 = select_regions(M1.mesh, input12, x12, d12, settings.smoothing, s12);
  r.refined_fraction_21 = select_regions(M2.mesh, input21, x21, d21, settings.smoothing, s21);
  r.selected_distortion = 0.5 * (s12 + s21);
  r.inconsistent_selected = inconsistent_vertices(x12, x21);
  return r;
}

/// select_refined_maps() with the fast marching geometries built here.
template <typename ConcurrencyTag>
Selection_result select_refined_maps(const Shape_data& M1, const Shape_data& M2, const std::vector<int>& input12,
                                     const std::vector<int>& input21, std::vector<int>& x12, std::vector<int>& x21,
                                     const Selection_settings& settings)
{
  Fast_marching_geometry g1, g2;
  invoke_both<ConcurrencyTag>([&] { g1.build(M1.mesh); }, [&] { g2.build(M2.mesh); });
  return select_refined_maps<ConcurrencyTag>(M1, g1, M2, g2, input12, input21, x12, x21, settings);
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_MAP_SELECTION_H
