// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Maps computed elsewhere: their repair by the tear and distortion repairs, and their comparison
// with the automatic maps of the pair (the cores of repair_torn_maps() and
// compare_with_automatic_maps()).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_GIVEN_MAPS_COMPARISON_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_GIVEN_MAPS_COMPARISON_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/candidate_maps.h>
#include <CGAL/Surface_mesh_correspondence/internal/extremity_hypotheses.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_distortion.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/tear_repair.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>

#include <chrono>
#include <cstddef>
#include <iostream>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// The comparison of repair_given_maps() (`compare_with_automatic_maps`): the automatic maps of
/// the pair (automatic_initial_maps() on the same shapes, sharing `cache`) replace `map_12` and
/// `map_21` when their sample maps distort geodesic distances less (pair_distortion(), mean of both
/// directions; ties keep the given maps) and at most automatic_maps_maximum_distortion (above it the
/// pair is far from isometric, where the automatic maps can be wholly wrong however they compare). Maps computed elsewhere can be wrong as a whole, core
/// included, which no repair from their own cores undoes (the WKS maps of TOSCA_r michael13 -
/// michael19: error 0.34, orientation kept on 78% of the triangles). Given maps whose sample
/// distortion is at most automatic_maps_comparison_threshold are kept without computing the
/// automatic maps. Both pairs are compared at the pass size (zoomout_pass_size: the given maps
/// after a kept repair pass, the automatic maps before their growth), and only the kept pair grows
/// to zoomout_final_size (grow_initial_maps(); given maps that no repair pass recomputed have no
/// functional maps and stay as they are). Returns `given`, or the automatic maps' result, with the
/// comparison's fields and the times of both.
/// The given maps as the caller gave them, before their repair: kept when the comparison finds the
/// pair far from isometric.
struct Given_maps_before_repair
{
  std::vector<std::size_t> map_12, map_21;
};

template <typename ConcurrencyTag>
Automatic_initialization_result compare_given_with_automatic_maps(const Initialization_shape& shape1,
                                                                  const Initialization_shape& shape2,
                                                                  const Initialization_settings& s,
                                                                  Initialization_pass_cache& cache,
                                                                  std::vector<std::size_t>& map_12,
                                                                  std::vector<std::size_t>& map_21,
                                                                  const Automatic_initialization_result& given,
                                                                  const Given_maps_before_repair& before)
{
  prepare_distortion_samples<ConcurrencyTag>(shape1, shape2, s, cache);
  const double given_distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21);
  if(given_distortion <= s.automatic_maps_comparison_threshold)
  {
    if(s.verbose)
      std::cerr << "repair_torn_maps: sample distortion of the given maps " << given_distortion << " <= "
                << s.automatic_maps_comparison_threshold << ": kept without the automatic maps\n";
    Automatic_initialization_result r = given;
    r.compared_with_automatic_maps = true;
    r.given_maps_distortion = given_distortion;
    grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r);
    return r;
  }
  // Without the extremity hypotheses: they run on automatic maps more distorted than
  // extremity_hypothesis_threshold, which the comparison does not trust anyway
  // (automatic_maps_maximum_distortion), and would cost several passes for nothing.
  Initialization_settings automatic_settings = s;
  automatic_settings.extremity_hypotheses = 0;
  std::vector<std::size_t> a12, a21;
  Automatic_initialization_result automatic =
      automatic_initial_maps<ConcurrencyTag>(shape1, shape2, automatic_settings, a12, a21, &cache, false);
  const double automatic_distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, cache, a12, a21);
  const bool trusted = automatic_distortion <= s.automatic_maps_maximum_distortion;
  const bool keep_automatic = trusted && automatic_distortion < given_distortion;
  if(s.verbose)
    std::cerr << "repair_torn_maps: sample distortion of the given maps " << given_distortion
              << ", of the automatic maps " << automatic_distortion << " (trusted up to "
              << s.automatic_maps_maximum_distortion << "): "
              << (keep_automatic ? "the automatic maps are kept" : "the given maps are kept") << "\n";
  Automatic_initialization_result r = keep_automatic ? automatic : given;
  if(keep_automatic)
  {
    map_12.swap(a12);
    map_21.swap(a21);
    r.spectra_seconds = given.spectra_seconds;
  }
  else if(!trusted && (map_12 != before.map_12 || map_21 != before.map_21))
  {
    // Far from isometric: the repair assumed a near-isometry as the automatic maps do; the maps
    // stay as given (no functional maps: nothing grows).
    map_12 = before.map_12;
    map_21 = before.map_21;
    r.repair_passes = 0;
    r.distortion_repair_passes = 0;
    r.functional_map_12.resize(0, 0);
    r.functional_map_21.resize(0, 0);
    r.final_basis_size = 0;
    r.torn_fraction = r.torn_fraction_before;
    r.repair_undone = true;
  }
  r.far_from_isometric = !trusted;
  r.functional_map_seconds = given.functional_map_seconds + automatic.functional_map_seconds;
  r.zoomout_seconds = given.zoomout_seconds + automatic.zoomout_seconds;
  r.passes = given.passes + automatic.passes;
  r.compared_with_automatic_maps = true;
  r.automatic_maps_computed = true;
  r.automatic_maps_kept = keep_automatic;
  r.given_maps_distortion = given_distortion;
  r.automatic_maps_distortion = automatic_distortion;
  grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r);
  return r;
}

/// The first step of repair_given_maps(): the orientation of the given maps, then their tear
/// repair and distortion repair (unless `repair` is false).
template <typename ConcurrencyTag>
Automatic_initialization_result repair_given_maps_tears(const Initialization_shape& shape1,
                                                        const Initialization_shape& shape2,
                                                        const Initialization_settings& s,
                                                        std::vector<std::size_t>& map_12,
                                                        std::vector<std::size_t>& map_21, bool repair,
                                                        Initialization_pass_cache& cache)
{
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  const std::vector<int> t12(map_12.begin(), map_12.end()), t21(map_21.begin(), map_21.end());
  Automatic_initialization_result given;
  given.orientation_agreement = 0.5 * (orientation_agreement(m1, m2, vertex_normals(m2), t12) +
                                       orientation_agreement(m2, m1, vertex_normals(m1), t21));
  given.orientation_sign = given.orientation_agreement >= 0.5 ? 1 : -1;
  Automatic_initialization_result r = given;
  if(repair)
  {
    r = repair_torn_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, given, &cache);
    if(s.distortion_repair_passes > 0)
      r = repair_distorted_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, r, &cache);
  }
  return r;
}

/// The second step of repair_given_maps(): with `compare_with_automatic_maps`, the comparison
/// with the automatic maps (only the kept maps grow to the final size), else the growth of the
/// maps of a kept repair pass (the given maps have no functional maps and stay as they are).
template <typename ConcurrencyTag>
Automatic_initialization_result compare_or_grow_given_maps(const Initialization_shape& shape1,
                                                           const Initialization_shape& shape2,
                                                           const Initialization_settings& s,
                                                           std::vector<std::size_t>& map_12,
                                                           std::vector<std::size_t>& map_21,
                                                           Automatic_initialization_result r,
                                                           Initialization_pass_cache& cache,
                                                           const Given_maps_before_repair& before)
{
  if(s.compare_with_automatic_maps)
    return compare_given_with_automatic_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r, before);
  grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r);
  return r;
}

/// repair_torn_maps() and repair_distorted_maps() for maps computed elsewhere (unless `repair` is
/// false), then, with `compare_with_automatic_maps`, the comparison with the automatic maps: their
/// orientation (relative to the embeddings) is read from the orientation agreement of their
/// triangles, and the result holds their tears and distortions.
template <typename ConcurrencyTag>
Automatic_initialization_result repair_given_maps(const Initialization_shape& shape1, const Initialization_shape& shape2,
                                                  const Initialization_settings& s, std::vector<std::size_t>& map_12,
                                                  std::vector<std::size_t>& map_21, bool repair = true)
{
  const auto start = std::chrono::steady_clock::now();
  Initialization_pass_cache cache;
  const Given_maps_before_repair before{map_12, map_21};
  Automatic_initialization_result r =
      repair_given_maps_tears<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, repair, cache);
  r = compare_or_grow_given_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, r, cache, before);
  r.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_GIVEN_MAPS_COMPARISON_H
