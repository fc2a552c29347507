// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: the settings structs turned into the library's named-parameter packs, so that the
// tool goes through the public entry points (Correspondence_shape, refine_coupled_maps()).

#ifndef SMC_TOOLS_COMAP_PARAMETERS_H
#define SMC_TOOLS_COMAP_PARAMETERS_H

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include <functional>

namespace comap {

/// Named parameters of Correspondence_shape for `s`, with `eigenpairs` eigenpairs.
inline auto shape_parameters(const CGAL::Surface_mesh_correspondence::internal::Shape_settings& s, int eigenpairs)
{
  namespace p = CGAL::Surface_mesh_correspondence::parameters;
  const CGAL::Surface_mesh_correspondence::Descriptor_settings& d = s.descriptors;
  const auto oracle = p::distance_oracle(
      s.oracle, p::number_of_rings(s.local_radius_in_edge_lengths, p::number_of_landmarks(s.number_of_landmarks)));
  const auto descriptors = p::hks_weight(
      d.hks_weight,
      p::wks_weight(d.wks_weight,
                    p::shot_weight(d.shot_weight,
                                   p::number_of_hks_scales(
                                       d.number_of_hks_scales,
                                       p::number_of_wks_energies(d.number_of_wks_energies,
                                                                 p::wks_variance(d.wks_variance,
                                                                                 p::shot_radius(d.shot_radius,
                                                                                                oracle)))))));
  return p::number_of_eigenpairs(eigenpairs, p::use_intrinsic_delaunay(s.use_intrinsic_delaunay, descriptors));
}

/// Named parameters of refine_coupled_maps() for `r`, with `visitor` used by reference.
template <typename Visitor>
auto refinement_parameters(const CGAL::Surface_mesh_correspondence::Refinement_settings& r, Visitor& visitor)
{
  namespace p = CGAL::Surface_mesh_correspondence::parameters;
  const auto solver = p::trws_number_of_iterations(
      r.trws_number_of_iterations,
      p::trws_relative_tolerance(r.trws_relative_tolerance, p::visitor(std::ref(visitor))));
  const auto schedule = p::number_of_outer_iterations(
      r.number_of_outer_iterations,
      p::stop_when_consistency_worsens(r.stop_when_consistency_worsens,
                                       p::keep_consistent_input_maps(r.keep_consistent_input_maps, solver)));
  const auto terms = p::consistency_weight(r.consistency_weight, p::use_coupling(
      r.use_coupling,
      p::use_neighbor_matches(r.use_neighbor_matches, p::pairwise_rings(r.pairwise_rings, schedule))));
  return p::number_of_candidates(r.number_of_candidates,
                                 p::ring_schedule(r.ring_schedule, p::unary_weight(r.unary_weight, terms)));
}

} // namespace comap

#endif // SMC_TOOLS_COMAP_PARAMETERS_H
