// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The package's own named parameters, on top of CGAL 5.5's `Named_function_parameters`.
//
// CGAL's list of parameter names is closed, but `Named_function_parameters<T, Tag, Base>` accepts
// any tag type, and `get_parameter()`, `choose_parameter()` and `is_default_parameter` work with
// any tag. Our tags are enums in `CGAL::Surface_mesh_correspondence::internal_np`; each has a free
// function in `CGAL::Surface_mesh_correspondence::parameters` with two overloads:
//
//   parameters::number_of_candidates(20)                       // a new pack
//   parameters::number_of_candidates(20, other_pack)           // pushed onto an existing pack
//
// CGAL's member chainers work after ours:
//   parameters::number_of_candidates(20).vertex_point_map(vpm)
// and `parameters::combine(a, b)` merges two packs (entries of `a` take precedence).
// Every CGAL parameter function (vertex_point_map, number_of_iterations, visitor, ...) is also
// reachable through `CGAL::Surface_mesh_correspondence::parameters`.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_PARAMETERS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <type_traits>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// The list of the package's named parameters: (tag type, tag value, function name).
/// Documentation of each parameter is with the functions that read it.
#define CGAL_SMC_NAMED_PARAMETERS(X)                                                     \
  /* TRW-S solver */                                                                     \
  X(relative_tolerance_t, relative_tolerance, relative_tolerance)                        \
  X(initial_labeling_t, initial_labeling, initial_labeling)                              \
  X(node_index_map_t, node_index_map, node_index_map)                                    \
  X(use_float_messages_t, use_float_messages, use_float_messages)                        \
  /* Laplace-Beltrami operator and spectrum */                                           \
  X(number_of_eigenpairs_t, number_of_eigenpairs, number_of_eigenpairs)                  \
  X(use_intrinsic_delaunay_t, use_intrinsic_delaunay, use_intrinsic_delaunay)            \
  X(eigen_shift_t, eigen_shift, eigen_shift)                                             \
  X(precomputed_spectrum_t, precomputed_spectrum, precomputed_spectrum)                  \
  /* descriptors */                                                                      \
  X(number_of_hks_scales_t, number_of_hks_scales, number_of_hks_scales)                  \
  X(number_of_wks_energies_t, number_of_wks_energies, number_of_wks_energies)            \
  X(wks_variance_t, wks_variance, wks_variance)                                          \
  X(shot_radius_t, shot_radius, shot_radius)                                             \
  X(hks_weight_t, hks_weight, hks_weight)                                                \
  X(wks_weight_t, wks_weight, wks_weight)                                                \
  X(shot_weight_t, shot_weight, shot_weight)                                             \
  X(user_descriptor_map_t, user_descriptor_map, user_descriptor_map)                     \
  X(user_descriptor_weight_t, user_descriptor_weight, user_descriptor_weight)            \
  /* geodesic distances and sampling */                                                  \
  X(distance_oracle_t, distance_oracle, distance_oracle)                                 \
  X(local_radius_t, local_radius, local_radius)                                          \
  X(number_of_rings_t, number_of_rings, number_of_rings)                                 \
  X(number_of_landmarks_t, number_of_landmarks, number_of_landmarks)                     \
  X(seed_vertices_t, seed_vertices, seed_vertices)                                       \
  X(maximum_distance_t, maximum_distance, maximum_distance)                              \
  X(target_vertices_t, target_vertices, target_vertices)                                 \
  X(geodesic_method_t, geodesic_method, geodesic_method)                                 \
  /* coupled refinement */                                                               \
  X(number_of_candidates_t, number_of_candidates, number_of_candidates)                  \
  X(ring_schedule_t, ring_schedule, ring_schedule)                                       \
  X(unary_weight_t, unary_weight, unary_weight)                                          \
  X(use_coupling_t, use_coupling, use_coupling)                                          \
  X(consistency_weight_t, consistency_weight, consistency_weight)                        \
  X(number_of_outer_iterations_t, number_of_outer_iterations, number_of_outer_iterations)\
  X(trws_number_of_iterations_t, trws_number_of_iterations, trws_number_of_iterations)   \
  X(trws_relative_tolerance_t, trws_relative_tolerance, trws_relative_tolerance)         \
  X(use_neighbor_matches_t, use_neighbor_matches, use_neighbor_matches)                  \
  X(pairwise_rings_t, pairwise_rings, pairwise_rings)                                    \
  X(stop_when_consistency_worsens_t, stop_when_consistency_worsens, stop_when_consistency_worsens) \
  X(keep_consistent_input_maps_t, keep_consistent_input_maps, keep_consistent_input_maps) \
  X(refinement_preset_t, refinement_preset, refinement_preset)                        \
  /* automatic initialisation */                                                         \
  X(spectral_basis_size_t, spectral_basis_size, spectral_basis_size)                     \
  X(zoomout_final_size_t, zoomout_final_size, zoomout_final_size)                        \
  X(zoomout_pass_size_t, zoomout_pass_size, zoomout_pass_size)                           \
  X(zoomout_step_t, zoomout_step, zoomout_step)                                          \
  X(zoomout_growth_step_t, zoomout_growth_step, zoomout_growth_step)                     \
  X(orientation_weight_t, orientation_weight, orientation_weight)                        \
  X(commutativity_weight_t, commutativity_weight, commutativity_weight)                  \
  X(landmarks_t, landmarks, landmarks)                                                   \
  X(number_of_repair_passes_t, number_of_repair_passes, number_of_repair_passes)         \
  X(tear_threshold_t, tear_threshold, tear_threshold)                                    \
  X(tear_repair_distortion_tolerance_t, tear_repair_distortion_tolerance,                \
    tear_repair_distortion_tolerance)                                                    \
  X(number_of_distortion_repair_passes_t, number_of_distortion_repair_passes,            \
    number_of_distortion_repair_passes)                                                  \
  X(compare_with_automatic_maps_t, compare_with_automatic_maps, compare_with_automatic_maps) \
  X(automatic_maps_comparison_threshold_t, automatic_maps_comparison_threshold,          \
    automatic_maps_comparison_threshold)

namespace internal_np {
#define CGAL_SMC_DECLARE_TAG(X, Y, Z) enum X { Y };
CGAL_SMC_NAMED_PARAMETERS(CGAL_SMC_DECLARE_TAG)
#undef CGAL_SMC_DECLARE_TAG
} // namespace internal_np

namespace parameters {

// Everything of CGAL::parameters (default_values(), vertex_point_map(), get_parameter(),
// choose_parameter(), is_default_parameter, ...) is reachable from here too.
using namespace CGAL::parameters;

#define CGAL_SMC_DECLARE_FUNCTION(X, Y, Z)                                                \
  template <typename K>                                                                   \
  CGAL::Named_function_parameters<K, internal_np::X> Z(const K& k)                        \
  {                                                                                       \
    return CGAL::Named_function_parameters<K, internal_np::X>(k);                         \
  }                                                                                       \
  template <typename K, typename T, typename Tag, typename Base>                          \
  CGAL::Named_function_parameters<K, internal_np::X,                                      \
                                  CGAL::Named_function_parameters<T, Tag, Base> >         \
  Z(const K& k, const CGAL::Named_function_parameters<T, Tag, Base>& np)                  \
  {                                                                                       \
    return CGAL::Named_function_parameters<K, internal_np::X,                             \
                                           CGAL::Named_function_parameters<T, Tag, Base> >\
        (k, np);                                                                          \
  }
CGAL_SMC_NAMED_PARAMETERS(CGAL_SMC_DECLARE_FUNCTION)
#undef CGAL_SMC_DECLARE_FUNCTION

namespace internal {

// The type of the pack made of the entries of `A` put on top of `B`.
template <typename A, typename B>
struct Combined;

// The empty pack (`default_values()`) contributes nothing.
template <typename B>
struct Combined<CGAL::Named_function_parameters<bool, CGAL::internal_np::all_default_t,
                                                CGAL::internal_np::No_property>, B>
{
  typedef B type;
  static type make(const CGAL::Named_function_parameters<bool, CGAL::internal_np::all_default_t,
                                                         CGAL::internal_np::No_property>&,
                   const B& b)
  {
    return b;
  }
};

template <typename T, typename Tag, typename B>
struct Combined<CGAL::Named_function_parameters<T, Tag, CGAL::internal_np::No_property>, B>
{
  typedef CGAL::Named_function_parameters<T, Tag, B> type;
  static type make(const CGAL::Named_function_parameters<T, Tag, CGAL::internal_np::No_property>& a,
                   const B& b)
  {
    return type(CGAL::internal_np::get_reference(a.v), b);
  }
};

template <typename T, typename Tag, typename Base, typename B>
struct Combined<CGAL::Named_function_parameters<T, Tag, Base>, B>
{
  typedef Combined<Base, B> Rest;
  typedef CGAL::Named_function_parameters<T, Tag, typename Rest::type> type;
  static type make(const CGAL::Named_function_parameters<T, Tag, Base>& a, const B& b)
  {
    return type(CGAL::internal_np::get_reference(a.v), Rest::make(static_cast<const Base&>(a), b));
  }
};

} // namespace internal

/// Merges two named-parameter packs into one. When both give the same parameter, the value in
/// `a` is used (it is found first).
template <typename T1, typename Tag1, typename Base1, typename T2, typename Tag2, typename Base2>
typename internal::Combined<CGAL::Named_function_parameters<T1, Tag1, Base1>,
                            CGAL::Named_function_parameters<T2, Tag2, Base2> >::type
combine(const CGAL::Named_function_parameters<T1, Tag1, Base1>& a,
        const CGAL::Named_function_parameters<T2, Tag2, Base2>& b)
{
  return internal::Combined<CGAL::Named_function_parameters<T1, Tag1, Base1>,
                            CGAL::Named_function_parameters<T2, Tag2, Base2> >::make(a, b);
}

} // namespace parameters
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_PARAMETERS_H
