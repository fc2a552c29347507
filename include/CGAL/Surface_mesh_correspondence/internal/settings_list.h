// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The registry of the package's settings: the one list of every tunable setting of the matching
// pipeline (match_shapes(), Correspondence_shape, the component functions that share their names,
// and `comap`). Everything else is generated from it: the named parameters (parameters.h), the
// Matching_settings struct with its defaults, readers and checks (matching_settings.h), the
// settings file and the expert help of `comap`, and the settings table of the manual (checked by a
// test).
//
// X(name, type, default, default for given maps, valid range, stage, documentation)
//   - type: int, double, bool, Int_list, Fit_list, Distance_oracle_type or Refinement_selection;
//   - default for given maps: the value used when the maps to refine were given by the caller
//     (not computed by the automatic initialisation) and the setting was not set; it differs from
//     the default for five refinement settings only;
//   - range: range_any(), range_at_least(a), range_above(a), range_between(a, b) (inclusive),
//     range_below(b) (open upper bound) on the value (a list: on each element);
//   - stage: the stage of the pipeline that reads the setting (Matching_stage).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SETTINGS_LIST_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SETTINGS_LIST_H

#define CGAL_SMC_SETTINGS(X)                                                                                      \
  /* ------------------------------------------------ shape preparation */                                         \
  X(number_of_eigenpairs, int, 100, 100, range_between(2, 100000), preparation,                                    \
    "Laplace-Beltrami eigenpairs of the refinement's descriptor stack (HKS, WKS)")                                 \
  X(use_intrinsic_delaunay, bool, true, true, range_any(), preparation,                                            \
    "build the Laplace-Beltrami operator on the intrinsic Delaunay triangulation")                                 \
  X(hks_weight, double, 0.5, 0.5, range_at_least(0), preparation,                                                  \
    "weight of the heat kernel signature in the refinement's descriptor stack (0: none)")                          \
  X(wks_weight, double, 1.0, 1.0, range_at_least(0), preparation,                                                  \
    "weight of the wave kernel signature in the refinement's descriptor stack (0: none)")                          \
  X(shot_weight, double, 1.0, 1.0, range_at_least(0), preparation,                                                 \
    "weight of SHOT in the refinement's descriptor stack (0: none)")                                               \
  X(user_descriptor_weight, double, 1.0, 1.0, range_at_least(0), preparation,                                      \
    "weight of the user's descriptors (named parameter user_descriptor_map) in the descriptor stack")              \
  X(number_of_hks_scales, int, 16, 16, range_between(1, 100000), preparation, "HKS time scales")                  \
  X(number_of_wks_energies, int, 100, 100, range_between(2, 100000), preparation, "WKS energies")                 \
  X(wks_variance, double, 7.0, 7.0, range_above(0), preparation, "WKS filter width, in energy steps")              \
  X(shot_radius, double, 0.08, 0.08, range_between(1e-6, 1), preparation,                                          \
    "SHOT support radius, relative to the square root of the area (the refinement's descriptors and the "        \
    "choice among extremity hypotheses)")                                                                          \
  X(distance_oracle, Distance_oracle_type, Distance_oracle_type::automatic, Distance_oracle_type::automatic,       \
    range_any(), preparation,                                                                                      \
    "geodesic distances of the refinement: dense (n^2 memory), local (exact within oracle_radius, landmark "       \
    "estimate beyond) or automatic (local)")                                                                       \
  X(oracle_radius, double, 10, 10, range_above(0), preparation,                                                    \
    "radius of the local distance oracle's exact distances, in mean edge lengths")                                 \
  X(oracle_landmarks, int, 32, 32, range_between(1, 100000), preparation,                                          \
    "landmarks of the local distance oracle's estimate beyond its radius")                                         \
  /* ------------------------------------------------ automatic initialisation */                                  \
  X(initialization_fits, Fit_list,                                                                                 \
    (Fit_list{{20, 0.03, 0.3}, {15, 0.03, 0.3}, {20, 0.1, 1.0}, {30, 0.03, 0.3}, {40, 0.1, 1.0}, {60, 0.1, 1.0}}), \
    (Fit_list{{20, 0.03, 0.3}, {15, 0.03, 0.3}, {20, 0.1, 1.0}, {30, 0.03, 0.3}, {40, 0.1, 1.0}, {60, 0.1, 1.0}}), \
    range_at_least(0), initialization,                                                                             \
    "functional map fits tried (basis size, orientation weight, commutativity weight); the fit whose maps "        \
    "distort the sample distances least after a short ZoomOut is kept")                                            \
  X(fit_selection_basis_size, int, 40, 40, range_between(2, 100000), initialization,                               \
    "basis size at which the fits are compared")                                                                   \
  X(zoomout_final_size, int, 200, 200, range_between(2, 100000), initialization,                                   \
    "basis size at which ZoomOut ends: the automatic maps' final basis")                                           \
  X(zoomout_pass_size, int, 120, 120, range_between(2, 100000), initialization,                                    \
    "basis size at which each pass (the first one, each repair pass) ends its ZoomOut and is compared")            \
  X(zoomout_step, int, 5, 5, range_between(1, 100000), initialization, "ZoomOut basis growth per iteration")      \
  X(zoomout_growth_step, int, 10, 10, range_between(1, 100000), initialization,                                    \
    "ZoomOut basis growth per iteration from zoomout_pass_size to zoomout_final_size")                             \
  X(zoomout_number_of_samples, int, 1000, 1000, range_between(0, 100000000), initialization,                       \
    "vertices sampled per ZoomOut iteration (0: all)")                                                             \
  X(use_coupled_zoomout, bool, true, true, range_any(), initialization,                                            \
    "grow both maps jointly (favours maps that invert each other)")                                                \
  X(zoomout_bijectivity_weight, double, 1.0, 1.0, range_at_least(0), initialization,                               \
    "weight of the bijectivity term of the coupled ZoomOut")                                                       \
  X(use_procrustes, bool, true, true, range_any(), initialization,                                                 \
    "replace each fitted functional map by the nearest orthogonal one")                                            \
  X(initialization_number_of_eigenpairs, int, 0, 0, range_between(0, 100000), initialization,                      \
    "eigenpairs computed for the initialisation (0: zoomout_final_size)")                                          \
  X(initialization_wks_weight, double, 1.0, 1.0, range_at_least(0), initialization,                                \
    "weight of the WKS columns of the functional map fits")                                                        \
  X(initialization_hks_weight, double, 0.0, 0.0, range_at_least(0), initialization,                                \
    "weight of the HKS columns of the functional map fits")                                                        \
  X(initialization_number_of_wks_energies, int, 100, 100, range_between(2, 100000), initialization,                \
    "WKS energies of the functional map fits")                                                                     \
  X(initialization_wks_variance, double, 7.0, 7.0, range_above(0), initialization,                                \
    "WKS filter width of the functional map fits, in energy steps")                                                \
  X(initialization_number_of_hks_scales, int, 16, 16, range_between(1, 100000), initialization,                    \
    "HKS time scales of the functional map fits")                                                                  \
  X(signed_descriptor_weight, double, 1.0, 1.0, range_at_least(0), initialization,                                 \
    "weight of the orientation-sensitive descriptors <n, grad f x grad g> (0: none)")                              \
  X(signed_descriptor_smoothing, int, 60, 60, range_between(0, 100000), initialization,                            \
    "eigenfunctions that smooth the orientation-sensitive descriptors (0: not smoothed)")                          \
  X(number_of_operator_descriptors, int, 20, 20, range_between(0, 100000), initialization,                         \
    "descriptors with multiplication and orientation operators in the fits")                                       \
  X(number_of_repair_passes, int, 2, 2, range_between(0, 100), initialization,                                     \
    "tear repair passes at most: maps whose tears cut off part of a mesh are recomputed with landmarks from "      \
    "their core (0: no repair)")                                                                                   \
  X(number_of_distortion_repair_passes, int, 0, 0, range_between(0, 100), initialization,                          \
    "distortion repair passes at most: maps recomputed with landmarks from their isometric core, kept when they "  \
    "distort the sample distances less (0: none)")                                                                 \
  X(extremity_hypotheses, int, 3, 3, range_between(0, 100), initialization,                                       \
    "maps that distort the sample distances more than extremity_hypothesis_threshold: passes run from this many "  \
    "assignments of the shapes' extremities as landmarks, the one whose maps best keep the SHOT descriptors "      \
    "and the sample distances kept (0: none)")                                                                     \
  X(extremity_hypothesis_threshold, double, 0.1, 0.1, range_at_least(0), initialization,                          \
    "sample distortion above which the extremity hypotheses run (pairs far from isometric)")                      \
  X(extremity_hypothesis_tolerance, double, 0.5, 0.5, range_at_least(0), initialization,                          \
    "the maps of an extremity hypothesis may replace the descriptor-based maps only when they distort the "       \
    "sample distances at most this fraction more")                                                                 \
  X(extremity_hypothesis_distortion_weight, double, 2.0, 2.0, range_at_least(0), initialization,                 \
    "the extremity hypothesis kept is the one of lowest SHOT disagreement plus this times its sample "            \
    "distortion")                                                                                                  \
  X(extremity_hypothesis_repair_margin, double, 0.05, 0.05, range_at_least(0), initialization,                     \
    "only the extremity hypotheses whose first maps score at most this above the best one (SHOT disagreement "     \
    "plus the weighted sample distortion) get their tear repair and compete")                                      \
  X(tear_threshold, double, 0.06, 0.06, range_above(0), initialization,                                            \
    "a source edge is torn when its images are this far apart (relative to the square root of the target's "      \
    "area)")                                                                                                       \
  X(tear_area_fraction, double, 0.01, 0.01, range_between(0, 0.999999), initialization,                            \
    "maps are repaired when their tears cut off more than this fraction of a mesh's area")                         \
  X(tear_repair_distortion_tolerance, double, 0.05, 0.05, range_any(), initialization,                             \
    "a repair pass is kept only when its maps distort the sample distances at most this fraction more than the "   \
    "maps they replace (negative: no check)")                                                                      \
  X(number_of_tear_repair_landmarks, int, 30, 30, range_between(1, 100000), initialization,                        \
    "landmarks sampled in the core of each map by a repair pass")                                                  \
  X(landmark_distance_weight, double, 10.0, 10.0, range_at_least(0), initialization,                              \
    "passes with the user's landmarks: weight of the geodesic distances to the landmarks (divided by the square "  \
    "root of the area) appended to the ZoomOut embeddings (0: none)")                                             \
  X(landmark_orientation_weight, double, 3.0, 3.0, range_at_least(0), initialization,                            \
    "passes with anchor landmarks: weight of the orientation-sensitive descriptors appended to the ZoomOut "      \
    "embeddings (0: none)")                                                                                        \
  X(landmark_chirality_weight, double, 10.0, 10.0, range_at_least(0), initialization,                            \
    "passes with two or more anchor landmarks: weight of the turn between the directions to each two anchors "   \
    "(the sine of the angle between the gradients of their distances) appended to the ZoomOut embeddings (0: "   \
    "none)")                                                                                                       \
  /* ------------------------------------------------ given maps */                                                \
  X(repair_given_maps, bool, true, true, range_any(), repair,                                                      \
    "given maps: repair their tears (swapped limbs) with landmarks from their core before the refinement")         \
  X(compare_with_automatic_maps, bool, true, true, range_any(), comparison,                                        \
    "given maps: replace them by the automatic maps of the pair when these distort the sample distances less")     \
  X(automatic_maps_comparison_threshold, double, 0.035, 0.035, range_at_least(0), comparison,                      \
    "given maps whose sample distortion is at most this are kept without computing the automatic maps "            \
    "(0: always compare)")                                                                                         \
  X(automatic_maps_maximum_distortion, double, 0.1, 0.1, range_at_least(0), comparison,                           \
    "the automatic maps replace the given ones only when their sample distortion is at most this; above it the "  \
    "pair is far from isometric and the given maps are kept as given (their tear repair undone)")                  \
  /* ------------------------------------------------ coupled refinement */                                        \
  X(number_of_candidates, int, 40, 20, range_between(1, 100000), refinement,                                       \
    "candidate target vertices per source vertex (m)")                                                             \
  X(ring_schedule, Int_list, (Int_list{4, 3, 2, 1}), (Int_list{6, 4, 3, 2, 1}), range_between(0, 1000),           \
    refinement, "radius (in rings) of the candidate neighbourhoods at each outer iteration; the last one repeats")  \
  X(number_of_outer_iterations, int, 0, 0, range_between(0, 1000), refinement,                                     \
    "outer iterations (0: the length of ring_schedule)")                                                           \
  X(unary_weight, double, 0.03, 0.03, range_at_least(0), refinement,                                               \
    "weight of the descriptor term against the geodesic distortion term (mu)")                                     \
  X(consistency_weight, double, 0.5, 1.0, range_at_least(0), refinement,                                           \
    "weight of the cycle term: a candidate k of vertex i costs this times the geodesic distance from i to the "    \
    "opposite map's match of k, relative to the square root of the area (0: the paper's energy)")                  \
  X(use_coupling, bool, true, true, range_any(), refinement,                                                       \
    "candidates around the inverse of the opposite map and the cycle term (false: the paper's non-coupled "        \
    "ablation)")                                                                                                   \
  X(use_neighbor_matches, bool, true, true, range_any(), refinement,                                               \
    "the matches of the source neighbours are candidates too (propagation)")                                       \
  X(pairwise_rings, int, 1, 1, range_between(1, 10), refinement,                                                   \
    "pairwise terms between source vertices at most this many rings apart (1: mesh edges)")                        \
  X(stop_when_consistency_worsens, bool, true, false, range_any(), refinement,                                     \
    "stop at the first outer iteration that makes the maps less consistent (the paper's Eq. 4)")                   \
  X(trws_number_of_iterations, int, 15, 100, range_between(1, 1000000), refinement,                                \
    "TRW-S iterations per MRF solve")                                                                              \
  X(trws_relative_tolerance, double, 1e-4, 1e-4, range_at_least(0), refinement,                                    \
    "TRW-S stops when the lower bound's relative change is below this")                                            \
  X(use_refinement, bool, true, true, range_any(), refinement,                                                     \
    "refine the maps (false: return the initial maps, after the repair and the comparison of given maps)")         \
  /* ------------------------------------------------ selection */                                                 \
  X(refinement_selection, Refinement_selection, Refinement_selection::regions, Refinement_selection::regions,      \
    range_any(), selection,                                                                                        \
    "where the refined maps replace their input: regions (everywhere when they are more consistent, else where "   \
    "they distort mid-range geodesic distances less), consistency (whole maps, when more consistent: the paper's " \
    "rule) or refined (always)")                                                                                   \
  X(selection_radius, double, 0.06, 0.06, range_between(1e-4, 1), selection,                                      \
    "radius of the neighbourhoods whose geodesic distortion compares the two maps at each vertex, relative to "    \
    "the square root of the area")                                                                                 \
  X(selection_samples, int, 8, 8, range_between(1, 1000), selection,                                               \
    "vertices at distance selection_radius / 2 to selection_radius compared with each vertex")                     \
  X(selection_smoothing, int, 5, 5, range_between(0, 1000), selection,                                             \
    "rounds of neighbour averaging of the distortion scores before the maps are compared vertex by vertex")        \
  X(diagnostic_regions, int, 16, 16, range_between(0, 100000), selection,                                          \
    "regions of each mesh (cells of farthest point samples) over which the result's ground-truth-free "            \
    "diagnostics are also reported (0: the whole meshes only)")                                                    \
  X(confidence_threshold, double, 0.5, 0.5, range_between(0, 1), selection,                                        \
    "confidence below which the maps are reported as probably wrong as a whole (comap warns on stderr)")

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SETTINGS_LIST_H
