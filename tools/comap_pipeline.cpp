// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_pipeline.h"
#include "comap_parameters.h"

namespace comap {

const Evaluator& Prepared_shape::evaluator() const
{
  if(!evaluator_) evaluator_.reset(new Evaluator(indexed_mesh()));
  return *evaluator_;
}

std::unique_ptr<Prepared_shape> prepare_shape(const std::string& name, Mesh mesh, const Settings& settings,
                                              bool for_refinement, bool for_initialization, const Progress& progress)
{
  const Stopwatch watch;
  std::unique_ptr<Prepared_shape> p(new Prepared_shape);
  p->name = name;
  p->mesh = std::move(mesh);
  const int needed =
      for_initialization ? smc::internal::initialization_number_of_eigenpairs(settings.initialization) : 0;
  // The initialisation needs `needed` eigenpairs on the intrinsic Delaunay triangulation (as in
  // automatic_initial_maps()). When the refinement needs no more on the same operator, one
  // eigensolve serves both: the initialisation's spectrum first, then the refinement's shape
  // takes its leading eigenpairs (precomputed_spectrum).
  const bool shared = for_refinement && for_initialization && settings.shape.use_intrinsic_delaunay &&
                      settings.shape.number_of_eigenpairs <= needed;
  double initialization_spectrum_seconds = 0;
  if(!for_refinement || shared)
  {
    const Stopwatch t;
    smc::internal::Mesh_requirements requirements;
    requirements.allow_several_components = false;
    p->own_mesh_.reset(new smc::internal::Indexed_mesh(
        smc::internal::make_indexed_mesh(p->mesh, smc::parameters::default_values(), requirements, name)));
    p->times.mesh = t.seconds();
  }
  if(for_initialization && static_cast<int>(p->number_of_vertices()) <= needed)
    throw smc::Invalid_mesh_error(name + " has " + std::to_string(p->number_of_vertices()) +
                                  " vertices, too few for the automatic initialisation's basis of " +
                                  std::to_string(needed) + " eigenfunctions (lower --init-basis)");
  if(shared)
  {
    const Stopwatch t;
    p->own_spectrum_.reset(
        new smc::Laplace_beltrami_spectrum(*p->own_mesh_, smc::parameters::number_of_eigenpairs(needed)));
    initialization_spectrum_seconds = t.seconds();
    p->shape.reset(new Shape(p->mesh,
                             smc::parameters::precomputed_spectrum(
                                 p->own_spectrum_,  // shared with the shape, not copied
                                 shape_parameters(settings.shape, settings.shape.number_of_eigenpairs)),
                             name));
    p->times = p->shape->preprocessing_times();
    p->spectrum_from_initialization = true;
    p->own_mesh_.reset();      // the shape's flat copy is the same
    p->own_spectrum_.reset();  // and the shape keeps the whole spectrum
  }
  else if(for_refinement)
  {
    p->shape.reset(new Shape(p->mesh, shape_parameters(settings.shape, settings.shape.number_of_eigenpairs), name));
    p->times = p->shape->preprocessing_times();
  }
  if(for_initialization)
  {
    const Stopwatch t;
    if(!p->own_spectrum_ && (!p->shape || p->shape->data().largest_spectrum().number_of_eigenpairs() != needed ||
                             !p->shape->data().largest_spectrum().uses_intrinsic_delaunay()))
      p->own_spectrum_.reset(
          new smc::Laplace_beltrami_spectrum(p->indexed_mesh(), smc::parameters::number_of_eigenpairs(needed)));
    p->initialization_descriptors = smc::internal::initialization_descriptors<Concurrency>(
        p->indexed_mesh(), p->initialization_spectrum(), settings.initialization);
    p->initialization_seconds = initialization_spectrum_seconds + t.seconds();
  }
  p->total_seconds = watch.seconds();
  progress.line("prepared " + name + " (" + std::to_string(p->number_of_vertices()) + " vertices) in " +
                duration(p->total_seconds) + ": " + preparation_summary(*p));
  return p;
}

std::string preparation_summary(const Prepared_shape& s)
{
  std::string out;
  if(s.shape)
    out = "spectrum (" + std::to_string(s.shape->spectrum().number_of_eigenpairs()) +
          (s.spectrum_from_initialization ? " eigenpairs, the initialisation's first) " : " eigenpairs) ") +
          duration(s.times.spectrum) + ", descriptor stack " + duration(s.times.descriptors) +
          ", geodesic distances " + duration(s.times.distances);
  if(s.initialization_descriptors.size() > 0)
    out += std::string(out.empty() ? "" : ", ") + "initialisation " +
           (s.shape && &s.initialization_spectrum() == &s.shape->data().largest_spectrum()
                ? std::string("descriptors ")
                : "spectrum (" + std::to_string(s.initialization_spectrum().number_of_eigenpairs()) +
                      " eigenpairs) and descriptors ") +
           duration(s.initialization_seconds);
  return out;
}

namespace {

smc::internal::Initialization_shape initialization_shape(const Prepared_shape& s)
{
  if(s.initialization_descriptors.size() == 0)
    throw std::logic_error("the shape " + s.name + " was not prepared for the initialisation");
  smc::internal::Initialization_shape out;
  out.mesh = &s.indexed_mesh();
  out.spectrum = &s.initialization_spectrum();
  out.descriptors = &s.initialization_descriptors;
  return out;
}

} // namespace

smc::Automatic_initialization_result initialize_maps(const Prepared_shape& a, const Prepared_shape& b,
                                                     const Settings& settings, Vertex_map& map_12, Vertex_map& map_21)
{
  return smc::internal::automatic_initial_maps<Concurrency>(initialization_shape(a), initialization_shape(b),
                                                            settings.initialization, map_12, map_21);
}

smc::Automatic_initialization_result repair_maps(const Prepared_shape& a, const Prepared_shape& b,
                                                 const Settings& settings, Vertex_map& map_12, Vertex_map& map_21,
                                                 bool repair_tears)
{
  return smc::internal::repair_given_maps<Concurrency>(initialization_shape(a), initialization_shape(b),
                                                       settings.initialization, map_12, map_21, repair_tears);
}

bool repaired_maps_are_automatic(const smc::Automatic_initialization_result& r)
{
  return r.automatic_maps_kept || r.repair_passes > 0 || r.distortion_repair_passes > 0;
}

std::string initialization_summary(const smc::Automatic_initialization_result& r)
{
  if(r.compared_with_automatic_maps && !r.automatic_maps_computed)
    return "the given maps are kept: sample distortion " + fixed(r.given_maps_distortion, 4) +
           ", within the comparison threshold (no automatic maps computed)";
  if(r.compared_with_automatic_maps)
  {
    const std::string distortions = "sample distortion " + fixed(r.automatic_maps_distortion, 4) +
                                    " (automatic) against " + fixed(r.given_maps_distortion, 4) + " (given)";
    if(r.automatic_maps_kept) return "the automatic maps replace the given ones: " + distortions;
    return "the given maps are kept: " + distortions;
  }
  return "torn fraction " + percent(r.torn_fraction_before) +
         (r.repair_passes > 0 ? " -> " + percent(r.torn_fraction) + " after " + std::to_string(r.repair_passes) +
                                    " repair pass(es)"
                              : std::string(" (kept)")) +
         ", sample distortion " + fixed(r.sample_distortion_before, 4) +
         (r.distortion_repair_passes > 0 ? " -> " + fixed(r.sample_distortion, 4) + " after " +
                                               std::to_string(r.distortion_repair_passes) + " distortion repair pass(es)"
                                         : std::string(" (kept)"));
}

namespace {

/// Prints one line per MRF solve.
struct Progress_visitor : smc::Default_refinement_visitor
{
  const Progress* progress = nullptr;
  std::string label;
  int outer_iterations = 0;
  bool step(const smc::Refinement_step& s)
  {
    progress->line(label + "refinement " + std::to_string(s.outer_iteration + 1) + "/" +
                   std::to_string(outer_iterations) + (s.direction == 0 ? ", map 1->2" : ", map 2->1") + ", " +
                   std::to_string(s.rings) + (s.rings == 1 ? " ring" : " rings") + ": energy " +
                   significant(s.energy) + " (bound " + significant(s.lower_bound) + ", " +
                   std::to_string(s.trws_iterations) + " TRW-S iterations), " + std::to_string(s.changed_vertices) +
                   " matches changed, " + std::to_string(s.inconsistent_vertices) + " inconsistent; data " +
                   duration(s.data_preparation_seconds) + ", TRW-S " + duration(s.trws_seconds));
    return true;
  }
};

} // namespace

smc::Coupled_refinement_result refine_maps(const Prepared_shape& a, const Prepared_shape& b, Vertex_map& map_12,
                                           Vertex_map& map_21, const Settings& settings, bool automatic_input,
                                           const Progress& progress, const std::string& label)
{
  if(!a.shape || !b.shape) throw std::logic_error("refine_maps: the shapes were not prepared for the refinement");
  Progress_visitor visitor;
  visitor.progress = &progress;
  visitor.label = label;
  // Automatic choices: keep the input maps when they are given, stop early and use the short ring
  // schedule when they are automatic.
  const smc::Refinement_settings r = resolved_refinement(settings, automatic_input);
  visitor.outer_iterations = r.outer_iterations();
  return smc::refine_coupled_maps<Concurrency>(*a.shape, *b.shape, map_12, map_21, refinement_parameters(r, visitor));
}

void write_preparation(Json_writer& json, const std::string& key, const Prepared_shape& s)
{
  json.begin_object(key)
      .value("name", s.name)
      .value("vertices", s.number_of_vertices())
      .value("faces", static_cast<std::size_t>(num_faces(s.mesh)))
      .value("eigenpairs", s.shape ? s.shape->spectrum().number_of_eigenpairs() : 0)
      .value("initialization_eigenpairs",
             s.initialization_descriptors.size() > 0 ? s.initialization_spectrum().number_of_eigenpairs() : 0)
      .value("mesh_seconds", s.times.mesh)
      .value("spectrum_seconds", s.times.spectrum)
      .value("descriptor_seconds", s.times.descriptors)
      .value("distance_seconds", s.times.distances)
      .value("initialization_seconds", s.initialization_seconds)
      .value("total_seconds", s.total_seconds)
      .value("dense_distance_oracle", s.shape ? s.shape->has_dense_oracle() : false)
      .end_object();
}

void write_initialization(Json_writer& json, const std::string& key, const smc::Automatic_initialization_result& r)
{
  json.begin_object(key)
      .value("functional_map_seconds", r.functional_map_seconds)
      .value("zoomout_seconds", r.zoomout_seconds)
      .value("total_seconds", r.total_seconds)
      .value("selection_score", r.selection_score)
      .value("orientation_sign", r.orientation_sign)
      .value("cycle_error", r.cycle_error)
      .value("cycle_fixed_fraction", r.cycle_fixed_fraction)
      .value("orientation_agreement", r.orientation_agreement)
      .value("initial_basis_size", r.initial_basis_size)
      .value("final_basis_size", r.final_basis_size)
      .value("repair_passes", r.repair_passes)
      .value("torn_fraction_before", r.torn_fraction_before)
      .value("torn_fraction", r.torn_fraction)
      .value("distortion_repair_passes", r.distortion_repair_passes)
      .value("sample_distortion_before", r.sample_distortion_before)
      .value("sample_distortion", r.sample_distortion)
      .value("compared_with_automatic_maps", r.compared_with_automatic_maps)
      .value("automatic_maps_computed", r.automatic_maps_computed)
      .value("automatic_maps_kept", r.automatic_maps_kept)
      .value("given_maps_distortion", r.given_maps_distortion)
      .value("automatic_maps_distortion", r.automatic_maps_distortion)
      .end_object();
}

void write_refinement(Json_writer& json, const std::string& key, const smc::Coupled_refinement_result& r)
{
  json.begin_object(key)
      .value("outer_iterations", r.outer_iterations)
      .value("kept_outer_iterations", r.kept_outer_iterations)
      .value("termination", smc::to_string(r.termination))
      .value("inconsistent_vertices_before", r.inconsistent_vertices_before)
      .value("inconsistent_vertices_after", r.inconsistent_vertices_after)
      .value("data_preparation_seconds", r.data_preparation_seconds)
      .value("trws_seconds", r.trws_seconds)
      .value("total_seconds", r.total_seconds);
  json.begin_array("steps");
  for(const smc::Refinement_step& s : r.steps)
    json.begin_object()
        .value("outer_iteration", s.outer_iteration)
        .value("direction", s.direction == 0 ? "1->2" : "2->1")
        .value("rings", s.rings)
        .value("energy", s.energy)
        .value("lower_bound", s.lower_bound)
        .value("trws_iterations", s.trws_iterations)
        .value("changed_vertices", s.changed_vertices)
        .value("inconsistent_vertices", s.inconsistent_vertices)
        .value("data_preparation_seconds", s.data_preparation_seconds)
        .value("trws_seconds", s.trws_seconds)
        .end_object();
  json.end_array();
  json.end_object();
}

void write_error_statistics(Json_writer& json, const std::string& key, const smc::Error_statistics& e,
                            bool with_curve)
{
  json.begin_object(key)
      .value("samples", e.errors.size())
      .value("mean", e.mean)
      .value("median", e.median)
      .value("maximum", e.maximum)
      .value("fraction_within_0.025", e.fraction_below(0.025))
      .value("fraction_within_0.05", e.fraction_below(0.05))
      .value("fraction_within_0.1", e.fraction_below(0.1));
  if(with_curve) json.value("thresholds", e.thresholds).value("cumulative", e.cumulative);
  json.end_object();
}

} // namespace comap
