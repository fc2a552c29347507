// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The inputs of the automatic initialisation: its settings (Initialization_settings, read from the
// named parameters and checked), the basis sizes and ZoomOut schedules derived from them, the
// column layout and weights of its descriptors, and the precomputed data of one shape.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_SETTINGS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_SETTINGS_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/zoomout.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// One configuration of the functional map fit tried by the initialisation.
typedef Functional_map_fit Fit_candidate;

/// Every setting of the automatic initialisation. Those of the registry (their defaults are the
/// registry's, see initialization_settings()) and the algorithm's fixed constants.
struct Initialization_settings
{
  // Basis sizes.
  /// The fit configurations tried (each in both directions); the best after a short ZoomOut is
  /// kept. Candidates larger than zoomout_final_size are skipped.
  std::vector<Fit_candidate> candidates = matching_defaults().initialization_fits;
  int selection_size = matching_defaults().fit_selection_basis_size;               ///< basis size at which candidates are compared
  /// How candidates are compared: by the geodesic distortion of their sample maps (true) or by
  /// the weighted descriptor distance between matched samples (false).
  bool select_by_distortion = true;
  /// Farthest-point samples whose pairwise geodesic distances measure the distortion.
  int distortion_samples = 100;
  int zoomout_final_size = matching_defaults().zoomout_final_size;          ///< k_final
  /// Basis size at which every pass (the first one and each repair pass) ends its ZoomOut: the
  /// tears, the distortions and the choice between passes are measured there, and the maps that
  /// are kept then grow on to zoomout_final_size (grow_initial_maps()).
  int zoomout_pass_size = matching_defaults().zoomout_pass_size;
  int zoomout_step = matching_defaults().zoomout_step;                  ///< ZoomOut basis growth per iteration
  /// ZoomOut basis growth per iteration from zoomout_pass_size to zoomout_final_size
  /// (grow_initial_maps()). Coarser than zoomout_step: the growth costs most at these sizes
  /// (TOSCA_r, every 8th pair: steps of 5, 10, 20 give 0.0260, 0.0263, 0.0266).
  int zoomout_growth_step = matching_defaults().zoomout_growth_step;
  int number_of_eigenpairs = matching_defaults().initialization_number_of_eigenpairs;          ///< eigenpairs computed (0: zoomout_final_size)
  // Descriptors.
  int number_of_wks_energies = matching_defaults().initialization_number_of_wks_energies;
  double wks_variance = matching_defaults().initialization_wks_variance;
  int number_of_hks_scales = matching_defaults().initialization_number_of_hks_scales;
  double wks_weight = matching_defaults().initialization_wks_weight;
  double hks_weight = matching_defaults().initialization_hks_weight;
  /// Weight of the orientation-sensitive descriptors <n, grad f x grad g> (0: none).
  double signed_descriptor_weight = matching_defaults().signed_descriptor_weight;
  /// They are smoothed by projection on this many eigenfunctions (0: not smoothed).
  int signed_descriptor_smoothing = matching_defaults().signed_descriptor_smoothing;
  /// Number of descriptors (evenly spread over the columns) that get multiplication and
  /// orientation operators.
  int number_of_operator_descriptors = matching_defaults().number_of_operator_descriptors;
  bool normalize_orientation_gradients = true;
  // Functional map energy (orientation and commutativity weights come from the candidates).
  Functional_map_weights weights;
  bool procrustes = matching_defaults().use_procrustes;                ///< replace each fitted map by the nearest orthogonal one
  // ZoomOut.
  bool coupled_zoomout = matching_defaults().use_coupled_zoomout;
  double zoomout_bijectivity_weight = matching_defaults().zoomout_bijectivity_weight;
  int zoomout_number_of_samples = matching_defaults().zoomout_number_of_samples;  ///< 0: all vertices in every iteration
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
  /// Weight of the geodesic distance fields of the anchor landmarks (divided by the square root of
  /// the mesh area) appended to the ZoomOut embeddings of a pass (0: none).
  double landmark_distance_weight = matching_defaults().landmark_distance_weight;
  /// Weight of the orientation-sensitive (signed) descriptors appended to the ZoomOut embeddings
  /// of a pass with anchor landmarks (0: none), unless zoomout_descriptor_weight sets the features
  /// of every pass. The distance fields of the anchors tell where a vertex lies along the body, not
  /// on which side of a limb: without these features ZoomOut cannot tell a limb from its mirror
  /// image about its axis.
  double landmark_orientation_weight = matching_defaults().landmark_orientation_weight;
  /// Weight of the chirality features of the anchor landmarks appended to the ZoomOut embeddings
  /// of a pass with two or more anchors (0: none; see landmark_chirality_fields()). The distance
  /// fields tell how far a vertex is from each anchor, not on which side of the body it lies: a
  /// torso turned front to back keeps them. The turn from the direction to one anchor to the
  /// direction to another, seen from the outside, changes sign there.
  double landmark_chirality_weight = matching_defaults().landmark_chirality_weight;
  /// The anchor landmarks, whose distance fields are ZoomOut features: the first
  /// min(anchor_landmarks, landmarks.size()) landmarks. All given landmarks by default; those
  /// added by add_landmark() are not anchors.
  std::size_t anchor_landmarks = std::numeric_limits<std::size_t>::max();
  /// Adds a landmark that is not an anchor (one of the core of a repaired map): the anchors stay
  /// those already given.
  void add_landmark(std::size_t vertex_1, std::size_t vertex_2)
  {
    anchor_landmarks = std::min(anchor_landmarks, landmarks.size());
    landmarks.emplace_back(vertex_1, vertex_2);
  }
  /// Adds an anchor landmark (an extremity of a hypothesis), after the anchors already given and
  /// before the landmarks that are not anchors.
  void add_anchor_landmark(std::size_t vertex_1, std::size_t vertex_2)
  {
    const std::size_t anchors = std::min(anchor_landmarks, landmarks.size());
    landmarks.insert(landmarks.begin() + std::ptrdiff_t(anchors), std::make_pair(vertex_1, vertex_2));
    anchor_landmarks = anchors + 1;
  }
  // Tear repair.
  /// Repair passes at most: after each set of maps whose tears cut off more than
  /// tear_min_fraction of a mesh, the maps are recomputed with landmarks sampled in the core (the
  /// largest region between the tears) of both maps, and kept when they are less torn.
  int tear_repair_passes = matching_defaults().number_of_repair_passes;
  /// A source edge is torn when its images are at least this far apart (relative to the square
  /// root of the target's area; at least four mean edge lengths).
  double tear_threshold = matching_defaults().tear_threshold;
  double tear_min_fraction = matching_defaults().tear_area_fraction;
  /// A tear repair pass is kept only when its maps also distort the geodesic distances of the
  /// distortion samples (pair_distortion()) at most this fraction more than the maps they replace
  /// (negative: no check). Landmarks from the core of a map torn over half a mesh can pull the
  /// repair into an untorn but mirrored map (TOSCA_r michael19 - michael8: 0.067 -> 0.30, its
  /// distortion +7%).
  double tear_repair_distortion_tolerance = matching_defaults().tear_repair_distortion_tolerance;
  /// Landmarks sampled in the core of each map by a repair pass.
  int tear_repair_landmarks = matching_defaults().number_of_tear_repair_landmarks;
  // Distortion repair.
  /// Distortion repair passes at most (0, the default: none; each pass costs about as much as the
  /// first one): after the tear repair, the maps are recomputed with
  /// landmarks from their isometric core (the largest set of samples whose pairwise geodesic
  /// distances the map preserves, see distortion_core()), with all the fit configurations of the
  /// first pass, and kept when they distort the sample distances less (distortion_repair_gain).
  int distortion_repair_passes = matching_defaults().number_of_distortion_repair_passes;
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
  // Extremity hypotheses.
  /// Passes from assignments of the extremities of both shapes, run when the sample distortion of
  /// the maps is above extremity_hypothesis_threshold (0: none; see try_extremity_hypotheses()).
  int extremity_hypotheses = matching_defaults().extremity_hypotheses;
  double extremity_hypothesis_threshold = matching_defaults().extremity_hypothesis_threshold;
  /// A hypothesis replaces the descriptor-based maps when its maps distort the samples at most
  /// this fraction more than they do (see try_extremity_hypotheses()).
  double extremity_hypothesis_tolerance = matching_defaults().extremity_hypothesis_tolerance;
  /// The extremities: local maxima of the mean geodesic distance to this many distortion samples
  /// within this radius (relative to the square root of the area), at most this many per shape.
  int extremity_sources = 32;
  double extremity_radius = 0.15;
  int maximum_extremities = 7;
  /// The SHOT support radius (relative to the square root of the area) of the descriptors by
  /// which the hypotheses are chosen (see try_extremity_hypotheses()).
  double shot_radius = matching_defaults().shot_radius;
  /// The hypothesis kept is the one of lowest SHOT disagreement plus this times its sample
  /// distortion (see try_extremity_hypotheses()).
  double extremity_hypothesis_distortion_weight = matching_defaults().extremity_hypothesis_distortion_weight;
  /// Only the hypotheses whose first pass ends at most this above the lowest criterion get their
  /// tear repair and compete (see try_extremity_hypotheses()).
  double extremity_hypothesis_repair_margin = matching_defaults().extremity_hypothesis_repair_margin;
  /// The weight of the WKS distance between matched extremities in the score of an assignment
  /// (extremity_assignments()): among assignments that keep the proportions alike, it prefers
  /// hands matched to hands rather than to feet, and a head to a head rather than to a jaw.
  double extremity_descriptor_weight = 0.5;
  /// An assignment may leave one extremity of the shape with fewer extremities unmatched, at this
  /// cost added to its score, when it still matches at least minimum_extremity_pairs (see
  /// extremity_assignments(); infinity: every extremity of that shape is matched).
  double unmatched_extremity_penalty = 0.05;
  int minimum_extremity_pairs = 5;
  /// Passes in all (the first one, tear repair and distortion repair): the distortion repair runs
  /// only while this allows.
  int maximum_passes = 3;
  /// The fit configurations of the repair passes (the landmarks constrain the fits, so fewer are
  /// needed); empty: those of the first pass.
  std::vector<Fit_candidate> repair_candidates{{20, 0.03, 0.3}, {40, 0.1, 1.0}};
  /// repair_given_maps() only: after the repairs, the given maps compete with the automatic maps
  /// of the pair (automatic_initial_maps() run on the same shapes); the pair of maps whose sample
  /// maps distort geodesic distances less is kept. Set by the callers (match_shapes() from the
  /// setting of the same name).
  bool compare_with_automatic_maps = false;
  /// ... only when the given maps' sample distortion is above this (0: always). Maps that preserve
  /// the sample distances well are kept without the cost of the automatic initialisation (on 77 of
  /// the 284 TOSCA_r pairs from the dataset's WKS maps, which then take about half the time).
  double automatic_maps_comparison_threshold = matching_defaults().automatic_maps_comparison_threshold;
  /// The automatic maps replace the given ones only when their sample distortion is at most this.
  /// On TOSCA_r (isometric) every automatic map that won the comparison distorted at most 0.071;
  /// on the non-isometric TOSCA_nonIso every automatic map distorted 0.13-0.23, and those that won
  /// were wholly wrong (errors 0.60-0.77 against 0.29-0.47 for the WKS maps they replaced).
  double automatic_maps_maximum_distortion = matching_defaults().automatic_maps_maximum_distortion;
  bool verbose = false;
  /// Called on the calling thread after each step of a pass (the fits, their scores, the ZoomOut)
  /// and after the growth to the final size: the progress of match_shapes(), whose stop request
  /// it throws.
  std::function<void()> step_done;
  void notify_step() const
  {
    if(step_done) step_done();
  }
};

/// The settings of the automatic initialisation in `m` (those of the registry that stage
/// initialization reads; compare_with_automatic_maps stays false).
inline Initialization_settings initialization_settings(const Matching_settings& m)
{
  Initialization_settings s;
  s.candidates = m.initialization_fits;
  s.selection_size = m.fit_selection_basis_size;
  s.zoomout_final_size = m.zoomout_final_size;
  s.zoomout_pass_size = m.zoomout_pass_size;
  s.zoomout_step = m.zoomout_step;
  s.zoomout_growth_step = m.zoomout_growth_step;
  s.zoomout_number_of_samples = m.zoomout_number_of_samples;
  s.coupled_zoomout = m.use_coupled_zoomout;
  s.zoomout_bijectivity_weight = m.zoomout_bijectivity_weight;
  s.procrustes = m.use_procrustes;
  s.number_of_eigenpairs = m.initialization_number_of_eigenpairs;
  s.wks_weight = m.initialization_wks_weight;
  s.hks_weight = m.initialization_hks_weight;
  s.number_of_wks_energies = m.initialization_number_of_wks_energies;
  s.wks_variance = m.initialization_wks_variance;
  s.number_of_hks_scales = m.initialization_number_of_hks_scales;
  s.signed_descriptor_weight = m.signed_descriptor_weight;
  s.signed_descriptor_smoothing = m.signed_descriptor_smoothing;
  s.number_of_operator_descriptors = m.number_of_operator_descriptors;
  s.tear_repair_passes = m.number_of_repair_passes;
  s.distortion_repair_passes = m.number_of_distortion_repair_passes;
  s.extremity_hypotheses = m.extremity_hypotheses;
  s.extremity_hypothesis_threshold = m.extremity_hypothesis_threshold;
  s.extremity_hypothesis_tolerance = m.extremity_hypothesis_tolerance;
  s.tear_threshold = m.tear_threshold;
  s.tear_min_fraction = m.tear_area_fraction;
  s.tear_repair_distortion_tolerance = m.tear_repair_distortion_tolerance;
  s.tear_repair_landmarks = m.number_of_tear_repair_landmarks;
  s.landmark_distance_weight = m.landmark_distance_weight;
  s.landmark_orientation_weight = m.landmark_orientation_weight;
  s.landmark_chirality_weight = m.landmark_chirality_weight;
  s.extremity_hypothesis_distortion_weight = m.extremity_hypothesis_distortion_weight;
  s.extremity_hypothesis_repair_margin = m.extremity_hypothesis_repair_margin;
  s.shot_radius = m.shot_radius;
  s.automatic_maps_comparison_threshold = m.automatic_maps_comparison_threshold;
  s.automatic_maps_maximum_distortion = m.automatic_maps_maximum_distortion;
  return s;
}

/// The landmarks of the named parameter `landmarks` (pairs of vertex indices), if given.
template <typename NamedParameters>
std::vector<std::pair<std::size_t, std::size_t> > landmarks_parameter(const NamedParameters& np)
{
  std::vector<std::pair<std::size_t, std::size_t> > out;
  const auto& landmarks = parameters::get_parameter(np, internal_np::landmarks);
  if constexpr(!std::is_same<typename std::decay<decltype(landmarks)>::type,
                             CGAL::internal_np::Param_not_found>::value)
  {
    for(const auto& l : landmarks)
      out.emplace_back(static_cast<std::size_t>(l.first), static_cast<std::size_t>(l.second));
  }
  return out;
}

/// Reads the named parameters of automatic_initial_maps() into settings: the registry's settings
/// (Matching_settings::from()), the landmarks and `verbose`.
template <typename NamedParameters>
Initialization_settings initialization_settings(const NamedParameters& np)
{
  Initialization_settings s = initialization_settings(Matching_settings::from(np));
  s.verbose = parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::verbose), s.verbose);
  s.landmarks = landmarks_parameter(np);
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
  auto finite_non_negative = [&](const char* name, double value) {
    if(!(value >= 0) || !std::isfinite(value))
      fail(std::string(name) + " = " + std::to_string(value) + " must be finite and non-negative");
  };
  if(s.candidates.empty()) fail("no functional map configuration to try");
  for(const Fit_candidate& c : s.candidates)
  {
    if(c.basis_size < 2)
      fail("initialization_fits: a basis size of " + std::to_string(c.basis_size) + " (at least 2)");
    if(!(c.orientation_weight >= 0) || !(c.commutativity_weight >= 0) || !std::isfinite(c.orientation_weight) ||
       !std::isfinite(c.commutativity_weight))
      fail("initialization_fits: the orientation and commutativity weights must be finite and non-negative");
  }
  if(largest_candidate_size(s) == 0)
  {
    int smallest = s.candidates.front().basis_size;
    for(const Fit_candidate& c : s.candidates) smallest = std::min(smallest, c.basis_size);
    fail("zoomout_final_size = " + std::to_string(s.zoomout_final_size) +
         " must be at least the smallest basis size of initialization_fits, " + std::to_string(smallest));
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
  if(s.extremity_hypotheses < 0) fail("extremity_hypotheses must be non-negative");
  finite_non_negative("extremity_hypothesis_threshold", s.extremity_hypothesis_threshold);
  finite_non_negative("extremity_hypothesis_tolerance", s.extremity_hypothesis_tolerance);
  if(s.extremity_sources < 1 || s.maximum_extremities < 0 || !(s.extremity_radius > 0))
    fail("extremity_sources and extremity_radius must be positive, maximum_extremities non-negative");
  finite_non_negative("extremity_descriptor_weight", s.extremity_descriptor_weight);
  if(!(s.unmatched_extremity_penalty >= 0)) fail("unmatched_extremity_penalty must be non-negative");
  if(s.minimum_extremity_pairs < 3) fail("minimum_extremity_pairs must be at least 3");
  finite_non_negative("automatic_maps_comparison_threshold", s.automatic_maps_comparison_threshold);
  finite_non_negative("automatic_maps_maximum_distortion", s.automatic_maps_maximum_distortion);
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
  finite_non_negative("landmark_distance_weight", s.landmark_distance_weight);
  finite_non_negative("landmark_orientation_weight", s.landmark_orientation_weight);
  finite_non_negative("landmark_chirality_weight", s.landmark_chirality_weight);
  finite_non_negative("extremity_hypothesis_distortion_weight", s.extremity_hypothesis_distortion_weight);
  if(!(s.extremity_hypothesis_repair_margin >= 0))
    fail("extremity_hypothesis_repair_margin = " + std::to_string(s.extremity_hypothesis_repair_margin) +
         " must be non-negative (infinity: every hypothesis is repaired)");
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

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_SETTINGS_H
