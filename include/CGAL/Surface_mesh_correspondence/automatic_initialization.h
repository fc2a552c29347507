// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Automatic initial point-to-point maps between two meshes, in both directions, without user
// input: an orientation-preserving functional map fitted to descriptors (WKS, HKS), upsampled to
// point maps by a coupled ZoomOut. These maps are the starting point of the coupled refinement.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_tears.h>
#include <CGAL/Surface_mesh_correspondence/internal/orientation_operator.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/zoomout.h>

#include <CGAL/assertions.h>
#include <CGAL/tags.h>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

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

namespace internal {

/// One configuration of the functional map fit tried by the initialisation.
struct Fit_candidate
{
  int basis_size;               ///< k0
  double orientation_weight;    ///< w_o
  double commutativity_weight;  ///< w_c
};

/// Every setting of the automatic initialisation, with its default.
struct Initialization_settings
{
  // Basis sizes.
  /// The fit configurations tried (each in both directions); the best after a short ZoomOut is
  /// kept. The named parameters spectral_basis_size, orientation_weight and commutativity_weight
  /// replace the list by a single configuration.
  /// Candidates larger than zoomout_final_size are skipped.
  std::vector<Fit_candidate> candidates{{20, 0.03, 0.3}, {15, 0.03, 0.3}, {20, 0.1, 1.0},
                                        {30, 0.03, 0.3}, {40, 0.1, 1.0},  {60, 0.1, 1.0}};
  int selection_size = 40;               ///< basis size at which candidates are compared
  /// How candidates are compared: by the geodesic distortion of their sample maps (true) or by
  /// the weighted descriptor distance between matched samples (false).
  bool select_by_distortion = true;
  /// Farthest-point samples whose pairwise geodesic distances measure the distortion.
  int distortion_samples = 100;
  int zoomout_final_size = 200;          ///< k_final
  /// Basis size at which every pass (the first one and each repair pass) ends its ZoomOut: the
  /// tears, the distortions and the choice between passes are measured there, and the maps that
  /// are kept then grow on to zoomout_final_size (grow_initial_maps()).
  int zoomout_pass_size = 120;
  int zoomout_step = 5;                  ///< ZoomOut basis growth per iteration
  /// ZoomOut basis growth per iteration from zoomout_pass_size to zoomout_final_size
  /// (grow_initial_maps()). Coarser than zoomout_step: the growth costs most at these sizes
  /// (TOSCA_r, every 8th pair: steps of 5, 10, 20 give 0.0260, 0.0263, 0.0266).
  int zoomout_growth_step = 10;
  int number_of_eigenpairs = 0;          ///< eigenpairs computed (0: zoomout_final_size)
  // Descriptors.
  int number_of_wks_energies = 100;
  double wks_variance = 7.0;
  int number_of_hks_scales = 16;
  double wks_weight = 1.0;
  double hks_weight = 0.0;
  /// Weight of the orientation-sensitive descriptors <n, grad f x grad g> (0: none).
  double signed_descriptor_weight = 1.0;
  /// They are smoothed by projection on this many eigenfunctions (0: not smoothed).
  int signed_descriptor_smoothing = 60;
  /// Number of descriptors (evenly spread over the columns) that get multiplication and
  /// orientation operators.
  int number_of_operator_descriptors = 20;
  bool normalize_orientation_gradients = true;
  // Functional map energy (orientation and commutativity weights come from the candidates).
  Functional_map_weights weights;
  bool procrustes = true;                ///< replace each fitted map by the nearest orthogonal one
  // ZoomOut.
  bool coupled_zoomout = true;
  double zoomout_bijectivity_weight = 1.0;
  int zoomout_number_of_samples = 1000;  ///< 0: all vertices in every iteration
  /// Weight of the descriptor coordinates appended to the ZoomOut embeddings (0: none), and its
  /// multiplier at the last step.
  double zoomout_descriptor_weight = 0.0;
  double zoomout_descriptor_final_ratio = 1.0;
  /// Use only the signed (orientation-sensitive) descriptors as ZoomOut features.
  bool zoomout_signed_features_only = true;
  // Landmarks.
  std::vector<std::pair<std::size_t, std::size_t> > landmarks;
  double landmark_descriptor_weight = 50.0;
  int number_of_landmark_energies = 10;
  double zoomout_landmark_weight = 0.01;
  /// With landmarks, the orientations fitted: 0 both (the landmarks choose), +1 or -1 only that
  /// hypothesis (relative to the meshes' own orientations).
  int landmark_orientation = 0;
  // Tear repair.
  /// Repair passes at most: after each set of maps whose tears cut off more than
  /// tear_min_fraction of a mesh, the maps are recomputed with landmarks sampled in the core (the
  /// largest region between the tears) of both maps, and kept when they are less torn.
  int tear_repair_passes = 2;
  /// A source edge is torn when its images are at least this far apart (relative to the square
  /// root of the target's area; at least four mean edge lengths).
  double tear_threshold = 0.06;
  double tear_min_fraction = 0.01;
  /// A tear repair pass is kept only when its maps also distort the geodesic distances of the
  /// distortion samples (pair_distortion()) at most this fraction more than the maps they replace
  /// (negative: no check). Landmarks from the core of a map torn over half a mesh can pull the
  /// repair into an untorn but mirrored map (TOSCA_r michael19 - michael8: 0.067 -> 0.30, its
  /// distortion +7%).
  double tear_repair_distortion_tolerance = 0.05;
  /// Landmarks sampled in the core of each map by a repair pass.
  int tear_repair_landmarks = 30;
  // Distortion repair.
  /// Distortion repair passes at most (0, the default: none; each pass costs about as much as the
  /// first one): after the tear repair, the maps are recomputed with
  /// landmarks from their isometric core (the largest set of samples whose pairwise geodesic
  /// distances the map preserves, see distortion_core()), with all the fit configurations of the
  /// first pass, and kept when they distort the sample distances less (distortion_repair_gain).
  int distortion_repair_passes = 0;
  /// Two samples agree when the map changes their geodesic distance by less than this (relative to
  /// the square root of the areas)...
  double distortion_core_tolerance = 0.04;
  /// ... and the core is the largest set found in which every sample agrees with this fraction of
  /// the others.
  double distortion_core_agreement = 0.9;
  /// Maps whose sample distortion (mean of both directions) is at most this are kept as they are.
  double distortion_repair_threshold = 0.035;
  /// New maps are kept only when their sample distortion is lower by at least this fraction: on
  /// shapes whose poses stretch the surface the ground truth is not the most isometric map, and
  /// small gains in isometry are as often losses in accuracy.
  double distortion_repair_gain = 0.2;
  /// Passes in all (the first one, tear repair and distortion repair): the distortion repair runs
  /// only while this allows.
  int maximum_passes = 3;
  /// The fit configurations of the repair passes (the landmarks constrain the fits, so fewer are
  /// needed); empty: those of the first pass.
  std::vector<Fit_candidate> repair_candidates{{20, 0.03, 0.3}, {40, 0.1, 1.0}};
  /// repair_given_maps() only: after the repairs, the given maps compete with the automatic maps
  /// of the pair (automatic_initial_maps() run on the same shapes); the pair of maps whose sample
  /// maps distort geodesic distances less is kept.
  bool compare_with_automatic_maps = false;
  /// ... only when the given maps' sample distortion is above this (0: always). Maps that preserve
  /// the sample distances well are kept without the cost of the automatic initialisation. The
  /// default 0.035 skips it on 77 of the 284 TOSCA_r pairs (repaired WKS maps), which then take
  /// about half the time; mean error 0.0247 instead of 0.0241 (benchmark/README.md).
  double automatic_maps_comparison_threshold = 0.035;
  bool verbose = false;
};

/// Reads the named parameters of automatic_initial_maps() into settings.
template <typename NamedParameters>
Initialization_settings initialization_settings(const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::is_default_parameter;
  Initialization_settings s;
  s.zoomout_final_size = choose_parameter(get_parameter(np, internal_np::zoomout_final_size),
                                          s.zoomout_final_size);
  s.zoomout_pass_size = choose_parameter(get_parameter(np, internal_np::zoomout_pass_size), s.zoomout_pass_size);
  s.zoomout_step = choose_parameter(get_parameter(np, internal_np::zoomout_step), s.zoomout_step);
  s.zoomout_growth_step = choose_parameter(get_parameter(np, internal_np::zoomout_growth_step), s.zoomout_growth_step);
  s.number_of_eigenpairs = choose_parameter(get_parameter(np, internal_np::number_of_eigenpairs),
                                            s.number_of_eigenpairs);
  s.number_of_wks_energies = choose_parameter(get_parameter(np, internal_np::number_of_wks_energies),
                                              s.number_of_wks_energies);
  s.wks_variance = choose_parameter(get_parameter(np, internal_np::wks_variance), s.wks_variance);
  s.number_of_hks_scales = choose_parameter(get_parameter(np, internal_np::number_of_hks_scales),
                                            s.number_of_hks_scales);
  s.wks_weight = choose_parameter(get_parameter(np, internal_np::wks_weight), s.wks_weight);
  s.hks_weight = choose_parameter(get_parameter(np, internal_np::hks_weight), s.hks_weight);
  if(!is_default_parameter<NamedParameters, internal_np::spectral_basis_size_t>::value ||
     !is_default_parameter<NamedParameters, internal_np::orientation_weight_t>::value ||
     !is_default_parameter<NamedParameters, internal_np::commutativity_weight_t>::value)
  {
    Fit_candidate c = s.candidates.front();
    c.basis_size = choose_parameter(get_parameter(np, internal_np::spectral_basis_size), c.basis_size);
    c.orientation_weight = choose_parameter(get_parameter(np, internal_np::orientation_weight),
                                            c.orientation_weight);
    c.commutativity_weight = choose_parameter(get_parameter(np, internal_np::commutativity_weight),
                                              c.commutativity_weight);
    s.candidates.assign(1, c);
  }
  s.tear_repair_passes = choose_parameter(get_parameter(np, internal_np::number_of_repair_passes),
                                          s.tear_repair_passes);
  s.tear_threshold = choose_parameter(get_parameter(np, internal_np::tear_threshold), s.tear_threshold);
  s.tear_repair_distortion_tolerance = choose_parameter(
      get_parameter(np, internal_np::tear_repair_distortion_tolerance), s.tear_repair_distortion_tolerance);
  s.distortion_repair_passes = choose_parameter(
      get_parameter(np, internal_np::number_of_distortion_repair_passes), s.distortion_repair_passes);
  s.compare_with_automatic_maps = choose_parameter(get_parameter(np, internal_np::compare_with_automatic_maps),
                                                   s.compare_with_automatic_maps);
  s.automatic_maps_comparison_threshold = choose_parameter(
      get_parameter(np, internal_np::automatic_maps_comparison_threshold), s.automatic_maps_comparison_threshold);
  s.verbose = choose_parameter(get_parameter(np, CGAL::internal_np::verbose), s.verbose);
  const auto& landmarks = get_parameter(np, internal_np::landmarks);
  if constexpr(!std::is_same<typename std::decay<decltype(landmarks)>::type,
                             CGAL::internal_np::Param_not_found>::value)
  {
    for(const auto& l : landmarks)
      s.landmarks.emplace_back(static_cast<std::size_t>(l.first), static_cast<std::size_t>(l.second));
  }
  return s;
}

/// The largest candidate basis size that is tried (candidates above zoomout_final_size are skipped).
inline int largest_candidate_size(const Initialization_settings& s)
{
  int k = 0;
  for(const Fit_candidate& c : s.candidates)
    if(c.basis_size <= s.zoomout_final_size) k = std::max(k, c.basis_size);
  return k;
}

/// Checks the settings against each other (not against the meshes).
inline void check_initialization_settings(const Initialization_settings& s)
{
  auto fail = [](const std::string& what) {
    throw Invalid_parameter_error("automatic_initial_maps: " + what);
  };
  if(s.candidates.empty()) fail("no functional map configuration to try");
  for(const Fit_candidate& c : s.candidates)
  {
    if(c.basis_size < 2)
      fail("spectral_basis_size = " + std::to_string(c.basis_size) + " must be at least 2");
    if(!(c.orientation_weight >= 0) || !(c.commutativity_weight >= 0) || !std::isfinite(c.orientation_weight) ||
       !std::isfinite(c.commutativity_weight))
      fail("orientation_weight and commutativity_weight must be finite and non-negative");
  }
  if(largest_candidate_size(s) == 0)
  {
    int smallest = s.candidates.front().basis_size;
    for(const Fit_candidate& c : s.candidates) smallest = std::min(smallest, c.basis_size);
    fail("zoomout_final_size = " + std::to_string(s.zoomout_final_size) +
         " must be at least spectral_basis_size = " + std::to_string(smallest));
  }
  if((s.select_by_distortion || s.distortion_repair_passes > 0) && s.distortion_samples < 2)
    fail("distortion_samples = " + std::to_string(s.distortion_samples) + " must be at least 2");
  if(s.zoomout_step < 1) fail("zoomout_step = " + std::to_string(s.zoomout_step) + " must be positive");
  if(s.zoomout_growth_step < 1)
    fail("zoomout_growth_step = " + std::to_string(s.zoomout_growth_step) + " must be positive");
  if(s.zoomout_pass_size < 2)
    fail("zoomout_pass_size = " + std::to_string(s.zoomout_pass_size) + " must be at least 2");
  if(s.number_of_eigenpairs != 0 && s.number_of_eigenpairs < s.zoomout_final_size)
    fail("number_of_eigenpairs = " + std::to_string(s.number_of_eigenpairs) +
         " is smaller than zoomout_final_size = " + std::to_string(s.zoomout_final_size));
  if(!(s.wks_weight >= 0) || !(s.hks_weight >= 0) || !(s.wks_weight + s.hks_weight > 0))
    fail("the descriptor weights (wks_weight, hks_weight) must be non-negative, one of them positive");
  if(s.wks_weight > 0 && s.number_of_wks_energies < 2)
    fail("number_of_wks_energies must be at least 2");
  if(s.hks_weight > 0 && s.number_of_hks_scales < 1) fail("number_of_hks_scales must be positive");
  if(!(s.signed_descriptor_weight >= 0)) fail("the signed descriptor weight must be non-negative");
  if(!(s.weights.laplacian >= 0) || !(s.weights.descriptor > 0)) fail("invalid functional map weights");
  if(s.landmark_orientation < -1 || s.landmark_orientation > 1) fail("landmark_orientation must be -1, 0 or 1");
  if(s.tear_repair_passes < 0) fail("tear_repair_passes must be non-negative");
  if(s.distortion_repair_passes < 0) fail("distortion_repair_passes must be non-negative");
  if(!(s.automatic_maps_comparison_threshold >= 0) || !std::isfinite(s.automatic_maps_comparison_threshold))
    fail("automatic_maps_comparison_threshold = " + std::to_string(s.automatic_maps_comparison_threshold) +
         " must be finite and non-negative");
  if(!(s.distortion_core_tolerance > 0) || !std::isfinite(s.distortion_core_tolerance))
    fail("distortion_core_tolerance must be positive");
  if(!(s.distortion_core_agreement > 0) || !(s.distortion_core_agreement <= 1))
    fail("distortion_core_agreement must be in (0, 1]");
  if(!(s.distortion_repair_threshold >= 0) || !std::isfinite(s.distortion_repair_threshold))
    fail("distortion_repair_threshold must be non-negative");
  if(s.maximum_passes < 1) fail("maximum_passes must be positive");
  if(!(s.distortion_repair_gain >= 0) || !(s.distortion_repair_gain < 1))
    fail("distortion_repair_gain must be in [0, 1)");
  if(!(s.tear_threshold > 0) || !std::isfinite(s.tear_threshold)) fail("tear_threshold must be positive");
  if(!(s.tear_min_fraction >= 0) || !(s.tear_min_fraction < 1)) fail("tear_min_fraction must be in [0, 1)");
  if(!std::isfinite(s.tear_repair_distortion_tolerance)) fail("tear_repair_distortion_tolerance must be finite");
  if(s.tear_repair_landmarks < 1) fail("tear_repair_landmarks must be positive");
}

/// The number of eigenpairs the initialisation needs.
inline int initialization_number_of_eigenpairs(const Initialization_settings& s)
{
  return s.number_of_eigenpairs > 0 ? s.number_of_eigenpairs : s.zoomout_final_size;
}

/// The basis size at which the fit candidates are compared: selection_size, at least the largest
/// candidate, at most zoomout_final_size.
inline int selection_basis_size(const Initialization_settings& s)
{
  return std::min(std::max(s.selection_size, largest_candidate_size(s)), s.zoomout_final_size);
}

/// The basis size at which every pass ends its ZoomOut: zoomout_pass_size, at least
/// selection_basis_size(), at most zoomout_final_size.
inline int pass_final_size(const Initialization_settings& s)
{
  return std::min(s.zoomout_final_size, std::max(s.zoomout_pass_size, selection_basis_size(s)));
}

/// The ZoomOut schedule of the initialisation from `step` to `final_size`.
inline Zoomout_settings initialization_zoomout_settings(const Initialization_settings& s, int step, int final_size)
{
  Zoomout_settings zs;
  zs.step = step;
  zs.final_size = final_size;
  zs.landmark_weight = s.zoomout_landmark_weight;
  zs.bijectivity_weight = s.zoomout_bijectivity_weight;
  zs.feature_final_ratio = s.zoomout_descriptor_final_ratio;
  return zs;
}

/// ZoomOut of both functional maps of a pair (unit-area bases and masses), coupled or one
/// direction at a time as `coupled_zoomout` says: C12 and C21 are replaced by the final maps,
/// t12 and t21 receive the point maps of all vertices.
template <typename ConcurrencyTag>
void zoomout_pair(const Eigen::MatrixXd& basis1, const Eigen::VectorXd& mass1, const Eigen::MatrixXd& basis2,
                  const Eigen::VectorXd& mass2, const Initialization_settings& s, const Zoomout_settings& zs,
                  const std::vector<int>& rows1, const std::vector<int>& rows2,
                  const std::vector<std::pair<int, int> >& landmarks, Eigen::MatrixXd& C12, Eigen::MatrixXd& C21,
                  std::vector<int>& t12, std::vector<int>& t21, const Zoomout_features& features12 = Zoomout_features(),
                  const Zoomout_features& features21 = Zoomout_features())
{
  if(s.coupled_zoomout)
  {
    coupled_zoomout_refine<ConcurrencyTag>(basis1, mass1, basis2, mass2, C12, C21, zs, rows1, rows2, landmarks, t12,
                                           t21, features12);
    return;
  }
  std::vector<std::pair<int, int> > landmarks21;
  for(const auto& l : landmarks) landmarks21.emplace_back(l.second, l.first);
  C12 = zoomout_refine<ConcurrencyTag>(basis1, mass1, basis2, C12, zs, rows1, landmarks, t12, features12);
  C21 = zoomout_refine<ConcurrencyTag>(basis2, mass2, basis1, C21, zs, rows2, landmarks21, t21, features21);
}

/// Column layout of initialization_descriptors(): d_wks WKS columns, d_hks HKS columns, then the
/// signed descriptors of the pairs below.
struct Initialization_descriptor_layout
{
  int wks = 0, hks = 0;
  std::vector<std::pair<int, int> > signed_pairs;  ///< pairs of (WKS or HKS) columns
  int plain() const { return wks + hks; }
  int total() const { return plain() + static_cast<int>(signed_pairs.size()); }
};

inline Initialization_descriptor_layout initialization_descriptor_layout(const Initialization_settings& s)
{
  Initialization_descriptor_layout l;
  const bool with_signed = s.signed_descriptor_weight > 0 && s.number_of_wks_energies >= 2 &&
                           s.number_of_hks_scales >= 2;
  l.wks = (s.wks_weight > 0 || with_signed) ? s.number_of_wks_energies : 0;
  l.hks = (s.hks_weight > 0 || with_signed) ? s.number_of_hks_scales : 0;
  if(with_signed)
  {
    // Pairs of smooth, large-scale functions (WKS at low energies, HKS at long times) and a few
    // mid-range WKS pairs; these were the most consistent across the poses and people of FAUST_r
    // (correlation of the values at ground-truth correspondences, benchmark/bench_init.cpp).
    auto wks = [&](double f) { return static_cast<int>(std::lround(f * (l.wks - 1))); };
    auto hks = [&](double f) { return l.wks + static_cast<int>(std::lround(f * (l.hks - 1))); };
    const std::pair<int, int> pairs[] = {{wks(0.3), wks(0.7)}, {wks(0.0), hks(1.0)}, {hks(2.0 / 3.0), hks(1.0)},
                                         {wks(0.05), hks(1.0)}, {wks(0.05), hks(2.0 / 3.0)}, {wks(0.0), wks(0.05)},
                                         {wks(0.7), wks(0.9)}, {wks(0.1), wks(0.2)}};
    for(const auto& p : pairs)
      if(p.first != p.second) l.signed_pairs.push_back(p);
  }
  return l;
}

/// The descriptors of one shape used by the initialisation, n x d (see
/// Initialization_descriptor_layout): WKS columns (if wks_weight > 0), HKS columns (if
/// hks_weight > 0), then orientation-sensitive columns <n, grad f x grad g> for pairs of them,
/// smoothed by projection on the first `signed_descriptor_smoothing` eigenfunctions. Compute once
/// per shape; initialization_descriptor_weights() gives the column weights.
template <typename ConcurrencyTag>
Eigen::MatrixXd initialization_descriptors(const Indexed_mesh& mesh, const Laplace_beltrami_spectrum& spectrum,
                                           const Initialization_settings& s)
{
  const int n = spectrum.number_of_vertices();
  const Initialization_descriptor_layout l = initialization_descriptor_layout(s);
  Eigen::MatrixXd out(n, l.total());
  // The pass's eigenpairs only: the descriptors, and so the passes, do not depend on the final size.
  const int k = std::min(pass_final_size(s), spectrum.number_of_eigenpairs());
  if(l.wks > 0)
    out.leftCols(l.wks) = wave_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_wks_energies(
                      l.wks, parameters::wks_variance(s.wks_variance, parameters::number_of_eigenpairs(k))));
  if(l.hks > 0)
    out.middleCols(l.wks, l.hks) = heat_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_hks_scales(l.hks, parameters::number_of_eigenpairs(k)));
  if(!l.signed_pairs.empty())
  {
    Eigen::MatrixXd g = gradient_cross_products(mesh, out.leftCols(l.plain()), l.signed_pairs,
                                                1.0 / std::sqrt(spectrum.total_area()));
    const int smoothing = std::min(s.signed_descriptor_smoothing, spectrum.number_of_eigenpairs());
    if(smoothing > 0)
    {
      const Eigen::MatrixXd& phi = spectrum.eigenvectors();
      g = phi.leftCols(smoothing) * (phi.leftCols(smoothing).transpose() * (spectrum.mass().asDiagonal() * g));
    }
    out.rightCols(g.cols()) = g;
  }
  return out;
}

/// The column weights matching initialization_descriptors().
inline Eigen::VectorXd initialization_descriptor_weights(const Initialization_settings& s)
{
  const Initialization_descriptor_layout l = initialization_descriptor_layout(s);
  Eigen::VectorXd w(l.total());
  w.head(l.wks).setConstant(std::max(0.0, s.wks_weight));
  w.segment(l.wks, l.hks).setConstant(std::max(0.0, s.hks_weight));
  w.tail(l.signed_pairs.size()).setConstant(s.signed_descriptor_weight);
  return w;
}

/// What the core needs of one shape; the stateful shape class precomputes it once per mesh.
struct Initialization_shape
{
  const Indexed_mesh* mesh = nullptr;
  const Laplace_beltrami_spectrum* spectrum = nullptr;
  /// n x d descriptors (initialization_descriptors()); columns correspond across shapes.
  const Eigen::MatrixXd* descriptors = nullptr;
};

/// Signed volume of a closed mesh (0 with a boundary): its sign tells the orientation.
inline double signed_volume(const Indexed_mesh& m)
{
  if(m.has_boundary()) return 0;
  double v = 0;
  for(int t = 0; t < m.number_of_triangles(); ++t)
    v += m.point(m.triangles(t, 0)).dot(m.point(m.triangles(t, 1)).cross(m.point(m.triangles(t, 2))));
  return v / 6.0;
}

/// Wave kernel maps from landmark vertices: for landmark p and energy e, the vertex function
/// sum_{j: lambda_j > 0} g_j(e) phi_j(p) phi_j(x) / sum_j g_j(e) (unit-area eigenpairs), which
/// does not depend on the signs of the eigenvectors.
inline Eigen::MatrixXd landmark_wave_kernel_maps(const Eigen::MatrixXd& basis, const Eigen::VectorXd& values,
                                                 const std::vector<int>& points, int energies)
{
  const Eigen::Index k = basis.cols();
  int first = 0;
  while(first < k && !(values[first] > 1e-9 * values[k - 1])) ++first;
  const double lo = std::log(values[std::min<Eigen::Index>(first, k - 1)]), hi = std::log(values[k - 1]);
  const double delta = energies > 1 ? (hi - lo) / (energies - 1) : (hi - lo);
  const double sigma = 7.0 * delta;
  // Column (l, e) of the result is basis * (g_e .* phi(p_l)): one matrix product for all of them.
  Eigen::MatrixXd spectral(k, Eigen::Index(points.size()) * energies);
  for(int e = 0; e < energies; ++e)
  {
    const double energy = energies > 1 ? lo + e * delta : 0.5 * (lo + hi);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(k);
    for(Eigen::Index j = first; j < k; ++j)
    {
      const double d = energy - std::log(values[j]);
      g[j] = std::exp(-d * d / (2 * sigma * sigma));
    }
    g /= std::max(g.sum(), 1e-300);
    for(std::size_t l = 0; l < points.size(); ++l)
      spectral.col(Eigen::Index(l) * energies + e) = g.cwiseProduct(basis.row(points[l]).transpose());
  }
  return basis * spectral;
}

/// The reduced terms of one shape at basis size k: descriptor coefficients and, for the columns
/// `operator_columns`, the multiplication and orientation operators.
template <typename ConcurrencyTag>
Functional_map_shape_terms initialization_terms(const Indexed_mesh& mesh, const Eigen::MatrixXd& basis_k,
                                                const Eigen::VectorXd& mass, const Eigen::VectorXd& values_k,
                                                double area, const Eigen::MatrixXd& descriptors,
                                                const std::vector<Eigen::Index>& operator_columns,
                                                const Initialization_settings& s)
{
  Functional_map_shape_terms t;
  t.eigenvalues = values_k;
  t.descriptor_coefficients = basis_k.transpose() * (mass.asDiagonal() * descriptors);
  const std::size_t m = operator_columns.size();
  if(m == 0) return t;
  const Reduced_operator_geometry g =
      reduced_operator_geometry(mesh, basis_k, mass, 1.0 / std::sqrt(area), 1.0 / area);
  t.multiplication_operators.resize(m);
  t.orientation_operators.resize(m);
  parallel_for<ConcurrencyTag>(m, [&](std::size_t i) {
    const Eigen::VectorXd f = descriptors.col(operator_columns[i]);
    t.multiplication_operators[i] = reduced_multiplication_operator(g, f);
    t.orientation_operators[i] = reduced_orientation_operator(mesh, g, f, s.normalize_orientation_gradients);
  });
  return t;
}

/// The terms restricted to the first k basis functions (the reduced operators of a smaller basis
/// are the leading blocks of those of a larger one).
inline Functional_map_shape_terms leading_terms(const Functional_map_shape_terms& t, int k)
{
  Functional_map_shape_terms r;
  r.eigenvalues = t.eigenvalues.head(k);
  r.descriptor_coefficients = t.descriptor_coefficients.topRows(k);
  for(const Eigen::MatrixXd& x : t.multiplication_operators) r.multiplication_operators.push_back(x.topLeftCorner(k, k));
  for(const Eigen::MatrixXd& x : t.orientation_operators) r.orientation_operators.push_back(x.topLeftCorner(k, k));
  return r;
}

/// Divides each pair of corresponding operators (S_f, T_f) by the mean of their Frobenius norms,
/// so that the commutativity terms measure relative residuals.
inline void normalize_operator_pairs(Functional_map_shape_terms& a, Functional_map_shape_terms& b)
{
  auto normalize = [](std::vector<Eigen::MatrixXd>& x, std::vector<Eigen::MatrixXd>& y) {
    for(std::size_t f = 0; f < x.size(); ++f)
    {
      const double scale = 0.5 * (x[f].norm() + y[f].norm());
      if(scale > 0)
      {
        x[f] /= scale;
        y[f] /= scale;
      }
    }
  };
  normalize(a.multiplication_operators, b.multiplication_operators);
  normalize(a.orientation_operators, b.orientation_operators);
}

/// The orthogonal matrix nearest to C in the Frobenius norm (U V^T of the SVD).
inline Eigen::MatrixXd nearest_orthogonal(const Eigen::MatrixXd& C)
{
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return svd.matrixU() * svd.matrixV().transpose();
}

/// Mean normalised Euclidean cycle error and fixed-point fraction of x -> back(forth(x)).
inline void cycle_statistics(const Indexed_mesh& m, const std::vector<int>& forth,
                             const std::vector<int>& back, double& error, double& fixed)
{
  const double scale = 1.0 / std::sqrt(m.total_area);
  double e = 0;
  std::size_t f = 0;
  for(std::size_t x = 0; x < forth.size(); ++x)
  {
    const int y = back[forth[x]];
    if(y == int(x)) ++f;
    e += (m.points.row(x) - m.points.row(y)).norm() * scale;
  }
  error = e / double(forth.size());
  fixed = double(f) / double(forth.size());
}

/// The area-weighted fraction of the triangles of `source` (with three distinct images) whose
/// image under `map` has the orientation of `target` (its vertex normals): about 1 for an
/// orientation-preserving map, 0 for a mirror map, 1/2 for a scrambled one.
inline double orientation_agreement(const Indexed_mesh& source, const Indexed_mesh& target,
                                    const Indexed_mesh::Points& target_normals, const std::vector<int>& map)
{
  double agree = 0, total = 0;
  for(int t = 0; t < source.number_of_triangles(); ++t)
  {
    const int a = map[source.triangles(t, 0)], b = map[source.triangles(t, 1)], c = map[source.triangles(t, 2)];
    if(a == b || b == c || a == c) continue;
    const Eigen::Vector3d normal = (target.point(b) - target.point(a)).cross(target.point(c) - target.point(a));
    const Eigen::Vector3d reference =
        (target_normals.row(a) + target_normals.row(b) + target_normals.row(c)).transpose();
    const double w = source.triangle_areas[t];
    total += w;
    if(normal.dot(reference) > 0) agree += w;
  }
  return total > 0 ? agree / total : 0.5;
}

/// Stores the final maps of a pass (or of grow_initial_maps()) and their cycle statistics,
/// orientation agreement and functional maps in `result`.
inline void set_initial_maps(const Indexed_mesh& m1, const Indexed_mesh& m2, const std::vector<int>& t12,
                             const std::vector<int>& t21, const Eigen::MatrixXd& C12, const Eigen::MatrixXd& C21,
                             std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                             Automatic_initialization_result& result)
{
  const double n1 = double(m1.number_of_vertices()), n2 = double(m2.number_of_vertices());
  double e1, f1, e2, f2;
  cycle_statistics(m1, t12, t21, e1, f1);
  cycle_statistics(m2, t21, t12, e2, f2);
  result.cycle_error = (e1 * n1 + e2 * n2) / (n1 + n2);
  result.cycle_fixed_fraction = (f1 * n1 + f2 * n2) / (n1 + n2);
  result.orientation_agreement = 0.5 * (orientation_agreement(m1, m2, vertex_normals(m2), t12) +
                                        orientation_agreement(m2, m1, vertex_normals(m1), t21));
  result.functional_map_12 = C12;
  result.functional_map_21 = C21;
  map_12.assign(t12.begin(), t12.end());
  map_21.assign(t21.begin(), t21.end());
}

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

  /// The row of a run from `source`, or null.
  const std::vector<double>* find(int source) const
  {
    const auto it = rows_.find(source);
    return it == rows_.end() ? nullptr : &it->second;
  }
  /// Whether a new row of `n` distances fits in the budget.
  bool has_room(std::size_t n) const { return bytes_ + n * sizeof(double) <= budget_; }
  /// Keeps `row` as the run from `source` (replacing an older row of that source).
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
        if(cache && (r < room || cache->find(vertices_[i]))) w.copy_distances(new_rows[r]);
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

/// Checks one shape against the settings.
inline void check_initialization_shape(const Initialization_shape& shape, int k, const std::string& name)
{
  if(!shape.mesh || !shape.spectrum || !shape.descriptors)
    throw Invalid_parameter_error("automatic_initial_maps: missing data for " + name);
  const Indexed_mesh& m = *shape.mesh;
  if(m.number_of_components != 1)
    throw Invalid_mesh_error("automatic_initial_maps: " + name + " has " +
                             std::to_string(m.number_of_components) +
                             " connected components; the spectral initialisation needs a connected "
                             "mesh (keep the largest component, e.g. with "
                             "CGAL::Polygon_mesh_processing::keep_largest_connected_components)");
  if(m.number_of_vertices() <= k)
    throw Invalid_mesh_error("automatic_initial_maps: " + name + " has " +
                             std::to_string(m.number_of_vertices()) + " vertices, too few for a basis of " +
                             std::to_string(k) + " eigenfunctions (reduce zoomout_final_size)");
  if(shape.spectrum->number_of_vertices() != m.number_of_vertices() ||
     shape.descriptors->rows() != m.number_of_vertices())
    throw Invalid_parameter_error("automatic_initial_maps: the spectrum or descriptors of " + name +
                                  " do not match its vertices");
  if(shape.spectrum->number_of_eigenpairs() < k)
    throw Invalid_parameter_error("automatic_initial_maps: the spectrum of " + name + " has " +
                                  std::to_string(shape.spectrum->number_of_eigenpairs()) +
                                  " eigenpairs, fewer than zoomout_final_size = " + std::to_string(k));
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
};

/// The samplings of both meshes, computed by the first pass and reused by the repair passes
/// (recomputed when the sample counts change).
struct Initialization_pass_cache
{
  bool ready = false;
  int number_of_samples = 0, distortion_count = 0;
  Initialization_sampling first, second;
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

/// One pass of automatic_initial_maps() on precomputed shapes (flat mesh, spectrum with at least
/// zoomout_final_size eigenpairs, descriptors from initialization_descriptors() with the same
/// settings): fits, selection and coupled ZoomOut, without the tear repair.
template <typename ConcurrencyTag>
Automatic_initialization_result single_pass_initial_maps(const Initialization_shape& shape1,
                                                       const Initialization_shape& shape2,
                                                       const Initialization_settings& s,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       Initialization_pass_cache* pass_cache = nullptr)
{
  typedef std::chrono::steady_clock Clock;
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  const Clock::time_point start = Clock::now();
  check_initialization_settings(s);
  const int kf = s.zoomout_final_size;
  const int kmax = largest_candidate_size(s);
  check_initialization_shape(shape1, kf, "mesh 1");
  check_initialization_shape(shape2, kf, "mesh 2");
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  const int n1 = m1.number_of_vertices(), n2 = m2.number_of_vertices();
  const Initialization_descriptor_layout layout = initialization_descriptor_layout(s);
  const Eigen::VectorXd descriptor_weights = initialization_descriptor_weights(s);
  for(const Initialization_shape* shape : {&shape1, &shape2})
    if(shape->descriptors->cols() != layout.total() || !shape->descriptors->allFinite())
      throw Invalid_parameter_error("automatic_initial_maps: the descriptors have " +
                                    std::to_string(shape->descriptors->cols()) + " columns, " +
                                    std::to_string(layout.total()) +
                                    " expected (compute them with initialization_descriptors() and "
                                    "the same settings), or non-finite values");
  std::vector<std::pair<int, int> > landmarks;
  for(const auto& l : s.landmarks)
  {
    if(l.first >= std::size_t(n1) || l.second >= std::size_t(n2))
      throw Invalid_parameter_error("automatic_initial_maps: landmark (" + std::to_string(l.first) +
                                    ", " + std::to_string(l.second) + ") is not a pair of vertices of "
                                    "mesh 1 (" + std::to_string(n1) + " vertices) and mesh 2 (" +
                                    std::to_string(n2) + " vertices)");
    landmarks.emplace_back(int(l.first), int(l.second));
  }
  std::vector<std::pair<int, int> > landmarks21;
  for(const auto& l : landmarks) landmarks21.emplace_back(l.second, l.first);

  Automatic_initialization_result result;
  result.passes = 1;
  const Laplace_beltrami_spectrum& S1 = *shape1.spectrum;
  const Laplace_beltrami_spectrum& S2 = *shape2.spectrum;
  const double A1 = S1.total_area(), A2 = S2.total_area();
  // Unit-area bases, masses and eigenvalues.
  const Eigen::MatrixXd basis1 = unit_area_basis(S1, kf), basis2 = unit_area_basis(S2, kf);
  const Eigen::VectorXd mass1 = unit_area_mass(S1), mass2 = unit_area_mass(S2);
  const Eigen::VectorXd values1 = S1.eigenvalues().head(kf) * A1, values2 = S2.eigenvalues().head(kf) * A2;

  // Descriptors: columns normalised to unit L2(M') norm on each shape, then landmark maps.
  const Clock::time_point fit_start = Clock::now();
  Eigen::MatrixXd D1 = *shape1.descriptors, D2 = *shape2.descriptors;
  Eigen::VectorXd column_weights = descriptor_weights;
  auto normalise = [](Eigen::MatrixXd& D, const Eigen::VectorXd& mass) {
    for(Eigen::Index c = 0; c < D.cols(); ++c)
    {
      const double norm = std::sqrt(D.col(c).cwiseAbs2().dot(mass));
      if(norm > 0) D.col(c) /= norm;
    }
  };
  normalise(D1, mass1);
  normalise(D2, mass2);
  // Meshes of opposite orientations (closed, signed volumes of opposite signs): the map reverses
  // the orientation of the embedding, so the signed descriptors of mesh 2 change sign.
  int orientation_sign = (signed_volume(m1) * signed_volume(m2) < 0) ? -1 : 1;
  // Operators for evenly spread plain descriptor columns with positive weight.
  std::vector<Eigen::Index> operator_columns;
  {
    std::vector<Eigen::Index> candidates;
    for(Eigen::Index c = 0; c < layout.plain(); ++c)
      if(column_weights[c] > 0) candidates.push_back(c);
    const std::size_t m = std::min<std::size_t>(candidates.size(),
                                                std::size_t(std::max(0, s.number_of_operator_descriptors)));
    for(std::size_t i = 0; i < m; ++i)
      operator_columns.push_back(candidates[(i * candidates.size() + candidates.size() / (2 * m)) / m]);
  }
  if(!landmarks.empty())
  {
    std::vector<int> p1, p2;
    for(const auto& l : landmarks)
    {
      p1.push_back(l.first);
      p2.push_back(l.second);
    }
    Eigen::MatrixXd L1, L2;
    invoke_both<ConcurrencyTag>(
        [&] { L1 = landmark_wave_kernel_maps(basis1, values1, p1, s.number_of_landmark_energies); },
        [&] { L2 = landmark_wave_kernel_maps(basis2, values2, p2, s.number_of_landmark_energies); });
    normalise(L1, mass1);
    normalise(L2, mass2);
    const Eigen::Index d = D1.cols(), dl = L1.cols();
    D1.conservativeResize(Eigen::NoChange, d + dl);
    D2.conservativeResize(Eigen::NoChange, d + dl);
    D1.rightCols(dl) = L1;
    D2.rightCols(dl) = L2;
    column_weights.conservativeResize(d + dl);
    column_weights.tail(dl).setConstant(s.landmark_descriptor_weight);
  }
  const Eigen::Index signed_begin = layout.plain(), signed_count = Eigen::Index(layout.signed_pairs.size());
  if(orientation_sign < 0) D2.middleCols(signed_begin, signed_count) *= -1.0;

  // Reduced terms at the largest candidate size (smaller ones are leading blocks).
  Functional_map_shape_terms T1, T2;
  invoke_both<ConcurrencyTag>(
      [&] {
        T1 = initialization_terms<ConcurrencyTag>(m1, basis1.leftCols(kmax), mass1, values1.head(kmax), A1, D1,
                                                  operator_columns, s);
      },
      [&] {
        T2 = initialization_terms<ConcurrencyTag>(m2, basis2.leftCols(kmax), mass2, values2.head(kmax), A2, D2,
                                                  operator_columns, s);
      });

  // Samples for the ZoomOut iterations and the distortion score (shared by all passes).
  Initialization_pass_cache own_cache;
  Initialization_pass_cache& cache = pass_cache ? *pass_cache : own_cache;
  prepare_pass_cache<ConcurrencyTag>(shape1, shape2, s, cache);
  const Initialization_samples& samples1 = cache.first.samples;
  const Initialization_samples& samples2 = cache.second.samples;
  const Eigen::MatrixXd& sample_distances1 = cache.first.sample_distances;
  const Eigen::MatrixXd& sample_distances2 = cache.second.sample_distances;
  const std::vector<int>& rows1 = samples1.rows;
  const std::vector<int>& rows2 = samples2.rows;
  Eigen::MatrixXd features1, features2;
  Zoomout_features features12, features21;
  // Feature weights: sqrt(w_c / sum w) times the ZoomOut descriptor weight, for all columns or the
  // signed ones only.
  Eigen::VectorXd feature_weights = column_weights;
  if(s.zoomout_signed_features_only && signed_count > 0)
  {
    feature_weights.setZero();
    feature_weights.segment(signed_begin, signed_count) = column_weights.segment(signed_begin, signed_count);
  }
  if(feature_weights.sum() > 0)
    feature_weights = (feature_weights / feature_weights.sum()).cwiseSqrt() * s.zoomout_descriptor_weight;
  auto make_features = [&](const Eigen::MatrixXd& D) {
    std::vector<Eigen::Index> used;
    for(Eigen::Index c = 0; c < feature_weights.size(); ++c)
      if(feature_weights[c] > 0) used.push_back(c);
    Eigen::MatrixXd F(D.rows(), Eigen::Index(used.size()));
    for(std::size_t i = 0; i < used.size(); ++i) F.col(Eigen::Index(i)) = feature_weights[used[i]] * D.col(used[i]);
    return F;
  };
  if(s.zoomout_descriptor_weight > 0)
  {
    features1 = make_features(D1);
    features2 = make_features(D2);
    features12.source = features21.target = &features1;
    features12.target = features21.source = &features2;
  }
  const Zoomout_settings select_settings = initialization_zoomout_settings(s, s.zoomout_step, selection_basis_size(s));

  // Candidates: fits of both directions for every configuration (and, with landmarks, for both
  // orientations), each refined by a short ZoomOut to the selection size and scored by the
  // weighted descriptor distance between matched sample vertices.
  struct Candidate
  {
    Fit_candidate config;
    int sign;
    int inverse_of;               // -1: a fit; else the index of the fit whose maps it inverts
    Eigen::MatrixXd C12, C21;     // after the short ZoomOut
    std::vector<int> images12, images21;  // of the distortion samples
    double score12 = 0, score21 = 0;
  };
  std::vector<Candidate> candidates;
  const std::vector<int> signs = landmarks.empty()             ? std::vector<int>{1}
                                 : s.landmark_orientation != 0 ? std::vector<int>{s.landmark_orientation}
                                                               : std::vector<int>{1, -1};
  for(int sign : signs)
    for(const Fit_candidate& c : s.candidates)
      if(c.basis_size <= kf) candidates.push_back({c, sign, -1, {}, {}, {}, {}});
  auto score = [&](const Eigen::MatrixXd& Da, const Eigen::MatrixXd& Db, const std::vector<int>& rows,
                   const std::vector<int>& map_rows) {
    double total = 0;
    for(std::size_t r = 0; r < map_rows.size(); ++r)
      total += (Da.row(rows.empty() ? int(r) : rows[r]) - Db.row(map_rows[r])).cwiseAbs2().dot(column_weights);
    return total / (double(map_rows.size()) * column_weights.sum());
  };
  // Short ZoomOut of both maps on the samples, then the descriptor scores of the sample matches
  // (or the images of the distortion samples, scored once all candidates are known).
  auto zoom_and_score = [&](Candidate& c, const Eigen::MatrixXd& C12, const Eigen::MatrixXd& C21) {
    std::vector<int> t12, t21;
    c.C12 = zoomout_refine<CGAL::Sequential_tag>(basis1, mass1, basis2, C12, select_settings, rows1, landmarks,
                                                 t12, Zoomout_features(), true);
    c.C21 = zoomout_refine<CGAL::Sequential_tag>(basis2, mass2, basis1, C21, select_settings, rows2, landmarks21,
                                                 t21, Zoomout_features(), true);
    if(s.select_by_distortion)
    {
      for(int r : samples1.distortion_rows) c.images12.push_back(t12[r]);
      for(int r : samples2.distortion_rows) c.images21.push_back(t21[r]);
    }
    else
    {
      Eigen::MatrixXd F2 = D2;
      if(c.sign < 0) F2.middleCols(signed_begin, signed_count) *= -1.0;
      c.score12 = score(D1, F2, rows1, t12);
      c.score21 = score(F2, D1, rows2, t21);
    }
  };
  // The fits, one task per candidate and direction, the largest bases first: a fit's cost grows
  // steeply with k0 (k0 = 60 is solved iteratively), so this keeps the threads busy to the end.
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd> > fitted(candidates.size());
  std::vector<std::size_t> fit_order(2 * candidates.size());
  std::iota(fit_order.begin(), fit_order.end(), std::size_t(0));
  std::stable_sort(fit_order.begin(), fit_order.end(), [&](std::size_t x, std::size_t y) {
    return candidates[x / 2].config.basis_size > candidates[y / 2].config.basis_size;
  });
  parallel_for_in_order<ConcurrencyTag>(fit_order.size(), [&](std::size_t t) {
    const std::size_t i = fit_order[t] / 2;
    const bool forward = fit_order[t] % 2 == 0;
    const Candidate& c = candidates[i];
    Functional_map_shape_terms a = leading_terms(T1, c.config.basis_size);
    Functional_map_shape_terms b = leading_terms(T2, c.config.basis_size);
    normalize_operator_pairs(a, b);
    Functional_map_weights w = s.weights;
    w.orientation = c.config.orientation_weight;
    w.commutativity = c.config.commutativity_weight;
    w.orientation_sign = orientation_sign * c.sign;
    if(c.sign < 0)
    {
      // The mirror hypothesis: the signed descriptors of mesh 2 change sign.
      b.descriptor_coefficients.middleCols(signed_begin, signed_count) *= -1.0;
    }
    Eigen::MatrixXd C = forward ? minimize_functional_map_energy(a, b, w, column_weights)
                                : minimize_functional_map_energy(b, a, w, column_weights);
    if(s.procrustes) C = nearest_orthogonal(C);
    (forward ? fitted[i].first : fitted[i].second) = std::move(C);
  });
  parallel_for<ConcurrencyTag>(candidates.size(),
                               [&](std::size_t i) { zoom_and_score(candidates[i], fitted[i].first, fitted[i].second); });
  if(s.select_by_distortion)
  {
    // The inverses of the fitted maps (C_21^T for 1 -> 2 and C_12^T for 2 -> 1, the maps being
    // nearly orthogonal) are candidates too: one direction often finds the right map when the
    // other does not.
    const std::size_t fits = candidates.size();
    for(std::size_t i = 0; i < fits; ++i)
      candidates.push_back({candidates[i].config, candidates[i].sign, int(i), {}, {}, {}, {}});
    parallel_for<ConcurrencyTag>(fits, [&](std::size_t i) {
      Candidate& c = candidates[fits + i];
      zoom_and_score(c, candidates[i].C21.transpose(), candidates[i].C12.transpose());
    });
    // The distortion scores: geodesic distances between all the images, then lookups.
    std::vector<int> all12, all21;
    for(const Candidate& c : candidates)
    {
      all12.insert(all12.end(), c.images12.begin(), c.images12.end());
      all21.insert(all21.end(), c.images21.begin(), c.images21.end());
    }
    Vertex_set_distances distances2, distances1;
    distances2.compute<ConcurrencyTag>(cache.second.geodesics, std::move(all12), std::sqrt(A2), &cache.second.rows);
    distances1.compute<ConcurrencyTag>(cache.first.geodesics, std::move(all21), std::sqrt(A1), &cache.first.rows);
    for(Candidate& c : candidates)
    {
      c.score12 = map_distortion(sample_distances1, distances2, c.images12);
      c.score21 = map_distortion(sample_distances2, distances1, c.images21);
    }
    if(s.verbose)
      std::cerr << "  distortion scores: " << distances2.size() << " and " << distances1.size()
                << " distinct sample images\n";
  }
  std::size_t best12 = 0, best21 = 0;
  for(std::size_t i = 1; i < candidates.size(); ++i)
  {
    if(candidates[i].score12 < candidates[best12].score12) best12 = i;
    if(candidates[i].score21 < candidates[best21].score21) best21 = i;
  }
  if(!landmarks.empty() && candidates[best12].sign != candidates[best21].sign)
  {
    // Both directions must agree on the orientation: keep the one of lower total score.
    auto best_with = [&](int sign, bool forward) {
      std::size_t b = candidates.size();
      for(std::size_t i = 0; i < candidates.size(); ++i)
        if(candidates[i].sign == sign &&
           (b == candidates.size() ||
            (forward ? candidates[i].score12 < candidates[b].score12 : candidates[i].score21 < candidates[b].score21)))
          b = i;
      return b;
    };
    const std::size_t p12 = best_with(1, true), p21 = best_with(1, false);
    const std::size_t q12 = best_with(-1, true), q21 = best_with(-1, false);
    if(candidates[p12].score12 + candidates[p21].score21 <= candidates[q12].score12 + candidates[q21].score21)
    {
      best12 = p12;
      best21 = p21;
    }
    else
    {
      best12 = q12;
      best21 = q21;
    }
  }
  if(s.verbose)
    for(std::size_t i = 0; i < candidates.size(); ++i)
      std::cerr << "  candidate " << i << ": k0 " << candidates[i].config.basis_size << ", w_o "
                << candidates[i].config.orientation_weight << ", w_c " << candidates[i].config.commutativity_weight
                << ", sign " << candidates[i].sign
                << (candidates[i].inverse_of >= 0 ? " (inverse maps)" : "") << ": scores " << candidates[i].score12 << " "
                << candidates[i].score21 << "\n";
  const int sign = candidates[best12].sign;
  result.orientation_sign = orientation_sign * sign;
  result.initial_basis_size = candidates[best12].config.basis_size;
  Eigen::MatrixXd C12 = candidates[best12].C12, C21 = candidates[best21].C21;
  result.selection_score = 0.5 * (candidates[best12].score12 + candidates[best21].score21);
  if(sign < 0)
  {
    D2.middleCols(signed_begin, signed_count) *= -1.0;
    if(s.zoomout_descriptor_weight > 0) features2 = make_features(D2);
  }
  result.functional_map_seconds = seconds_since(fit_start);
  if(s.verbose)
    std::cerr << "automatic_initial_maps: " << candidates.size() << " candidates in "
              << result.functional_map_seconds << " s; chosen " << best12 << " and " << best21
              << " (scores " << candidates[best12].score12 << ", " << candidates[best21].score21
              << "), orientation " << result.orientation_sign << "\n";

  // ZoomOut from the selection size to the pass size (grow_initial_maps() goes on to the final
  // size once the pass is chosen).
  const Clock::time_point zoom_start = Clock::now();
  const Zoomout_settings zs = initialization_zoomout_settings(s, s.zoomout_step, pass_final_size(s));
  std::vector<int> t12, t21;
  zoomout_pair<ConcurrencyTag>(basis1, mass1, basis2, mass2, s, zs, rows1, rows2, landmarks, C12, C21, t12, t21,
                               features12, features21);
  result.zoomout_seconds = seconds_since(zoom_start);
  result.final_basis_size = zs.final_size;
  set_initial_maps(m1, m2, t12, t21, C12, C21, map_12, map_21, result);
  result.total_seconds = seconds_since(start);
  if(s.verbose)
    std::cerr << "automatic_initial_maps: ZoomOut to " << zs.final_size << " in " << result.zoomout_seconds
              << " s, cycle error " << result.cycle_error << ", fixed " << result.cycle_fixed_fraction
              << ", orientation agreement " << result.orientation_agreement << "\n";
  return result;
}

/// The last step of automatic_initial_maps(): the maps that were kept (computed by a pass with a
/// ZoomOut to pass_final_size()) grow on to zoomout_final_size by the same ZoomOut, started from
/// the pass's final functional maps, with the user's landmarks (not those of a repair pass: the
/// maps already follow them) and without descriptor features (zoomout_descriptor_weight, 0 by
/// default, applies to the passes only). Nothing happens when the maps are already of the final
/// size. The torn fraction and the sample distortion of the result stay those of the kept pass.
template <typename ConcurrencyTag>
void grow_initial_maps(const Initialization_shape& shape1, const Initialization_shape& shape2,
                       const Initialization_settings& s, const Initialization_pass_cache& cache,
                       std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                       Automatic_initialization_result& result)
{
  const int kf = s.zoomout_final_size, k = int(result.functional_map_12.rows());
  if(k == 0 || k >= kf || result.functional_map_21.rows() != k) return;
  const auto start = std::chrono::steady_clock::now();
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  const Eigen::MatrixXd basis1 = unit_area_basis(*shape1.spectrum, kf), basis2 = unit_area_basis(*shape2.spectrum, kf);
  const Eigen::VectorXd mass1 = unit_area_mass(*shape1.spectrum), mass2 = unit_area_mass(*shape2.spectrum);
  std::vector<std::pair<int, int> > landmarks;
  for(const auto& l : s.landmarks) landmarks.emplace_back(int(l.first), int(l.second));
  Eigen::MatrixXd C12 = result.functional_map_12, C21 = result.functional_map_21;
  std::vector<int> t12, t21;
  zoomout_pair<ConcurrencyTag>(basis1, mass1, basis2, mass2, s, initialization_zoomout_settings(s, s.zoomout_growth_step, kf),
                               cache.first.samples.rows, cache.second.samples.rows, landmarks, C12, C21, t12, t21);
  set_initial_maps(m1, m2, t12, t21, C12, C21, map_12, map_21, result);
  result.final_basis_size = kf;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.zoomout_seconds += seconds;
  if(s.verbose)
    std::cerr << "automatic_initial_maps: ZoomOut from " << k << " to " << kf << " in " << seconds
              << " s, cycle error " << result.cycle_error << ", fixed " << result.cycle_fixed_fraction << "\n";
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
      repair.landmarks.emplace_back(std::size_t(p.first), std::size_t(p.second));
    for(const auto& p : core_correspondences(m2, tears.back, map_21, s.tear_repair_landmarks))
      repair.landmarks.emplace_back(std::size_t(p.second), std::size_t(p.first));
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
        repair.landmarks.emplace_back(std::size_t(v), map_12[std::size_t(v)]);
      }
      else
      {
        const int w = samples2[std::size_t(core[i])];
        repair.landmarks.emplace_back(map_21[std::size_t(w)], std::size_t(w));
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

/// The core of automatic_initial_maps() on precomputed shapes (see single_pass_initial_maps()):
/// one pass, then the tear repair (repair_torn_maps()) and the distortion repair
/// (repair_distorted_maps()), then the growth to the final size (grow_initial_maps()) unless
/// `grow` is false (the maps then stay at the pass size, for a comparison before the growth).
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
  const Automatic_initialization_result first =
      single_pass_initial_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, &cache);
  Automatic_initialization_result result =
      repair_torn_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, first, &cache);
  if(s.distortion_repair_passes > 0)
    result = repair_distorted_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, result, &cache);
  if(grow) grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, result);
  result.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

/// The comparison of repair_given_maps() (`compare_with_automatic_maps`): the automatic maps of
/// the pair (automatic_initial_maps() on the same shapes, sharing `cache`) replace `map_12` and
/// `map_21` when their sample maps distort geodesic distances less (pair_distortion(), mean of both
/// directions; ties keep the given maps). Maps computed elsewhere can be wrong as a whole, core
/// included, which no repair from their own cores undoes (the WKS maps of TOSCA_r michael13 -
/// michael19: error 0.34, orientation kept on 78% of the triangles). Given maps whose sample
/// distortion is at most automatic_maps_comparison_threshold are kept without computing the
/// automatic maps. Both pairs are compared at the pass size (zoomout_pass_size: the given maps
/// after a kept repair pass, the automatic maps before their growth), and only the kept pair grows
/// to zoomout_final_size (grow_initial_maps(); given maps that no repair pass recomputed have no
/// functional maps and stay as they are). Returns `given`, or the automatic maps' result, with the
/// comparison's fields and the times of both.
template <typename ConcurrencyTag>
Automatic_initialization_result compare_given_with_automatic_maps(const Initialization_shape& shape1,
                                                                  const Initialization_shape& shape2,
                                                                  const Initialization_settings& s,
                                                                  Initialization_pass_cache& cache,
                                                                  std::vector<std::size_t>& map_12,
                                                                  std::vector<std::size_t>& map_21,
                                                                  const Automatic_initialization_result& given)
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
  std::vector<std::size_t> a12, a21;
  Automatic_initialization_result automatic =
      automatic_initial_maps<ConcurrencyTag>(shape1, shape2, s, a12, a21, &cache, false);
  const double automatic_distortion = pair_distortion<ConcurrencyTag>(shape1, shape2, s, cache, a12, a21);
  const bool keep_automatic = automatic_distortion < given_distortion;
  if(s.verbose)
    std::cerr << "repair_torn_maps: sample distortion of the given maps " << given_distortion
              << ", of the automatic maps " << automatic_distortion << ": "
              << (keep_automatic ? "the automatic maps are kept" : "the given maps are kept") << "\n";
  Automatic_initialization_result r = keep_automatic ? automatic : given;
  if(keep_automatic)
  {
    map_12.swap(a12);
    map_21.swap(a21);
    r.spectra_seconds = given.spectra_seconds;
  }
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
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  const std::vector<int> t12(map_12.begin(), map_12.end()), t21(map_21.begin(), map_21.end());
  Automatic_initialization_result given;
  given.orientation_agreement = 0.5 * (orientation_agreement(m1, m2, vertex_normals(m2), t12) +
                                       orientation_agreement(m2, m1, vertex_normals(m1), t21));
  given.orientation_sign = given.orientation_agreement >= 0.5 ? 1 : -1;
  Initialization_pass_cache cache;
  Automatic_initialization_result r = given;
  if(repair)
  {
    r = repair_torn_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, given, &cache);
    if(s.distortion_repair_passes > 0)
      r = repair_distorted_maps<ConcurrencyTag>(shape1, shape2, s, map_12, map_21, r, &cache);
  }
  // Maps of a kept repair pass grow to the final size (the given maps have no functional maps and
  // stay as they are); with the comparison, only the kept maps grow.
  if(s.compare_with_automatic_maps)
    r = compare_given_with_automatic_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r);
  else
    grow_initial_maps<ConcurrencyTag>(shape1, shape2, s, cache, map_12, map_21, r);
  r.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

/// The spectrum and the descriptors of one flat mesh for automatic_initial_maps(): `given` is
/// reused when it has at least the eigenpairs the initialisation needs on the intrinsic Delaunay
/// triangulation (exactly as many: the maps equal those computed from the mesh alone; more: its
/// leading eigenpairs, equal to a new solve's up to the solver's tolerance), else computed.
struct Initialization_mesh_data
{
  std::shared_ptr<const Laplace_beltrami_spectrum> own_spectrum;
  const Laplace_beltrami_spectrum* spectrum = nullptr;
  std::shared_ptr<const Eigen::MatrixXd> descriptors;
  bool reused = false;  ///< `given` served
  bool cached = false;  ///< taken from the shape's cache
};

/// What initialization_descriptors() and the initialisation's spectrum depend on: two settings
/// with the same key give the same spectrum and descriptors on a shape.
inline std::vector<double> initialization_cache_key(const Initialization_settings& s)
{
  const Initialization_descriptor_layout l = initialization_descriptor_layout(s);
  std::vector<double> key{double(initialization_number_of_eigenpairs(s)), double(pass_final_size(s)),
                          double(l.wks), double(l.hks), s.wks_variance, double(s.signed_descriptor_smoothing)};
  for(const auto& p : l.signed_pairs)
  {
    key.push_back(p.first);
    key.push_back(p.second);
  }
  return key;
}

/// Fills `out` for mesh `m`. With a `cache` (a prepared shape's), the spectrum and descriptors
/// kept there for the same settings are taken, else computed and kept.
inline void prepare_initialization_mesh(const Indexed_mesh& m, const Laplace_beltrami_spectrum* given,
                                        const Initialization_settings& s, const char* name,
                                        Initialization_mesh_data& out, Shape_initialization_cache* cache = nullptr)
{
  const int k = initialization_number_of_eigenpairs(s);
  // Checked before the eigensolver, which would fail with a less helpful message.
  if(m.number_of_vertices() <= s.zoomout_final_size || m.number_of_vertices() <= k)
    throw Invalid_mesh_error(std::string("automatic_initial_maps: ") + name + " has " +
                             std::to_string(m.number_of_vertices()) + " vertices, too few for a basis of " +
                             std::to_string(k) + " eigenfunctions (reduce zoomout_final_size)");
  out.reused = given && given->number_of_eigenpairs() >= k && given->uses_intrinsic_delaunay();
  std::unique_lock<std::mutex> lock;
  std::vector<double> key;
  if(cache)
  {
    lock = std::unique_lock<std::mutex>(cache->mutex);  // held while computing: computed once
    key = initialization_cache_key(s);
    if(cache->descriptors && cache->key == key)
    {
      out.own_spectrum = cache->spectrum;
      out.spectrum = out.own_spectrum ? out.own_spectrum.get() : given;
      out.descriptors = cache->descriptors;
      out.cached = true;
      return;
    }
  }
  if(out.reused && given->number_of_eigenpairs() == k)
    out.spectrum = given;
  else
  {
    out.own_spectrum = out.reused ? std::make_shared<const Laplace_beltrami_spectrum>(*given, k)
                                  : std::make_shared<const Laplace_beltrami_spectrum>(
                                        m, parameters::number_of_eigenpairs(k));
    out.spectrum = out.own_spectrum.get();
  }
  out.descriptors =
      std::make_shared<const Eigen::MatrixXd>(initialization_descriptors<CGAL::Sequential_tag>(m, *out.spectrum, s));
  if(cache)
  {
    cache->key = std::move(key);
    cache->spectrum = out.own_spectrum;
    cache->descriptors = out.descriptors;
  }
}

/// A flat mesh for on_prepared_meshes(): with a prepared shape's spectrum (to reuse when it
/// serves) and cache, or neither.
struct Initialization_mesh_source
{
  const Indexed_mesh* mesh = nullptr;
  const Laplace_beltrami_spectrum* spectrum = nullptr;
  Shape_initialization_cache* cache = nullptr;
};

inline Initialization_mesh_source initialization_mesh_source(const Shape_data& d)
{
  return {&d.mesh, &d.largest_spectrum(), d.initialization.get()};
}

/// Prepares both meshes for the initialisation (concurrently) and runs `f(shape1, shape2)`; the
/// result gets the preparation time and the total time since `start`.
template <typename ConcurrencyTag, typename F>
Automatic_initialization_result on_prepared_meshes(const Initialization_mesh_source& m1,
                                                   const Initialization_mesh_source& m2,
                                                   const Initialization_settings& s,
                                                   std::chrono::steady_clock::time_point start, const F& f)
{
  Initialization_mesh_data d1, d2;
  invoke_both<ConcurrencyTag>(
      [&] { prepare_initialization_mesh(*m1.mesh, m1.spectrum, s, "mesh 1", d1, m1.cache); },
      [&] { prepare_initialization_mesh(*m2.mesh, m2.spectrum, s, "mesh 2", d2, m2.cache); });
  const double prepare_seconds = seconds_since(start);
  const Initialization_shape a{m1.mesh, d1.spectrum, d1.descriptors.get()},
      b{m2.mesh, d2.spectrum, d2.descriptors.get()};
  Automatic_initialization_result r = f(a, b);
  r.spectra_seconds = prepare_seconds;
  r.reused_spectra = int(d1.reused) + int(d2.reused);
  r.reused_descriptors = int(d1.cached) + int(d2.cached);
  r.total_seconds = seconds_since(start);
  return r;
}

/// Both public overloads of automatic_initial_maps(): prepares the two flat meshes (in parallel
/// with Parallel_tag) and runs the core; the times count from `start`.
template <typename ConcurrencyTag>
Automatic_initialization_result automatic_initial_maps_of_meshes(const Initialization_mesh_source& m1,
                                                                 const Initialization_mesh_source& m2,
                                                                 const Initialization_settings& s,
                                                                 std::vector<std::size_t>& map_12,
                                                                 std::vector<std::size_t>& map_21,
                                                                 std::chrono::steady_clock::time_point start)
{
  return on_prepared_meshes<ConcurrencyTag>(m1, m2, s, start,
                                            [&](const Initialization_shape& a, const Initialization_shape& b) {
                                              return automatic_initial_maps<ConcurrencyTag>(a, b, s, map_12, map_21);
                                            });
}

/// A connected indexed copy of a mesh for automatic_initial_maps() and repair_torn_maps().
template <typename TriangleMesh, typename NamedParameters>
Indexed_mesh initialization_mesh(const TriangleMesh& tm, const NamedParameters& np, const char* name)
{
  Mesh_requirements req;
  req.allow_several_components = false;
  return make_indexed_mesh(tm, np, req, name);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes initial point-to-point maps between two meshes in both directions, automatically.
///
/// Pipeline: the Laplace-Beltrami spectra and WKS descriptors of both meshes; functional maps
/// \f$ C_{12} \f$ and \f$ C_{21} \f$ of size `spectral_basis_size`, each minimising the energy of
/// fit_functional_map() (descriptor preservation, Laplacian and descriptor commutativity, and the
/// orientation-preserving term of Ren et al. 2018, which rules out left/right mirror maps); then a
/// coupled ZoomOut (Melzi et al. 2019) that grows both maps to `zoomout_pass_size`, each step
/// matching every vertex to its nearest neighbour in the joint embedding
/// \f$ [\Phi_1 C_{12}, \Phi_1] \f$ vs. \f$ [\Phi_2, \Phi_2 C_{21}] \f$ (which favours inverse
/// pairs of maps) and refitting. Then the tear repair: maps that swap two parts of a
/// symmetric body (limbs, feet) tear where a swapped part meets the rest; when the regions cut off
/// by the tears exceed 1% of a mesh, the maps are computed again with landmarks sampled in the
/// largest region of each map (see repair_torn_maps()), and kept when they are less torn and at
/// most 5% more distorted (`tear_repair_distortion_tolerance`). Optionally
/// (`number_of_distortion_repair_passes`) the distortion repair: maps that distort the geodesic
/// distances of farthest-point samples by more than 0.035 on average are computed again with
/// landmarks in their isometric core, and kept when they distort at least 20% less. Finally the
/// kept maps grow by the same coupled ZoomOut to `zoomout_final_size` (grow_initial_maps()).
///
/// The meshes must be oriented alike (both outward or both inward); for closed meshes of opposite
/// orientations (signed volumes of opposite signs) the orientation term is reversed
/// automatically. With landmarks, both orientations are fitted and the one of lower total
/// selection score is kept, so landmarks may select a mirror map.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (TBB: the two spectra
///   and the nearest-neighbour searches in parallel)
/// \tparam TriangleMesh1 a model of `FaceListGraph`
/// \tparam TriangleMesh2 a model of `FaceListGraph`
/// \tparam NamedParameters a sequence of named parameters
/// \param tm1 the first mesh (connected)
/// \param tm2 the second mesh (connected)
/// \param map_12 output: `map_12[i]` is the index of the vertex of `tm2` matched to vertex i of
///   `tm1` (indices of the vertex index maps)
/// \param map_21 output: the same from `tm2` to `tm1`
/// \param np optional named parameters among:
///   - `spectral_basis_size`: \f$ k_0 \f$, the size of the fitted functional maps; type `int`.
///     By default six fits are tried ((k_0, w_o, w_c) = (20, 0.03, 0.3), (15, 0.03, 0.3), (20,
///     0.1, 1), (30, 0.03, 0.3), (40, 0.1, 1), (60, 0.1, 1); those larger than `zoomout_final_size`
///     are skipped), together with the inverses of the fitted maps, and in each direction the one
///     whose map after a short ZoomOut distorts geodesic distances least (between 100
///     farthest-point samples) is kept; giving `spectral_basis_size`, `orientation_weight` or
///     `commutativity_weight` fits a single configuration, the values not given taken from the
///     first one.
///   - `zoomout_final_size`: \f$ k_f \f$, the basis size after ZoomOut; type `int`; default 200.
///   - `zoomout_pass_size`: the basis size at which every pass (the first one and each repair pass)
///     ends its ZoomOut; the tears, the distortions and the choice between passes are measured
///     there, and the kept maps then grow to \f$ k_f \f$; the WKS and HKS descriptors of the
///     initialisation use this many eigenpairs (with `number_of_eigenpairs` not given); type
///     `int`; default 120.
///   - `zoomout_step`: the basis growth per ZoomOut iteration; type `int`; default 5.
///   - `number_of_eigenpairs`: eigenpairs computed, at least \f$ k_f \f$; type `int`; default
///     \f$ k_f \f$.
///   - `orientation_weight`: \f$ w_o \f$; type `double` (0 disables the term).
///   - `commutativity_weight`: \f$ w_c \f$, descriptor commutativity; type `double`.
///   - `wks_weight`, `hks_weight`: weights of the WKS and HKS descriptor columns; type `double`;
///     defaults 1 and 0.
///   - `number_of_wks_energies`, `wks_variance`, `number_of_hks_scales`: the descriptors (defaults
///     100, 7, 16).
///   - `landmarks`: known correspondences, a range of pairs (vertex index in `tm1`, vertex index in
///     `tm2`) (e.g. `std::vector<std::pair<std::size_t, std::size_t>>`); default none.
///   - `number_of_repair_passes`: tear repair passes at most; type `int`; default 2 (0: no
///     repair).
///   - `tear_threshold`: a source edge is torn when its images are at least this far apart,
///     relative to the square root of the target's area (and at least four mean edge lengths);
///     type `double`; default 0.06.
///   - `tear_repair_distortion_tolerance`: a tear repair pass is kept only when it is less torn
///     and its maps distort the geodesic distances of farthest-point samples at most this much
///     more (relatively) than the maps it replaces; type `double`; default 0.05 (negative: no
///     distortion check, the less torn pass is kept).
///   - `number_of_distortion_repair_passes`: distortion repair passes at most (maps continuous but
///     wrong on a large part, e.g. half-body flips; see repair_distorted_maps()); type `int`;
///     default 0 (each pass costs about as much as the first one).
///   - `compare_with_automatic_maps`: repair_torn_maps() only (ignored here): whether the repaired
///     given maps compete with the automatic maps; type `bool`; default false.
///   - `automatic_maps_comparison_threshold`: repair_torn_maps() with the comparison and
///     compare_with_automatic_maps() only (ignored here): the automatic maps are computed and
///     compared only when the given maps' sample distortion is above it; type `double`; default
///     0.035 (0: always).
///   - `verbose`: print progress to `std::cerr`; type `bool`; default false.
///   - `vertex_point_map`, `vertex_index_map`: for both meshes (use the same types); defaults the
///     meshes' own.
/// \returns timings and diagnostics.
/// \pre both meshes are connected triangle meshes with more than \f$ k_f \f$ vertices (else
///   Invalid_mesh_error); parameters in range (else Invalid_parameter_error).
/// \throws Numerical_error if an eigensolver fails.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result automatic_initial_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const internal::Initialization_settings s = internal::initialization_settings(np);
  internal::check_initialization_settings(s);
  const internal::Indexed_mesh m1 = internal::initialization_mesh(tm1, np, "mesh 1");
  const internal::Indexed_mesh m2 = internal::initialization_mesh(tm2, np, "mesh 2");
  return internal::automatic_initial_maps_of_meshes<ConcurrencyTag>({&m1, nullptr, nullptr}, {&m2, nullptr, nullptr}, s,
                                                                    map_12, map_21, start);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// automatic_initial_maps() on two prepared shapes, to be refined with the same shapes. The
/// shapes' flat meshes are reused, and their spectra too when they hold at least the eigenpairs
/// the initialisation needs (200 by default) on the intrinsic Delaunay triangulation: either
/// their own spectrum (prepared with `number_of_eigenpairs(200)`), or a larger
/// `precomputed_spectrum` that they were given (one eigensolve per shape serves both: compute
/// 200 eigenpairs, give them to a shape that uses 100); otherwise the spectrum is computed
/// (`reused_spectra` of the result counts the reused ones). Each shape keeps what the
/// initialisation computed for it (its descriptors, and the spectrum when its own did not serve):
/// later calls on the shape with the same descriptor settings (eigenpairs, WKS, HKS and signed
/// descriptor settings, pass size) take them instead of computing them again
/// (`reused_descriptors` counts those shapes), also from repair_torn_maps() and
/// compare_with_automatic_maps() on shapes. One entry per shape (about 5 MB of descriptors for
/// 5000 vertices, plus 8 MB when the spectrum is kept); concurrent calls on one shape compute it
/// once. With a spectrum of exactly the needed size the maps are exactly those of the mesh-based
/// overload with the same named parameters (`np`: the initialisation's parameters, as there);
/// leading eigenpairs of a larger one equal a new solve's up to the eigensolver's tolerance. The
/// maps can be passed to refine_coupled_maps() with the same shapes.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result automatic_initial_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                       const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const internal::Initialization_settings s = internal::initialization_settings(np);
  internal::check_initialization_settings(s);
  return internal::automatic_initial_maps_of_meshes<ConcurrencyTag>(internal::initialization_mesh_source(shape_1.data()),
                                                                    internal::initialization_mesh_source(shape_2.data()),
                                                                    s, map_12, map_21, start);
}

namespace internal {

/// The settings of the public functions on given maps: repair_torn_maps() and, with `compare`
/// (which overrides the named parameter), compare_with_automatic_maps(); checked.
template <typename NamedParameters>
Initialization_settings given_maps_settings(const NamedParameters& np, bool compare)
{
  Initialization_settings s = initialization_settings(np);
  if(compare) s.compare_with_automatic_maps = true;
  check_initialization_settings(s);
  return s;
}

/// The public functions on given maps (`repair`: repair_torn_maps(), else
/// compare_with_automatic_maps()), on flat meshes or prepared shapes; the times count from `start`.
template <typename ConcurrencyTag>
Automatic_initialization_result repair_given_maps_of_sources(const Initialization_mesh_source& m1,
                                                             const Initialization_mesh_source& m2,
                                                             const Initialization_settings& s,
                                                             std::vector<std::size_t>& map_12,
                                                             std::vector<std::size_t>& map_21, bool repair,
                                                             std::chrono::steady_clock::time_point start)
{
  const std::size_t n1 = std::size_t(m1.mesh->number_of_vertices()), n2 = std::size_t(m2.mesh->number_of_vertices());
  check_vertex_map(map_12, n1, n2, "map 1->2");
  check_vertex_map(map_21, n2, n1, "map 2->1");
  return on_prepared_meshes<ConcurrencyTag>(m1, m2, s, start,
                                            [&](const Initialization_shape& a, const Initialization_shape& b) {
                                              return repair_given_maps<ConcurrencyTag>(a, b, s, map_12, map_21,
                                                                                       repair);
                                            });
}

template <typename ConcurrencyTag, typename TriangleMesh1, typename TriangleMesh2, typename NamedParameters>
Automatic_initialization_result repair_given_maps_of_meshes(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np, bool repair, bool compare)
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const Initialization_settings s = given_maps_settings(np, compare);
  const Indexed_mesh m1 = initialization_mesh(tm1, np, "mesh 1");
  const Indexed_mesh m2 = initialization_mesh(tm2, np, "mesh 2");
  return repair_given_maps_of_sources<ConcurrencyTag>({&m1, nullptr, nullptr}, {&m2, nullptr, nullptr}, s, map_12,
                                                      map_21, repair, start);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Repairs maps that swap parts of the shapes (limbs, feet): the tear repair of
/// automatic_initial_maps() applied to maps computed elsewhere. Each map's source is cut along its
/// tears (edges whose endpoints land at least `tear_threshold` sqrt(area) apart); when the regions
/// cut off from the largest one (the core) exceed `tear_min_fraction` of a mesh, both maps are
/// recomputed by the automatic initialisation with farthest-point samples of the cores (and
/// their images) as landmarks, in the orientation of the given maps, and kept when they are less
/// torn and at most `tear_repair_distortion_tolerance` (5%) more distorted. Maps without tears
/// are returned unchanged. With `number_of_distortion_repair_passes`, the distortion repair
/// follows (see repair_distorted_maps(): maps whose sample distortion is above 0.035 are
/// recomputed from landmarks in their isometric core, and kept when at least 20% less distorted).
/// With `compare_with_automatic_maps(true)` the (repaired) maps then compete with the automatic
/// maps of the pair (automatic_initial_maps(), about the time of one more initialisation): the
/// pair of maps whose farthest-point samples' geodesic distances are less distorted is returned,
/// unless the repaired maps distort them at most `automatic_maps_comparison_threshold` (default
/// 0.035), in which case they are kept without computing the automatic maps. This catches given
/// maps that are wrong as a whole, which their own cores cannot repair.
///
/// \param map_12, map_21 input and output: `map_12[i]` is the vertex of `tm2` matched to vertex i of
///   `tm1` (indices of the vertex index maps), `map_21` the other way round
/// \param np the named parameters of automatic_initial_maps(); `landmarks` are kept in every pass
/// \returns `repair_passes` (0: the maps were kept), the torn fractions before and after,
///   `distortion_repair_passes` and the sample distortions before and after, timings; with
///   `compare_with_automatic_maps`, `automatic_maps_kept` and both distortions compared (when the
///   automatic maps are kept, the other fields describe them, see Automatic_initialization_result)
/// \throws Invalid_map_error for maps of the wrong size or with entries out of range, and the
///   exceptions of automatic_initial_maps()
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result repair_torn_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                 std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                                                 const NamedParameters& np = parameters::default_values())
{
  return internal::repair_given_maps_of_meshes<ConcurrencyTag>(tm1, tm2, map_12, map_21, np, true, false);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// repair_torn_maps() on two prepared shapes (maps indexed as the shapes' vertices): the shapes'
/// flat meshes, spectra and kept initialisation descriptors are used as by
/// automatic_initial_maps() on shapes, with the same maps as the overload on meshes when the
/// shapes' spectra are of the initialisation's size or not used.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result repair_torn_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                 const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                 std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                                                 const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  return internal::repair_given_maps_of_sources<ConcurrencyTag>(
      internal::initialization_mesh_source(shape_1.data()), internal::initialization_mesh_source(shape_2.data()),
      internal::given_maps_settings(np, false), map_12, map_21, true, start);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Keeps maps computed elsewhere, or replaces them by the automatic maps of the pair
/// (automatic_initial_maps() with the same named parameters), whichever distort the geodesic
/// distances between 100 farthest-point samples of each mesh less (mean of both directions; ties
/// keep the given maps). The given maps are not repaired (repair_torn_maps() with
/// `compare_with_automatic_maps(true)` repairs them first). A safety net for maps that may be
/// wrong as a whole (symmetry flips, a body turned by 180 degrees), which no local refinement
/// undoes; it costs one automatic initialisation, except on given maps whose sample distortion is
/// at most `automatic_maps_comparison_threshold` (default 0.035; 0: always compare), which are kept
/// without computing the automatic maps (`automatic_maps_computed` false). Sample distortion is not accuracy: on a pair
/// whose deformation stretches the surface, exact maps can distort more than slightly less
/// accurate automatic maps, which then replace them.
///
/// \param map_12, map_21 input and output, as for repair_torn_maps()
/// \param np the named parameters of automatic_initial_maps()
/// \returns the result of the automatic maps when they replaced the given ones, else a result
///   describing the given maps; in both, `compared_with_automatic_maps`, `automatic_maps_computed`,
///   `automatic_maps_kept`, `given_maps_distortion`, `automatic_maps_distortion` and the times of
///   the whole comparison
/// \throws Invalid_map_error for maps of the wrong size or with entries out of range, and the
///   exceptions of automatic_initial_maps()
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result compare_with_automatic_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np = parameters::default_values())
{
  return internal::repair_given_maps_of_meshes<ConcurrencyTag>(tm1, tm2, map_12, map_21, np, false, true);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// compare_with_automatic_maps() on two prepared shapes (maps indexed as the shapes' vertices),
/// using their flat meshes, spectra and kept initialisation descriptors as automatic_initial_maps()
/// on shapes does.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result compare_with_automatic_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                            const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  return internal::repair_given_maps_of_sources<ConcurrencyTag>(
      internal::initialization_mesh_source(shape_1.data()), internal::initialization_mesh_source(shape_2.data()),
      internal::given_maps_settings(np, true), map_12, map_21, false, start);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H
