// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The summary returned by automatic_initial_maps(), repair_torn_maps() and
// compare_with_automatic_maps(): timings, diagnostics of the maps, the repairs and the comparison,
// and the final functional maps.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_RESULT_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_RESULT_H

#include <Eigen/Core>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Summary of automatic_initial_maps(): timings and diagnostics.
struct Automatic_initialization_result
{
  /// Seconds spent on the flat mesh copies, spectra and descriptors (0 when they were given).
  double spectra_seconds = 0;
  /// Seconds spent on the reduced operators and the functional map fits.
  double functional_map_seconds = 0;
  /// Seconds spent in ZoomOut (both directions).
  double zoomout_seconds = 0;
  /// Total seconds.
  double total_seconds = 0;
  /// The selection score of the chosen fits after the short ZoomOut, averaged over both
  /// directions: the mean geodesic distortion of the sample maps (distances divided by the square
  /// root of the area), or with select_by_distortion off the weighted descriptor distance between
  /// matched samples.
  double selection_score = 0;
  /// Orientation of the maps: +1 preserving, -1 reversing (chosen from landmarks or the meshes'
  /// orientations, see automatic_initial_maps()).
  int orientation_sign = 1;
  /// Cycle consistency: the mean over the vertices x of both meshes of the Euclidean distance
  /// \f$ \|x - T_{21}(T_{12}(x))\| / \sqrt{A} \f$ (and symmetrically).
  double cycle_error = 0;
  /// The fraction of the vertices of both meshes with \f$ T_{21}(T_{12}(x)) = x \f$ (and
  /// symmetrically).
  double cycle_fixed_fraction = 0;
  /// The area-weighted fraction of triangles whose images keep their orientation (about 1 for
  /// orientation-preserving maps, 0 for mirror maps), averaged over both directions.
  double orientation_agreement = 0;
  /// Basis sizes: of the initial functional maps and after ZoomOut.
  int initial_basis_size = 0, final_basis_size = 0;
  /// Tear repair (see automatic_initial_maps()): the passes whose maps were kept (0: the first
  /// maps were kept), and the torn fraction (area cut off from the core by tears, mean of both
  /// directions) of the first maps and of the kept pass's maps (before their growth to the final
  /// basis size).
  int repair_passes = 0;
  double torn_fraction_before = 0, torn_fraction = 0;
  /// Distortion repair (see automatic_initial_maps()): the passes whose maps were kept, and the
  /// geodesic distortion of the sample maps (mean of both directions) before the distortion repair
  /// and of the kept pass's maps (before their growth to the final basis size).
  int distortion_repair_passes = 0;
  double sample_distortion_before = 0, sample_distortion = 0;
  /// Extremity hypotheses (see automatic_initial_maps()): the extremities found on each mesh, the
  /// hypotheses tried (0: the maps distorted the sample distances too little for them to run) and
  /// the one whose maps were kept (1 for the first; 0: none, the descriptor-based maps were kept),
  /// and the seconds they took.
  int extremities_1 = 0, extremities_2 = 0;
  int extremity_hypotheses = 0, extremity_hypothesis = 0;
  double extremity_seconds = 0;
  /// Comparison with the automatic maps (repair_torn_maps() with `compare_with_automatic_maps`):
  /// whether it ran, whether the automatic maps replaced the (repaired) given maps, and the
  /// geodesic distortions of the sample maps (mean of both directions) of both pairs of maps, at
  /// the pass basis size (zoomout_pass_size) for maps computed by a pass: only the kept pair then
  /// grows to the final basis size. When the automatic maps are kept, the other fields describe them (their
  /// own repair passes, torn fractions, functional maps), except the times and `passes`, which
  /// count both the given maps' repair and the automatic initialisation.
  /// `automatic_maps_computed` is false when the given maps' sample distortion was at most
  /// `automatic_maps_comparison_threshold`: they were kept without computing the automatic maps
  /// (`automatic_maps_distortion` is then 0).
  bool compared_with_automatic_maps = false;
  bool automatic_maps_computed = false;
  bool automatic_maps_kept = false;
  double given_maps_distortion = 0, automatic_maps_distortion = 0;
  /// Given maps compared with automatic maps that distort the sample distances more than
  /// `automatic_maps_maximum_distortion`: the pair is far from isometric, where neither the
  /// automatic maps nor the tear repair (both assume a near-isometry) are trusted. The given maps
  /// are then kept as the caller gave them: a kept repair pass is undone (`repair_undone`,
  /// `repair_passes` then 0).
  bool far_from_isometric = false, repair_undone = false;
  /// Passes run in all (fits and ZoomOut: the first one and the repair passes, kept or not).
  int passes = 0;
  /// Spectra taken from the prepared shapes (0, 1 or 2) instead of computed (the overloads on
  /// Correspondence_shape objects; always 0 for those on meshes).
  int reused_spectra = 0;
  /// Shapes (0, 1 or 2) whose initialisation spectrum and descriptors were kept from an earlier
  /// call with the same descriptor settings (the overloads on Correspondence_shape objects; always
  /// 0 for those on meshes).
  int reused_descriptors = 0;
  /// The final functional maps (unit-area bases): C12 (k x k, pulls functions from mesh 2 back
  /// to mesh 1, the map of map_12) and C21.
  Eigen::MatrixXd functional_map_12, functional_map_21;
};

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_RESULT_H
