// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The repairs of the automatic initialisation: the tear repair (maps that swap parts of the
// shapes) and the distortion repair (maps wrong on a large part) of a pair of maps, and the core
// of automatic_initial_maps() on prepared shapes (a pass, the repairs, the growth).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TEAR_REPAIR_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TEAR_REPAIR_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/candidate_maps.h>
#include <CGAL/Surface_mesh_correspondence/internal/functional_map_fitting.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_distortion.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_tears.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <iostream>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// The tears of both maps of a pair (1 -> 2 on mesh 1, 2 -> 1 on mesh 2).
struct Pair_tears
{
  Map_tears forth, back;
  double torn_fraction() const { return 0.5 * (forth.torn_fraction + back.torn_fraction); }
};

inline Pair_tears pair_tears(const Indexed_mesh& m1, const Indexed_mesh& m2, const std::vector<std::size_t>& map_12,
                             const std::vector<std::size_t>& map_21, double relative_threshold)
{
  Pair_tears t;
  t.forth = map_tears(m1, m2, map_12, tear_threshold(m2, relative_threshold));
  t.back = map_tears(m2, m1, map_21, tear_threshold(m1, relative_threshold));
  return t;
}

/// The tear repair of a pair of maps (see automatic_initial_maps()). A map that swaps two limbs
/// of a symmetric body, or two feet, is continuous on each part but jumps where a swapped part
/// meets the rest; cut along these tears, its source falls into regions, of which the largest (the
/// core) is mapped consistently. While the tears of the maps cut off more than tear_min_fraction
/// of a mesh, the maps are computed again by single_pass_initial_maps() with
/// tear_repair_landmarks farthest-point samples of the core of each map (and their images) added
/// to the landmarks, in the orientation `orientation_sign` (that of the maps, relative to the
/// embeddings); the landmark descriptors then tell the swapped parts apart. New maps replace the
/// old ones only when they are less torn. Returns the result of the pass whose maps were kept, or
/// `result` (the one of the given maps) updated with the torn fractions. `pass_cache`: the
/// samplings of the pass that computed the maps, if any (see single_pass_initial_maps()).
template <typename ConcurrencyTag>
Automatic_initialization_result repair_torn_maps(const Initialization_shape& shape1, const Initialization_shape& shape2,
                                                 const Initialization_settings& s, std::vector<std::size_t>& map_12,
                                                 std::vector<std::size_t>& map_21, Automatic_initialization_result result,
                                                 Initialization_pass_cache* pass_cache = nullptr)
{
  Initialization_pass_cache own_cache;
  if(!pass_cache) pass_cache = &own_cache;
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  Pair_tears tears = pair_tears(m1, m2, map_12, map_21, s.tear_threshold);
  result.torn_fraction_before = result.torn_fraction = tears.torn_fraction();
  const bool check_distortion = s.tear_repair_distortion_tolerance >= 0;
  double distortion = -1;  // of the current maps, computed when first needed
  // The orientation hypothesis of the maps, relative to the meshes' own orientations.
  const int mesh_sign = (signed_volume(m1) * signed_volume(m2) < 0) ? -1 : 1;
  double functional_map_seconds = result.functional_map_seconds, zoomout_seconds = result.zoomout_seconds;
  int passes = result.passes;
  for(int pass = 1; pass <= s.tear_repair_passes; ++pass)
  {
    if(std::max(tears.forth.torn_fraction, tears.back.torn_fraction) <= s.tear_min_fraction) break;
    ++passes;
    Initialization_settings repair = s;
    repair.landmark_orientation = result.orientation_sign * mesh_sign;
    if(!s.repair_candidates.empty()) repair.candidates = s.repair_candidates;
    for(const auto& p : core_correspondences(m1, tears.forth, map_12, s.tear_repair_landmarks))
      repair.add_landmark(std::size_t(p.first), std::size_t(p.second));
    for(const auto& p : core_correspondences(m2, tears.back, map_21, s.tear_repair_landmarks))
      repair.add_landmark(std::size_t(p.second), std::size_t(p.first));
    std::vector<std::size_t> r12, r21;
    Automatic_initialization_result r = single_pass_initial_maps<ConcurrencyTag>(shape1, shape2, repair, r12, r21, pass_cache);
    const Pair_tears repaired = pair_tears(m1, m2, r12, r21, s.tear_threshold);
    functional_map_seconds += r.functional_map_seconds;
    zoomout_seconds += r.zoomout_seconds;
    bool keep = repaired.torn_fraction() < tears.torn_fraction();
    double repaired_distortion = 0;
    if(keep && check_distortion)
    {
      prepare_distortion_samples<ConcurrencyTag>(shape1, shape2, s, *pass_cache);
      if(distortion < 0) distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, *pass_cache, map_12, map_21);
      repaired_distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, *pass_cache, r12, r21);
      keep = repaired_distortion <= (1 + s.tear_repair_distortion_tolerance) * distortion;
    }
    if(s.verbose)
      std::cerr << "automatic_initial_maps: repair pass " << pass << " with " << repair.landmarks.size()
                << " landmarks: torn fraction " << tears.torn_fraction() << " -> " << repaired.torn_fraction()
                << ", distortion " << distortion << " -> " << repaired_distortion
                << (keep ? " (kept)" : " (discarded)") << "\n";
    if(!keep) break;
    r.spectra_seconds = result.spectra_seconds;
    r.torn_fraction_before = result.torn_fraction_before;
    r.torn_fraction = repaired.torn_fraction();
    r.repair_passes = pass;
    result = r;
    map_12.swap(r12);
    map_21.swap(r21);
    tears = repaired;
    distortion = repaired_distortion;
  }
  result.functional_map_seconds = functional_map_seconds;
  result.zoomout_seconds = zoomout_seconds;
  result.passes = passes;
  return result;
}

/// The distortion repair of a pair of maps (see automatic_initial_maps()). A map can be continuous,
/// orientation-preserving and without tears and still be wrong on a large part: a humanoid whose
/// upper body is mirrored and turned by 180 degrees, for one. Its isometric core (distortion_core())
/// is the part where the map preserves geodesic distances. While the sample distortion
/// (pair_distortion()) is above distortion_repair_threshold and distortion_repair_passes and
/// maximum_passes allow, the maps are computed again by single_pass_initial_maps() with
/// tear_repair_landmarks core samples of the map with the larger core (and their images) added to
/// the landmarks, in the orientation of the maps, and kept when their sample distortion is lower by
/// at least distortion_repair_gain (20%). Returns the result of the
/// pass whose maps were kept, or `result` updated with the distortions.
template <typename ConcurrencyTag>
Automatic_initialization_result repair_distorted_maps(const Initialization_shape& shape1,
                                                      const Initialization_shape& shape2,
                                                      const Initialization_settings& s,
                                                      std::vector<std::size_t>& map_12,
                                                      std::vector<std::size_t>& map_21,
                                                      Automatic_initialization_result result,
                                                      Initialization_pass_cache* pass_cache = nullptr)
{
  Initialization_pass_cache own_cache;
  if(!pass_cache) pass_cache = &own_cache;
  prepare_distortion_samples<ConcurrencyTag>(shape1, shape2, s, *pass_cache);
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  std::vector<int> core12, core21;
  double distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, *pass_cache, map_12, map_21, &core12, &core21);
  result.sample_distortion_before = result.sample_distortion = distortion;
  const int mesh_sign = (signed_volume(m1) * signed_volume(m2) < 0) ? -1 : 1;
  double functional_map_seconds = result.functional_map_seconds, zoomout_seconds = result.zoomout_seconds;
  const std::vector<int>& samples1 = pass_cache->first.samples.distortion_vertices;
  const std::vector<int>& samples2 = pass_cache->second.samples.distortion_vertices;
  int passes = result.passes;
  for(int pass = 1; pass <= s.distortion_repair_passes; ++pass)
  {
    if(distortion <= s.distortion_repair_threshold || passes >= s.maximum_passes) break;
    ++passes;
    Initialization_settings repair = s;
    repair.landmark_orientation = result.orientation_sign * mesh_sign;  // all the fits of the first pass
    // The landmarks come from the larger core only: the cores of the two maps of a half-flipped
    // pair can keep opposite halves.
    const std::size_t l = std::size_t(s.tear_repair_landmarks);
    const bool forth = double(core12.size()) * double(samples2.size()) >= double(core21.size()) * double(samples1.size());
    const std::vector<int>& core = forth ? core12 : core21;
    for(std::size_t i = 0; i < std::min(l, core.size()); ++i)
    {
      if(forth)
      {
        const int v = samples1[std::size_t(core[i])];
        repair.add_landmark(std::size_t(v), map_12[std::size_t(v)]);
      }
      else
      {
        const int w = samples2[std::size_t(core[i])];
        repair.add_landmark(map_21[std::size_t(w)], std::size_t(w));
      }
    }
    std::vector<std::size_t> r12, r21;
    Automatic_initialization_result r =
        single_pass_initial_maps<ConcurrencyTag>(shape1, shape2, repair, r12, r21, pass_cache);
    std::vector<int> next12, next21;
    const double repaired = pair_distortion<ConcurrencyTag>(shape1, shape2, s, *pass_cache, r12, r21, &next12, &next21);
    functional_map_seconds += r.functional_map_seconds;
    zoomout_seconds += r.zoomout_seconds;
    const bool keep = repaired <= (1.0 - s.distortion_repair_gain) * distortion;
    if(s.verbose)
      std::cerr << "automatic_initial_maps: distortion repair pass " << pass << " with " << repair.landmarks.size()
                << " landmarks (cores of " << core12.size() << " and " << core21.size() << " samples): distortion "
                << distortion << " -> " << repaired << (keep ? " (kept)" : " (discarded)") << "\n";
    if(!keep) break;
    r.spectra_seconds = result.spectra_seconds;
    r.repair_passes = result.repair_passes;
    r.torn_fraction_before = result.torn_fraction_before;
    r.torn_fraction = pair_tears(m1, m2, r12, r21, s.tear_threshold).torn_fraction();
    r.distortion_repair_passes = pass;
    r.sample_distortion_before = result.sample_distortion_before;
    r.sample_distortion = repaired;
    result = r;
    map_12.swap(r12);
    map_21.swap(r21);
    distortion = repaired;
    core12.swap(next12);
    core21.swap(next21);
  }
  result.functional_map_seconds = functional_map_seconds;
  result.zoomout_seconds = zoomout_seconds;
  result.passes = passes;
  return result;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TEAR_REPAIR_H
