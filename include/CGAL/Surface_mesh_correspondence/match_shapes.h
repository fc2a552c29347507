// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// match_shapes(): the whole matching job in one call, from two meshes (or two prepared shapes) to
// the best maps in both directions: validation, preparation, initial maps (automatic, or given
// and then repaired and compared with the automatic ones), the coupled refinement, and the
// selection of where the refined maps replace their input.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_MATCH_SHAPES_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_MATCH_SHAPES_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/candidate_maps.h>
#include <CGAL/Surface_mesh_correspondence/internal/given_maps_comparison.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_diagnostics.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_selection.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <array>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// What match_shapes() did: the decision taken at each stage and why, the wall time of each
/// stage, the consistency and distortion of the maps before and after the refinement, and the
/// refinement's solves (TRW-S energies and bounds).
struct Matching_result
{
  /// Where the initial maps came from: the automatic initialisation, or the caller
  /// (`initial_maps`).
  Map_origin initial_maps = Map_origin::automatic;
  /// The kind of maps that entered the refinement, which chose its defaults: automatic also for
  /// given maps that a kept repair pass recomputed or that the automatic maps replaced.
  Map_origin refined_maps = Map_origin::automatic;
  /// Landmarks guided the automatic initialisation.
  bool used_landmarks = false;
  /// Given maps: whether their tears were repaired (setting `repair_given_maps`) and how many
  /// repair passes were kept (also for automatic maps: their own tear repair).
  bool repaired = false;
  int repair_passes = 0;
  /// Given maps: whether they were compared with the automatic maps, whether those were computed
  /// (not when the given maps' sample distortion was within `automatic_maps_comparison_threshold`)
  /// and kept, and both sample distortions.
  bool compared = false, automatic_maps_computed = false, automatic_maps_kept = false;
  double given_maps_distortion = 0, automatic_maps_distortion = 0;
  /// Whether the refinement ran (setting `use_refinement`), its summary (solves with their
  /// energies, bounds and TRW-S iterations, termination reason, times) and the selection that
  /// followed it.
  bool refined = false;
  Coupled_refinement_result refinement;
  Selection_result selection;
  /// Why the refinement stopped (schedule_completed when it did not run).
  Refinement_termination termination = Refinement_termination::schedule_completed;
  /// The automatic initialisation, repair or comparison (fits, ZoomOut, tears, distortions).
  Automatic_initialization_result initialization;
  /// One line per decision, in order ("initial maps: automatic ...", "refinement: ...").
  std::vector<std::string> decisions;
  /// Wall seconds of each stage (indexed by Matching_stage) and of the whole call.
  std::array<double, 7> stage_seconds{};
  double total_seconds = 0;
  /// Consistency before the refinement (the maps that entered it) and of the returned maps:
  /// vertices with T21(T12(x)) != x (both directions), and the mean Euclidean cycle error
  /// |x - T21(T12(x))| / sqrt(area) over the vertices of both meshes.
  std::size_t inconsistent_vertices_before = 0, inconsistent_vertices_after = 0;
  double cycle_error_before = 0, cycle_error_after = 0;
  /// The mean mid-range geodesic distortion (see Selection_result) of the maps that entered the
  /// refinement and of the returned maps (0 when the refinement did not run).
  double distortion_before = 0, distortion_after = 0;
  /// Ground-truth-free diagnostics (cycle consistency, distortion, descriptor distance,
  /// orientation, MRF energy) of the maps that entered the refinement and of the returned maps
  /// (the same maps when the refinement did not run), per direction, over each mesh and per
  /// region (`diagnostic_regions`).
  Matching_diagnostics diagnostics;
  /// How far the returned maps are trusted, from their diagnostics; `confidence.low` says they are
  /// probably wrong as a whole (`confidence_threshold`).
  Matching_confidence confidence;
  /// The maps that entered the refinement, as vertex indices (mesh 1 -> 2 and 2 -> 1): the
  /// automatic maps, or the given maps after their repair and comparison.
  Vertex_index_map_vector unrefined_map_12, unrefined_map_21;
  /// What the input check found in mesh 1 and mesh 2 beyond manifold meshes of well-shaped
  /// triangles (non-manifold edges and vertices, degenerate faces), which the matching handled.
  Mesh_irregularities irregularities_1, irregularities_2;

  double seconds(Matching_stage s) const { return stage_seconds[static_cast<std::size_t>(s)]; }
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The visitor of match_shapes(): the events of its stages. Every function returns whether the
/// run goes on; a false stops it, and match_shapes() throws Matching_stopped, leaving the output
/// maps as they were. Derive from it and hide the functions you need. The functions may be called
/// from any thread of the run, never concurrently.
struct Default_matching_visitor
{
  /// A stage begins (stages that do not apply to a run are skipped).
  bool stage_begun(Matching_stage) { return true; }
  /// A stage has done about this fraction (in [0, 1]) of its work.
  bool progress(Matching_stage, double /*fraction*/) { return true; }
  /// A stage has ended after `seconds`.
  bool stage_ended(Matching_stage, double /*seconds*/) { return true; }
  /// A TRW-S iteration of a refinement solve (direction 0: the map 1 -> 2, 1: 2 -> 1).
  bool trws_iteration(int /*direction*/, std::size_t /*iteration*/, double /*energy*/, double /*lower_bound*/)
  {
    return true;
  }
  /// A refinement solve has ended.
  bool refinement_step(const Refinement_step&) { return true; }
};

namespace internal {

/// Thrown inside a run when the visitor asks to stop; match_shapes() turns it into
/// Matching_stopped.
struct Stop_request
{
  Matching_stage stage;
};

/// Forwards the events to the user's visitor (one at a time) and throws Stop_request when it
/// returns false.
template <typename Visitor>
class Matching_events
{
public:
  explicit Matching_events(Visitor& v) : visitor_(v) {}

  void begin(Matching_stage s)
  {
    stage_ = s;
    start_ = std::chrono::steady_clock::now();
    check(call([&] { return visitor_.stage_begun(s); }));
  }
  double end(Matching_stage s)
  {
    const double seconds = seconds_since(start_);
    check(call([&] { return visitor_.stage_ended(s, seconds); }));
    return seconds;
  }
  void progress(double fraction)
  {
    check(call([&] { return visitor_.progress(stage_, std::min(1.0, std::max(0.0, fraction))); }));
  }
  // The refinement's visitor interface.
  bool trws_iteration(int direction, std::size_t iteration, double energy, double bound)
  {
    check(call([&] { return visitor_.trws_iteration(direction, iteration, energy, bound); }));
    return true;
  }
  bool step(const Refinement_step& s)
  {
    check(call([&] { return visitor_.refinement_step(s); }));
    return true;
  }

private:
  // Once the visitor has returned false, it is not called again: the tasks still running (the
  // other shape's preparation, the other direction's solve) stop at their next event.
  template <typename F>
  bool call(const F& f)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if(stopped_) return false;
    stopped_ = !f();
    return !stopped_;
  }
  void check(bool go_on) const
  {
    if(!go_on) throw Stop_request{stage_};
  }

  Visitor& visitor_;
  std::mutex mutex_;
  bool stopped_ = false;
  Matching_stage stage_ = Matching_stage::validation;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// The inputs of a run on prepared shapes, read from the named parameters.
struct Matching_inputs
{
  Matching_settings settings;
  std::optional<std::pair<std::vector<int>, std::vector<int> > > initial_maps;
  std::vector<std::pair<std::size_t, std::size_t> > landmarks;
  bool verbose = false;
};

inline double mean_cycle_error(const Shape_data& a, const Shape_data& b, const std::vector<int>& x12,
                               const std::vector<int>& x21)
{
  double e1, f1, e2, f2;
  cycle_statistics(a.mesh, x12, x21, e1, f1);
  cycle_statistics(b.mesh, x21, x12, e2, f2);
  const double n1 = double(x12.size()), n2 = double(x21.size());
  return (e1 * n1 + e2 * n2) / (n1 + n2);
}

inline std::string fixed_text(double x, int digits = 4)
{
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

inline std::string percent_text(double x) { return fixed_text(100 * x, 1) + "%"; }

/// The initialisation stage of a run without initial maps.
template <typename ConcurrencyTag, typename Events>
void automatic_stage(const Shape_data& d1, const Shape_data& d2, const Initialization_settings& s,
                     std::vector<std::size_t>& m12, std::vector<std::size_t>& m21, Events& events,
                     Matching_result& result)
{
  events.begin(Matching_stage::initialization);
  result.initialization = automatic_initial_maps_of_meshes<ConcurrencyTag>(
      initialization_mesh_source(d1), initialization_mesh_source(d2), s, m12, m21, std::chrono::steady_clock::now());
  result.repair_passes = result.initialization.repair_passes;
  result.decisions.push_back("initial maps: automatic (functional maps and ZoomOut), " +
                             std::to_string(result.initialization.repair_passes) + " tear repair pass(es) kept" +
                             (result.used_landmarks ? ", guided by " + std::to_string(s.landmarks.size()) +
                                                          " landmarks"
                                                    : std::string()));
  result.stage_seconds[std::size_t(Matching_stage::initialization)] = events.end(Matching_stage::initialization);
}

/// The repair and comparison stages of a run with initial maps.
template <typename ConcurrencyTag, typename Events>
void given_maps_stages(const Shape_data& d1, const Shape_data& d2, const Initialization_settings& s, bool repair,
                       std::vector<std::size_t>& m12, std::vector<std::size_t>& m21, Events& events,
                       Matching_result& result)
{
  const auto start = std::chrono::steady_clock::now();
  result.repaired = repair;
  result.compared = s.compare_with_automatic_maps;
  result.decisions.push_back("initial maps: given");
  if(!repair && !s.compare_with_automatic_maps) return;
  result.initialization = on_prepared_meshes<ConcurrencyTag>(
      initialization_mesh_source(d1), initialization_mesh_source(d2), s, start,
      [&](const Initialization_shape& a, const Initialization_shape& b) {
        Initialization_pass_cache cache;
        const Given_maps_before_repair before{m12, m21};
        if(repair) events.begin(Matching_stage::repair);
        Automatic_initialization_result r = repair_given_maps_tears<ConcurrencyTag>(a, b, s, m12, m21, repair, cache);
        if(repair)
        {
          result.decisions.push_back(
              r.repair_passes > 0
                  ? "tear repair: a repair pass replaced the given maps (torn fraction " +
                        percent_text(r.torn_fraction_before) + " -> " + percent_text(r.torn_fraction) + ")"
                  : "tear repair: the given maps were kept (torn fraction " + percent_text(r.torn_fraction_before) +
                        ")");
          result.stage_seconds[std::size_t(Matching_stage::repair)] = events.end(Matching_stage::repair);
        }
        if(s.compare_with_automatic_maps) events.begin(Matching_stage::comparison);
        r = compare_or_grow_given_maps<ConcurrencyTag>(a, b, s, m12, m21, r, cache, before);
        if(s.compare_with_automatic_maps)
        {
          if(!r.automatic_maps_computed)
            result.decisions.push_back("comparison: the given maps were kept without computing the automatic maps "
                                       "(sample distortion " + fixed_text(r.given_maps_distortion) + " <= " +
                                       fixed_text(s.automatic_maps_comparison_threshold) + ")");
          else
            result.decisions.push_back(
                std::string("comparison: the ") + (r.automatic_maps_kept ? "automatic" : "given") +
                " maps were kept (sample distortion " + fixed_text(r.automatic_maps_distortion) + " automatic, " +
                fixed_text(r.given_maps_distortion) + " given" +
                (!r.automatic_maps_kept && r.automatic_maps_distortion < r.given_maps_distortion
                     ? "; the automatic maps are not trusted above " +
                           fixed_text(s.automatic_maps_maximum_distortion) + ": a pair far from isometric"
                     : std::string()) +
                ")" + (r.repair_undone ? "; the repair was undone: the given maps are kept as given" : ""));
          result.stage_seconds[std::size_t(Matching_stage::comparison)] = events.end(Matching_stage::comparison);
        }
        return r;
      });
  const Automatic_initialization_result& r = result.initialization;
  result.repair_passes = r.repair_passes;
  result.automatic_maps_computed = r.automatic_maps_computed;
  result.automatic_maps_kept = r.automatic_maps_kept;
  result.given_maps_distortion = r.given_maps_distortion;
  result.automatic_maps_distortion = r.automatic_maps_distortion;
  // Maps of the automatic initialisation (the automatic maps, or a kept repair pass: ZoomOut maps
  // steered by landmarks from the given maps' core) are refined as automatic maps.
  result.refined_maps = (r.automatic_maps_kept || r.repair_passes > 0 || r.distortion_repair_passes > 0)
                            ? Map_origin::automatic
                            : Map_origin::given;
}

/// The refinement and selection stages.
template <typename ConcurrencyTag, typename Events>
void refinement_stages(const Shape_data& d1, const Shape_data& d2, const Matching_settings& settings,
                       std::vector<int>& x12, std::vector<int>& x21, Events& events, Matching_result& result)
{
  result.inconsistent_vertices_before = inconsistent_vertices(x12, x21);
  result.cycle_error_before = mean_cycle_error(d1, d2, x12, x21);
  const Matching_settings resolved = settings.resolved(result.refined_maps);
  const Refinement_settings rs = Refinement_settings::from(resolved);
  const Selection_settings selection_settings = Selection_settings::from(settings);
  if(!settings.use_refinement)
  {
    result.decisions.push_back("refinement: not run (use_refinement is false)");
    result.inconsistent_vertices_after = result.inconsistent_vertices_before;
    result.cycle_error_after = result.cycle_error_before;
    // The diagnostics of the returned maps (no stage of their own: a fraction of a second).
    Fast_marching_geometry g1, g2;
    invoke_both<ConcurrencyTag>([&] { g1.build(d1.mesh); }, [&] { g2.build(d2.mesh); });
    result.diagnostics = matching_diagnostics<ConcurrencyTag>(d1, g1, d2, g2, x12, x21, x12, x21,
                                                              Diagnostics_settings::from(rs, selection_settings));
    result.confidence = matching_confidence(result.diagnostics, selection_settings.confidence_threshold);
    return;
  }
  const std::vector<int> input12 = x12, input21 = x21;
  events.begin(Matching_stage::refinement);
  result.refinement = refine_coupled_maps<ConcurrencyTag>(d1, d2, x12, x21, rs, events);
  result.refined = true;
  result.termination = result.refinement.termination;
  result.decisions.push_back(std::string("refinement: ") +
                             (result.refined_maps == Map_origin::automatic ? "defaults for automatic maps"
                                                                           : "defaults for given maps") +
                             ", " + std::to_string(result.refinement.kept_outer_iterations) + " of " +
                             std::to_string(result.refinement.outer_iterations) + " outer iterations kept (" +
                             to_string(result.termination) + ")");
  result.stage_seconds[std::size_t(Matching_stage::refinement)] = events.end(Matching_stage::refinement);

  events.begin(Matching_stage::selection);
  Fast_marching_geometry g1, g2;
  invoke_both<ConcurrencyTag>([&] { g1.build(d1.mesh); }, [&] { g2.build(d2.mesh); });
  result.selection =
      select_refined_maps<ConcurrencyTag>(d1, g1, d2, g2, input12, input21, x12, x21, selection_settings);
  const Selection_result& s = result.selection;
  result.distortion_before = s.input_distortion;
  result.distortion_after = s.selected_distortion;
  std::string why;
  if(settings.refinement_selection == Refinement_selection::refined)
    why = "the refined maps (refinement_selection refined)";
  else if(s.refined_more_consistent)
    why = "the refined maps, more consistent than their input (" + std::to_string(s.inconsistent_refined) + " < " +
          std::to_string(s.inconsistent_input) + " inconsistent vertices)";
  else if(settings.refinement_selection == Refinement_selection::consistency)
    why = "the input maps, more consistent than the refined ones (" + std::to_string(s.inconsistent_input) +
          " <= " + std::to_string(s.inconsistent_refined) + " inconsistent vertices)";
  else
    why = "the refined maps where they distort mid-range distances less (" + percent_text(s.refined_fraction_12) +
          " and " + percent_text(s.refined_fraction_21) + " of the vertices), the input elsewhere: the refined "
          "maps are less consistent (" + std::to_string(s.inconsistent_refined) + " >= " +
          std::to_string(s.inconsistent_input) + " inconsistent vertices)";
  result.decisions.push_back("selection: " + why);
  result.diagnostics = matching_diagnostics<ConcurrencyTag>(d1, g1, d2, g2, input12, input21, x12, x21,
                                                            Diagnostics_settings::from(rs, selection_settings));
  result.confidence = matching_confidence(result.diagnostics, selection_settings.confidence_threshold);
  result.stage_seconds[std::size_t(Matching_stage::selection)] = events.end(Matching_stage::selection);
  result.inconsistent_vertices_after = inconsistent_vertices(x12, x21);
  result.cycle_error_after = mean_cycle_error(d1, d2, x12, x21);
}

/// A run on prepared shapes: the maps are computed in `x12` and `x21`.
template <typename ConcurrencyTag, typename Events>
Matching_result match_prepared_shapes(const Shape_data& d1, const Shape_data& d2, const Matching_inputs& in,
                                      std::vector<int>& x12, std::vector<int>& x21, Events& events,
                                      std::chrono::steady_clock::time_point start)
{
  Matching_result result;
  result.irregularities_1 = mesh_irregularities(d1.mesh);
  result.irregularities_2 = mesh_irregularities(d2.mesh);
  for(int k : {1, 2})
  {
    const Mesh_irregularities& r = k == 1 ? result.irregularities_1 : result.irregularities_2;
    if(!r.empty())
      result.decisions.push_back("input: mesh " + std::to_string(k) + " has " + irregularities_summary(r) +
                                 " (tufted Laplacian" + (r.degenerate_faces.empty() ? "" : " with mollification") +
                                 ")");
  }
  const Matching_settings& settings = in.settings;
  const std::size_t n1 = std::size_t(d1.number_of_vertices()), n2 = std::size_t(d2.number_of_vertices());
  Initialization_settings s = initialization_settings(settings);
  s.landmarks = in.landmarks;
  s.verbose = in.verbose;
  result.used_landmarks = !in.landmarks.empty();
  // Progress of the initialisation: its steps (three per pass, every repair pass counted).
  const double expected_steps = 3.0 * (1 + 2 * s.tear_repair_passes + s.distortion_repair_passes);
  double steps = 0;
  s.step_done = [&] { events.progress(++steps / expected_steps); };
  std::vector<std::size_t> m12, m21;
  if(!in.initial_maps)
  {
    automatic_stage<ConcurrencyTag>(d1, d2, s, m12, m21, events, result);
  }
  else
  {
    result.initial_maps = result.refined_maps = Map_origin::given;
    m12.assign(in.initial_maps->first.begin(), in.initial_maps->first.end());
    m21.assign(in.initial_maps->second.begin(), in.initial_maps->second.end());
    check_vertex_map(m12, n1, n2, "initial map 1->2");
    check_vertex_map(m21, n2, n1, "initial map 2->1");
    s.compare_with_automatic_maps = settings.compare_with_automatic_maps;
    given_maps_stages<ConcurrencyTag>(d1, d2, s, settings.repair_given_maps, m12, m21, events, result);
  }
  x12.assign(m12.begin(), m12.end());
  x21.assign(m21.begin(), m21.end());
  result.unrefined_map_12 = std::move(m12);
  result.unrefined_map_21 = std::move(m21);
  refinement_stages<ConcurrencyTag>(d1, d2, settings, x12, x21, events, result);
  result.total_seconds = seconds_since(start);
  return result;
}

/// The settings, landmarks and flags of the named parameters (the initial maps are read by the
/// overloads, which know their types).
template <typename NamedParameters>
Matching_inputs matching_inputs(const NamedParameters& np, std::size_t n1, std::size_t n2)
{
  Matching_inputs in;
  in.settings = Matching_settings::from(np);
  in.landmarks = landmarks_parameter(np);
  for(const auto& l : in.landmarks)
    if(l.first >= n1 || l.second >= n2)
      throw Invalid_parameter_error("landmark (" + std::to_string(l.first) + ", " + std::to_string(l.second) +
                                    ") is not a pair of vertices of mesh 1 (" + std::to_string(n1) +
                                    " vertices) and mesh 2 (" + std::to_string(n2) + " vertices)");
  in.verbose = parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::verbose), false);
  check_initialization_settings(initialization_settings(in.settings));
  return in;
}

/// Runs `f(events)` with the visitor of `np` (by reference when given as std::ref(v)), turning a
/// stop request into Matching_stopped.
template <typename NamedParameters, typename F>
Matching_result with_matching_events(const NamedParameters& np, const F& f)
{
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Default_matching_visitor>::reference Visitor_reference;
  Default_matching_visitor default_visitor;
  Visitor_reference visitor =
      parameters::choose_parameter(parameters::get_parameter_reference(np, CGAL::internal_np::visitor), default_visitor);
  typedef typename std::remove_reference<Visitor_reference>::type Visitor;
  Matching_events<Visitor> events(visitor);
  try
  {
    return f(events);
  }
  catch(const Stop_request& stop)
  {
    throw Matching_stopped(std::string("match_shapes: stopped by the visitor during the ") + to_string(stop.stage) +
                           " stage");
  }
}

/// The pipeline of match_shapes() on meshes that are not prepared yet: the validation, the
/// preparation of both shapes (both at once with Parallel_tag), the run on them.
/// `initial_maps(s1, s2, in)` puts the given initial maps into `in` as indices (once the shapes
/// know their vertices), `output(s1, s2, x12, x21)` writes the maps.
template <typename ConcurrencyTag, typename TriangleMesh1, typename TriangleMesh2, typename NamedParameters,
          typename NamedParameters1, typename NamedParameters2, typename InitialMaps, typename Output>
Matching_result match_unprepared_meshes(const TriangleMesh1& tm1, const TriangleMesh2& tm2, std::size_t n1,
                                        std::size_t n2, bool has_initial_maps, const NamedParameters& np,
                                        const NamedParameters1& np1, const NamedParameters2& np2,
                                        const InitialMaps& initial_maps, const Output& output)
{
  const auto start = std::chrono::steady_clock::now();
  return with_matching_events(np, [&](auto& events) {
    events.begin(Matching_stage::validation);
    Matching_inputs in = matching_inputs(np, n1, n2);
    const double validation = events.end(Matching_stage::validation);

    events.begin(Matching_stage::preparation);
    const bool for_initialization =
        !has_initial_maps || in.settings.repair_given_maps || in.settings.compare_with_automatic_maps;
    typedef Correspondence_shape<TriangleMesh1, ConcurrencyTag> Shape1;
    typedef Correspondence_shape<TriangleMesh2, ConcurrencyTag> Shape2;
    std::optional<Shape1> s1;
    std::optional<Shape2> s2;
    int prepared = 0;
    invoke_both<ConcurrencyTag>(
        [&] {
          s1.emplace(tm1, parameters::combine(np1, np), Shape_preparation{for_initialization}, "mesh 1");
          events.progress(0.5 * ++prepared);
        },
        [&] {
          s2.emplace(tm2, parameters::combine(np2, np), Shape_preparation{for_initialization}, "mesh 2");
          events.progress(0.5 * ++prepared);
        });
    const double preparation = events.end(Matching_stage::preparation);

    initial_maps(*s1, *s2, in);
    std::vector<int> x12, x21;
    Matching_result result = match_prepared_shapes<ConcurrencyTag>(s1->data(), s2->data(), in, x12, x21, events, start);
    result.stage_seconds[std::size_t(Matching_stage::validation)] = validation;
    result.stage_seconds[std::size_t(Matching_stage::preparation)] = preparation;
    output(*s1, *s2, x12, x21);
    result.total_seconds = seconds_since(start);
    return result;
  });
}

template <typename T>
struct Is_correspondence_shape : std::false_type
{};
template <typename TriangleMesh, typename Tag>
struct Is_correspondence_shape<Correspondence_shape<TriangleMesh, Tag> > : std::true_type
{};

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes dense point-to-point maps between two prepared shapes, in both directions: the whole
/// pipeline of match_shapes() on meshes, without the preparation (each shape is prepared once,
/// for one-against-many matching; see Correspondence_shape).
///
/// `map_12[i]` receives the vertex of `shape_2` matched to vertex i of `shape_1`, `map_21` the
/// other way round (indices of the shapes' vertex index maps); they are written only when the run
/// succeeds. Named parameters: those of match_shapes(), with `initial_maps(a, b)` taking two
/// Vertex_index_map_vector. The settings of stage `preparation` are those the shapes were
/// prepared with; the initialisation's descriptors are computed (once per shape) when the
/// initialisation settings differ from the shapes'.
/// \throws as match_shapes()
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Matching_result match_shapes(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                             const Correspondence_shape<TriangleMesh2, Tag2>& shape_2, Vertex_index_map_vector& map_12,
                             Vertex_index_map_vector& map_21, const NamedParameters& np = parameters::default_values())
{
  const auto start = std::chrono::steady_clock::now();
  return internal::with_matching_events(np, [&](auto& events) {
    events.begin(Matching_stage::validation);
    internal::Matching_inputs in =
        internal::matching_inputs(np, shape_1.number_of_vertices(), shape_2.number_of_vertices());
    const auto& given = parameters::get_parameter_reference(np, internal_np::initial_maps);
    if constexpr(!std::is_same<typename std::decay<decltype(given)>::type, CGAL::internal_np::Param_not_found>::value)
    {
      const Vertex_index_map_vector& a = given.first;
      const Vertex_index_map_vector& b = given.second;
      check_vertex_map(a, shape_1.number_of_vertices(), shape_2.number_of_vertices(), "initial map 1->2");
      check_vertex_map(b, shape_2.number_of_vertices(), shape_1.number_of_vertices(), "initial map 2->1");
      in.initial_maps.emplace(std::vector<int>(a.begin(), a.end()), std::vector<int>(b.begin(), b.end()));
    }
    Matching_result result;
    const double validation = events.end(Matching_stage::validation);
    std::vector<int> x12, x21;
    result = internal::match_prepared_shapes<ConcurrencyTag>(shape_1.data(), shape_2.data(), in, x12, x21, events,
                                                             start);
    result.stage_seconds[std::size_t(Matching_stage::validation)] = validation;
    map_12.assign(x12.begin(), x12.end());
    map_21.assign(x21.begin(), x21.end());
    return result;
  });
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes dense, accurate and cycle-consistent point-to-point maps between two triangle
/// meshes, in both directions, in one call: the package's whole pipeline with the library's
/// defaults.
///
/// The stages (Matching_stage), as the named parameters say:
///   1. validation of the settings, initial maps and landmarks;
///   2. preparation of each shape (Correspondence_shape: one Laplace-Beltrami eigensolve per shape
///      for the initialisation and the refinement's descriptors, the initialisation's
///      descriptors, the geodesic distance oracle), both shapes at once with Parallel_tag;
///   3. initial maps: automatic by default (functional maps fitted to descriptors, coupled
///      ZoomOut, tear repair; guided by `landmarks` when given); or the maps of `initial_maps`,
///      whose tears are repaired (`repair_given_maps`) and which are compared with the automatic
///      maps, the less distorting pair being kept (`compare_with_automatic_maps`);
///   4. the coupled refinement (Azencot, Dubrovina and Guibas 2019, with a cycle term), with the
///      defaults that fit where the maps came from (Map_origin);
///   5. the selection: the refined maps replace their input everywhere when they are more
///      consistent (Eq. 4 of the paper), else only where they distort mid-range geodesic distances
///      less (`refinement_selection`).
/// Each refinement solve minimises, over the candidates \f$ x(i) \in \Phi(i) \f$,
/// \f[ \sum_i \big( \mu \| F_a(i) - F_b(x(i)) \|^2 + \lambda\, d_a(i, y(x(i))) \big)
///     + \sum_{(i,j) \in E_a} \big| d_a(i,j) - d_b(x(i), x(j)) \big| \f]
/// (see refine_coupled_maps()).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (every stage; both give
///   the same maps bit for bit)
/// \tparam TriangleMesh1, TriangleMesh2 models of `FaceListGraph` whose faces are triangles
/// \tparam VertexVertexMap12 a model of `WritablePropertyMap` from the vertices of `tm1` to those
///   of `tm2`; the same for VertexVertexMap21. They are written only when the run succeeds.
/// \param tm1, tm2 the two meshes
/// \param map_12, map_21 output: the vertex of `tm2` matched to each vertex of `tm1`, and the other
///   way round
/// \param np optional named parameters:
///   - every setting of the registry by its name (Matching_settings; the settings table of the
///     manual), or all of them at once with `matching_settings(s)` (individual named parameters
///     take precedence);
///   - `initial_maps(map_12, map_21)`: readable property maps from the vertices of `tm1` to those of
///     `tm2` and back: the maps to start from (default: automatic);
///   - `landmarks`: a range of pairs (vertex index in `tm1`, vertex index in `tm2`) of known
///     correspondences for the automatic initialisation;
///   - `visitor`: a Default_matching_visitor (by reference with std::ref(v)); `verbose`.
/// \param np1, np2 `vertex_point_map` and `vertex_index_map` of each mesh
/// \returns what the run did (Matching_result)
/// \throws Invalid_mesh_error (empty, non-triangle, non-manifold or several-component meshes,
///   degenerate faces, non-finite coordinates, too few vertices), Invalid_map_error (initial maps
///   that are not maps between the meshes), Invalid_parameter_error (a setting out of its range, a
///   landmark out of range), Numerical_error, Matching_stopped (the visitor stopped the run)
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename VertexVertexMap12, typename VertexVertexMap21,
          typename NamedParameters = parameters::Default_named_parameters,
          typename NamedParameters1 = parameters::Default_named_parameters,
          typename NamedParameters2 = parameters::Default_named_parameters>
typename std::enable_if<!internal::Is_correspondence_shape<TriangleMesh1>::value &&
                            !std::is_same<TriangleMesh1, Triangle_soup>::value,
                        Matching_result>::type
match_shapes(const TriangleMesh1& tm1, const TriangleMesh2& tm2, VertexVertexMap12 map_12, VertexVertexMap21 map_21,
             const NamedParameters& np = parameters::default_values(),
             const NamedParameters1& np1 = parameters::default_values(),
             const NamedParameters2& np2 = parameters::default_values())
{
  const auto& given = parameters::get_parameter_reference(np, internal_np::initial_maps);
  constexpr bool has_initial_maps =
      !std::is_same<typename std::decay<decltype(given)>::type, CGAL::internal_np::Param_not_found>::value;
  return internal::match_unprepared_meshes<ConcurrencyTag>(
      tm1, tm2, std::size_t(num_vertices(tm1)), std::size_t(num_vertices(tm2)), has_initial_maps, np, np1, np2,
      [&](const auto& s1, const auto& s2, internal::Matching_inputs& in) {
        if constexpr(has_initial_maps)
        {
          auto vim1 = CGAL::get_initialized_vertex_index_map(tm1, np1);
          auto vim2 = CGAL::get_initialized_vertex_index_map(tm2, np2);
          in.initial_maps.emplace(
              internal::vertex_map_indices<int>(given.first, tm2, s1, vim2, "initial map 1->2", "mesh 2"),
              internal::vertex_map_indices<int>(given.second, tm1, s2, vim1, "initial map 2->1", "mesh 1"));
        }
        else
          (void)s1, (void)s2, (void)in;
      },
      [&](const auto& s1, const auto& s2, const std::vector<int>& x12, const std::vector<int>& x21) {
        for(std::size_t i = 0; i < x12.size(); ++i) put(map_12, s1.vertex(i), s2.vertex(std::size_t(x12[i])));
        for(std::size_t k = 0; k < x21.size(); ++k) put(map_21, s2.vertex(k), s1.vertex(std::size_t(x21[k])));
      });
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// match_shapes() on two triangle soups (Triangle_soup: points and index triples, vertex i being
/// point i), which need no halfedge data structure: the same pipeline, with the maps as vectors
/// of point indices (`map_12[i]`: the point of `soup_2` matched to point i of `soup_1`), written
/// only when the run succeeds. Named parameters: those of match_shapes() on meshes, with
/// `initial_maps(a, b)` taking two Vertex_index_map_vector.
/// \throws as match_shapes() on meshes
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename NamedParameters = parameters::Default_named_parameters>
Matching_result match_shapes(const Triangle_soup& soup_1, const Triangle_soup& soup_2,
                             Vertex_index_map_vector& map_12, Vertex_index_map_vector& map_21,
                             const NamedParameters& np = parameters::default_values())
{
  const auto& given = parameters::get_parameter_reference(np, internal_np::initial_maps);
  constexpr bool has_initial_maps =
      !std::is_same<typename std::decay<decltype(given)>::type, CGAL::internal_np::Param_not_found>::value;
  const std::size_t n1 = soup_1.number_of_vertices(), n2 = soup_2.number_of_vertices();
  if constexpr(has_initial_maps)
  {
    check_vertex_map(given.first, n1, n2, "initial map 1->2");
    check_vertex_map(given.second, n2, n1, "initial map 2->1");
  }
  return internal::match_unprepared_meshes<ConcurrencyTag>(
      soup_1, soup_2, n1, n2, has_initial_maps, np, parameters::default_values(), parameters::default_values(),
      [&](const auto&, const auto&, internal::Matching_inputs& in) {
        if constexpr(has_initial_maps)
          in.initial_maps.emplace(std::vector<int>(given.first.begin(), given.first.end()),
                                  std::vector<int>(given.second.begin(), given.second.end()));
        else
          (void)in;
      },
      [&](const auto&, const auto&, const std::vector<int>& x12, const std::vector<int>& x21) {
        map_12.assign(x12.begin(), x12.end());
        map_21.assign(x21.begin(), x21.end());
      });
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_MATCH_SHAPES_H
