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
// reachable through `CGAL::Surface_mesh_correspondence::parameters`. Every setting of the registry
// (internal/settings_list.h, see Matching_settings) has its named parameter of the same name.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_PARAMETERS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Surface_mesh_correspondence/internal/settings_list.h>

#include <type_traits>
#include <utility>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// The named parameters that are not settings of the registry: inputs of the functions
/// (initial maps, landmarks, precomputed data) and parameters of the component functions
/// (the TRW-S solver, the spectrum, the geodesic distances): (tag type, tag value, function name).
/// The settings (internal/settings_list.h) get their named parameters from the registry.
#define CGAL_SMC_NAMED_PARAMETERS(X)                                                     \
  /* the matching pipeline */                                                            \
  X(matching_settings_t, matching_settings, matching_settings)                           \
  X(initial_maps_t, initial_maps, initial_maps_pair)                                     \
  X(landmarks_t, landmarks, landmarks)                                                   \
  /* TRW-S solver */                                                                     \
  X(relative_tolerance_t, relative_tolerance, relative_tolerance)                        \
  X(initial_labeling_t, initial_labeling, initial_labeling)                              \
  /* Laplace-Beltrami spectrum and descriptors */                                        \
  X(eigen_shift_t, eigen_shift, eigen_shift)                                             \
  X(precomputed_spectrum_t, precomputed_spectrum, precomputed_spectrum)                  \
  X(user_descriptor_map_t, user_descriptor_map, user_descriptor_map)                     \
  /* geodesic distances and sampling */                                                  \
  X(local_radius_t, local_radius, local_radius)                                          \
  X(seed_vertices_t, seed_vertices, seed_vertices)                                       \
  X(maximum_distance_t, maximum_distance, maximum_distance)                              \
  X(target_vertices_t, target_vertices, target_vertices)                                 \
  X(geodesic_method_t, geodesic_method, geodesic_method)

namespace internal_np {
#define CGAL_SMC_DECLARE_TAG(X, Y, Z) enum X { Y };
#define CGAL_SMC_DECLARE_SETTING_TAG(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC) enum NAME##_t { NAME };
CGAL_SMC_NAMED_PARAMETERS(CGAL_SMC_DECLARE_TAG)
CGAL_SMC_SETTINGS(CGAL_SMC_DECLARE_SETTING_TAG)
#undef CGAL_SMC_DECLARE_SETTING_TAG
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
#define CGAL_SMC_DECLARE_SETTING_FUNCTION(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC) \
  CGAL_SMC_DECLARE_FUNCTION(NAME##_t, NAME, NAME)
CGAL_SMC_SETTINGS(CGAL_SMC_DECLARE_SETTING_FUNCTION)
#undef CGAL_SMC_DECLARE_SETTING_FUNCTION
#undef CGAL_SMC_DECLARE_FUNCTION

/// The maps to start from (match_shapes()): `map_12` from the vertices of the first mesh to
/// those of the second, `map_21` the other way round (readable property maps, or
/// Vertex_index_map_vector for prepared shapes).
template <typename Map12, typename Map21>
CGAL::Named_function_parameters<std::pair<Map12, Map21>, internal_np::initial_maps_t>
initial_maps(const Map12& map_12, const Map21& map_21)
{
  return initial_maps_pair(std::make_pair(map_12, map_21));
}
template <typename Map12, typename Map21, typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<std::pair<Map12, Map21>, internal_np::initial_maps_t,
                                CGAL::Named_function_parameters<T, Tag, Base> >
initial_maps(const Map12& map_12, const Map21& map_21, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return initial_maps_pair(std::make_pair(map_12, map_21), np);
}

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
