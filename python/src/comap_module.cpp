// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The C++ half of the Python package `comap`: the library's match_shapes() on meshes given as
// arrays. The Python half (comap/__init__.py) converts array-likes to the contiguous arrays this
// module takes and documents the API.

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>
#include <CGAL/Surface_mesh_correspondence/settings_io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>
#include <memory>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;
namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;

#ifdef CGAL_LINKED_WITH_TBB
typedef CGAL::Parallel_tag Concurrency;
#else
typedef CGAL::Sequential_tag Concurrency;
#endif

typedef py::array_t<double, py::array::c_style | py::array::forcecast> Points_array;
typedef py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> Index_array;

/// The triangle soup of points (n, 3) and faces (m, 3), checked by the library (the Python half
/// has checked the shapes and types); vertex i is point i.
smc::Triangle_soup soup_of_arrays(const Points_array& points, const Index_array& faces, const std::string& name)
{
  const auto p = points.unchecked<2>();
  const auto f = faces.unchecked<2>();
  std::vector<std::array<double, 3> > soup_points(std::size_t(p.shape(0)));
  for(py::ssize_t i = 0; i < p.shape(0); ++i) soup_points[std::size_t(i)] = {{p(i, 0), p(i, 1), p(i, 2)}};
  std::vector<std::array<std::int64_t, 3> > soup_faces(std::size_t(f.shape(0)));
  for(py::ssize_t i = 0; i < f.shape(0); ++i) soup_faces[std::size_t(i)] = {{f(i, 0), f(i, 1), f(i, 2)}};
  return smc::Triangle_soup(soup_points, soup_faces, smc::Triangle_soup_origin(name));
}

/// `map` as indices, checked against the vertex counts of its source and target meshes.
smc::Vertex_index_map_vector checked_map(const Index_array& map, std::size_t sources, std::size_t targets,
                                         const std::string& what)
{
  const auto m = map.unchecked<1>();
  if(std::size_t(m.shape(0)) != sources)
    throw smc::Invalid_map_error(what + " has " + std::to_string(m.shape(0)) + " entries but its source mesh has " +
                                 std::to_string(sources) + " vertices");
  smc::Vertex_index_map_vector out(sources);
  for(py::ssize_t i = 0; i < m.shape(0); ++i)
  {
    if(m(i) < 0 || std::size_t(m(i)) >= targets)
      throw smc::Invalid_map_error(what + ": entry " + std::to_string(i) + " is " + std::to_string(m(i)) +
                                   ", not a vertex of its target mesh (" + std::to_string(targets) + " vertices)");
    out[std::size_t(i)] = std::size_t(m(i));
  }
  return out;
}

template <typename Range>
py::array_t<std::int64_t> index_array(const Range& r)
{
  py::array_t<std::int64_t> out(py::ssize_t(r.size()));
  auto o = out.mutable_unchecked<1>();
  for(std::size_t i = 0; i < r.size(); ++i) o(py::ssize_t(i)) = std::int64_t(r[i]);
  return out;
}

const char* origin_name(smc::Map_origin o) { return o == smc::Map_origin::automatic ? "automatic" : "given"; }

py::dict diagnostics_dict(const smc::Map_diagnostics& m)
{
  py::dict d;
  d["vertices"] = m.vertices;
  d["inconsistent_fraction"] = m.inconsistent_fraction;
  d["cycle_error"] = m.cycle_error;
  d["distortion"] = m.distortion;
  d["distortion_samples"] = m.distortion_samples;
  d["global_distortion"] = m.global_distortion;
  d["descriptor_distance"] = m.descriptor_distance;
  d["orientation_reversal"] = m.orientation_reversal;
  d["global_orientation_reversal"] = m.global_orientation_reversal;
  d["energy"] = m.energy;
  return d;
}

/// Matching_diagnostics as `comap match --stats` writes it, plus the region of every vertex
/// (`regions_1`, `regions_2`: numpy arrays).
py::dict diagnostics_dict(const smc::Matching_diagnostics& g)
{
  py::dict out;
  for(int direction = 0; direction < 2; ++direction)
  {
    py::dict phases;
    for(int phase = 0; phase < 2; ++phase)
    {
      const smc::Direction_diagnostics& x = phase == 0 ? g.before[direction] : g.after[direction];
      py::dict whole = diagnostics_dict(x.whole);
      py::list regions;
      for(const smc::Map_diagnostics& region : x.regions) regions.append(diagnostics_dict(region));
      whole["regions"] = regions;
      phases[phase == 0 ? "before" : "after"] = whole;
    }
    out[direction == 0 ? "map_12" : "map_21"] = phases;
  }
  out["regions_1"] = index_array(g.regions_1);
  out["regions_2"] = index_array(g.regions_2);
  return out;
}

/// What the input check found in a mesh (0-based indices): non_manifold_edges (k x 2),
/// non_manifold_vertices, degenerate_faces.
py::dict irregularities_dict(const smc::Mesh_irregularities& r)
{
  py::array_t<std::int64_t> edges({py::ssize_t(r.non_manifold_edges.size()), py::ssize_t(2)});
  auto e = edges.mutable_unchecked<2>();
  for(std::size_t k = 0; k < r.non_manifold_edges.size(); ++k)
    for(int c = 0; c < 2; ++c) e(py::ssize_t(k), c) = std::int64_t(r.non_manifold_edges[k][std::size_t(c)]);
  py::dict d;
  d["non_manifold_edges"] = edges;
  d["non_manifold_vertices"] = index_array(r.non_manifold_vertices);
  d["degenerate_faces"] = index_array(r.degenerate_faces);
  return d;
}

/// The figures of Matching_result, with the keys of `comap match --stats` ("result").
py::dict result_dict(const smc::Matching_result& r)
{
  py::dict d;
  d["initial_maps"] = origin_name(r.initial_maps);
  d["refined_maps"] = origin_name(r.refined_maps);
  d["used_landmarks"] = r.used_landmarks;
  d["repaired"] = r.repaired;
  d["repair_passes"] = r.repair_passes;
  d["compared"] = r.compared;
  d["automatic_maps_computed"] = r.automatic_maps_computed;
  d["automatic_maps_kept"] = r.automatic_maps_kept;
  d["given_maps_distortion"] = r.given_maps_distortion;
  d["automatic_maps_distortion"] = r.automatic_maps_distortion;
  d["refined"] = r.refined;
  d["termination"] = smc::to_string(r.termination);
  d["decisions"] = r.decisions;
  d["irregularities_1"] = irregularities_dict(r.irregularities_1);
  d["irregularities_2"] = irregularities_dict(r.irregularities_2);
  py::dict selection;
  selection["refined_more_consistent"] = r.selection.refined_more_consistent;
  selection["refined_fraction_12"] = r.selection.refined_fraction_12;
  selection["refined_fraction_21"] = r.selection.refined_fraction_21;
  selection["input_distortion"] = r.selection.input_distortion;
  selection["refined_distortion"] = r.selection.refined_distortion;
  selection["selected_distortion"] = r.selection.selected_distortion;
  selection["inconsistent_input"] = r.selection.inconsistent_input;
  selection["inconsistent_refined"] = r.selection.inconsistent_refined;
  selection["inconsistent_selected"] = r.selection.inconsistent_selected;
  d["selection"] = selection;
  d["inconsistent_vertices_before"] = r.inconsistent_vertices_before;
  d["inconsistent_vertices_after"] = r.inconsistent_vertices_after;
  d["cycle_error_before"] = r.cycle_error_before;
  d["cycle_error_after"] = r.cycle_error_after;
  d["distortion_before"] = r.distortion_before;
  d["distortion_after"] = r.distortion_after;
  if(r.diagnostics.computed) d["diagnostics"] = diagnostics_dict(r.diagnostics);
  py::dict confidence;
  confidence["score"] = r.confidence.score;
  confidence["score_12"] = r.confidence.direction_scores[0];
  confidence["score_21"] = r.confidence.direction_scores[1];
  confidence["low"] = r.confidence.low;
  confidence["reason"] = r.confidence.reason;
  d["confidence"] = confidence;
  py::dict stages;
  for(int s = 0; s <= int(smc::Matching_stage::selection); ++s)
    stages[smc::to_string(smc::Matching_stage(s))] = r.stage_seconds[std::size_t(s)];
  stages["total"] = r.total_seconds;
  d["stage_seconds"] = stages;
  py::list steps;
  for(const smc::Refinement_step& s : r.refinement.steps)
  {
    py::dict step;
    step["outer_iteration"] = s.outer_iteration;
    step["direction"] = s.direction == 0 ? "1->2" : "2->1";
    step["rings"] = s.rings;
    step["energy"] = s.energy;
    step["lower_bound"] = s.lower_bound;
    step["trws_iterations"] = s.trws_iterations;
    step["changed_vertices"] = s.changed_vertices;
    step["inconsistent_vertices"] = s.inconsistent_vertices;
    steps.append(step);
  }
  py::dict refinement;
  refinement["outer_iterations"] = r.refinement.outer_iterations;
  refinement["kept_outer_iterations"] = r.refinement.kept_outer_iterations;
  refinement["steps"] = steps;
  d["refinement"] = refinement;
  d["unrefined_map_12"] = index_array(r.unrefined_map_12);
  d["unrefined_map_21"] = index_array(r.unrefined_map_21);
  return d;
}

// ------------------------------------------------------------------------------ running

/// The settings of a run, by registry name (values already canonical: bool, float, str, lists of
/// floats, lists of lists of floats).
typedef std::map<std::string, smc::Setting_value> Settings_dict;

smc::Matching_settings matching_settings(const Settings_dict& given)
{
  smc::Matching_settings settings;
  for(const auto& [name, value] : given) settings.set(name, value);
  return settings;
}

/// The settings a settings file sets (its null entries left out: they keep the defaults).
Settings_dict read_settings(const std::string& file)
{
  Settings_dict out;
  for(const smc::Settings_file_entry& e : smc::read_settings_file(file))
    if(e.value) out[e.name] = *e.value;
  return out;
}

/// The visitor of a run from Python: forwards the stages' progress to the callback (with the
/// GIL) and stops the run when the callback returns False or raises, or when Ctrl-C was pressed.
class Python_visitor : public smc::Default_matching_visitor
{
public:
  explicit Python_visitor(py::object callback) : callback_(std::move(callback)) {}

  bool stage_begun(smc::Matching_stage s) { return event(s, 0.0); }
  bool progress(smc::Matching_stage s, double fraction) { return event(s, fraction); }
  bool stage_ended(smc::Matching_stage s, double) { return event(s, 1.0); }
  bool trws_iteration(int, std::size_t, double, double) { return !interrupted; }
  bool refinement_step(const smc::Refinement_step&) { return !interrupted; }

  std::atomic<bool> interrupted{false};
  bool stopped_by_callback = false;
  std::optional<py::error_already_set> callback_error;

private:
  bool event(smc::Matching_stage s, double fraction)
  {
    if(interrupted) return false;
    if(callback_.is_none()) return true;
    py::gil_scoped_acquire gil;
    try
    {
      const py::object answer = callback_(smc::to_string(s), fraction);
      if(answer.is(py::bool_(false)))
      {
        stopped_by_callback = true;
        return false;
      }
    }
    catch(py::error_already_set& e)
    {
      callback_error.emplace(std::move(e));
      return false;
    }
    return true;
  }

  py::object callback_;
};

/// Runs `f()` (a matching call, with the GIL held by the caller) on another thread, in an arena of
/// `threads` threads (0: every core), while this thread waits without the GIL and checks for
/// Ctrl-C every 50 ms: Ctrl-C stops the run at its next event and raises KeyboardInterrupt; a
/// callback that returned False raises comap.Stopped, one that raised re-raises its exception.
template <typename F>
auto run_from_python(Python_visitor& visitor, int threads, const F& f) -> decltype(f())
{
  decltype(f()) result{};
  std::exception_ptr error;
  std::optional<py::error_already_set> interrupt;
  {
    py::gil_scoped_release release;
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::thread worker([&] {
      try
      {
#ifdef CGAL_LINKED_WITH_TBB
        if(threads > 0)
        {
          tbb::task_arena arena(threads);
          arena.execute([&] { result = f(); });
        }
        else
          result = f();
#else
        (void)threads;
        result = f();
#endif
      }
      catch(...)
      {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_all();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while(!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; }))
    {
      if(interrupt) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if(PyErr_CheckSignals() != 0)
        {
          interrupt.emplace();
          visitor.interrupted = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if(interrupt) throw *interrupt;
  if(visitor.callback_error) throw *visitor.callback_error;
  if(error) std::rethrow_exception(error);
  return result;
}

/// The landmark pairs of a (k, 2) array.
std::vector<std::pair<std::size_t, std::size_t> > landmark_pairs(const std::optional<Index_array>& landmarks)
{
  std::vector<std::pair<std::size_t, std::size_t> > pairs;
  if(!landmarks) return pairs;
  const auto l = landmarks->unchecked<2>();
  for(py::ssize_t k = 0; k < l.shape(0); ++k)
  {
    if(l(k, 0) < 0 || l(k, 1) < 0)
      throw smc::Invalid_parameter_error("landmark " + std::to_string(k) + " (" + std::to_string(l(k, 0)) + ", " +
                                         std::to_string(l(k, 1)) + ") has a negative vertex index");
    pairs.emplace_back(std::size_t(l(k, 0)), std::size_t(l(k, 1)));
  }
  return pairs;
}

py::tuple match(const Points_array& v1, const Index_array& f1, const Points_array& v2, const Index_array& f2,
                const std::optional<std::pair<Index_array, Index_array> >& init, const std::optional<Index_array>& landmarks,
                const Settings_dict& settings_dict, int threads, py::object progress)
{
  const smc::Triangle_soup m1 = soup_of_arrays(v1, f1, "mesh 1");
  const smc::Triangle_soup m2 = soup_of_arrays(v2, f2, "mesh 2");
  const std::size_t n1 = m1.number_of_vertices(), n2 = m2.number_of_vertices();
  const std::vector<std::pair<std::size_t, std::size_t> > pairs = landmark_pairs(landmarks);
  const smc::Matching_settings settings = matching_settings(settings_dict);
  smc::Vertex_index_map_vector x12, x21;
  Python_visitor visitor(std::move(progress));
  const auto np = smc::parameters::matching_settings(
      settings, smc::parameters::landmarks(pairs, smc::parameters::visitor(std::ref(visitor))));
  smc::Matching_result r;
  if(init)
  {
    const smc::Vertex_index_map_vector a = checked_map(init->first, n1, n2, "init[0] (the map 1 -> 2)"),
                                       b = checked_map(init->second, n2, n1, "init[1] (the map 2 -> 1)");
    r = run_from_python(visitor, threads, [&] {
      return smc::match_shapes<Concurrency>(m1, m2, x12, x21, smc::parameters::initial_maps(a, b, np));
    });
  }
  else
    r = run_from_python(visitor, threads, [&] { return smc::match_shapes<Concurrency>(m1, m2, x12, x21, np); });
  return py::make_tuple(index_array(x12), index_array(x21), result_dict(r));
}

// ------------------------------------------------------------------------------ prepared shapes

smc::Vertex_index_map_vector index_vector(const Index_array& a, const std::string& what)
{
  const auto m = a.unchecked<1>();
  smc::Vertex_index_map_vector out(std::size_t(m.shape(0)));
  for(py::ssize_t i = 0; i < m.shape(0); ++i)
  {
    if(m(i) < 0)
      throw smc::Invalid_map_error(what + ": entry " + std::to_string(i) + " is " + std::to_string(m(i)) +
                                   ", not a vertex index");
    out[std::size_t(i)] = std::size_t(m(i));
  }
  return out;
}


typedef smc::Correspondence_shape<smc::Triangle_soup, Concurrency> Correspondence_shape;

/// A shape prepared once (spectrum, descriptors, distance oracle, the initialisation's data) for
/// matching against many.
struct Shape
{
  smc::Triangle_soup mesh;
  std::unique_ptr<Correspondence_shape> shape;

  Shape(const Points_array& v, const Index_array& f, const std::string& n, const Settings_dict& settings, int threads)
      : mesh(soup_of_arrays(v, f, n))
  {
    const smc::Matching_settings s = matching_settings(settings);
    Python_visitor visitor{py::none()};
    shape = run_from_python(visitor, threads, [&] {
      return std::make_unique<Correspondence_shape>(mesh, smc::parameters::matching_settings(s), n);
    });
  }
  std::size_t number_of_vertices() const { return shape->number_of_vertices(); }
  py::dict preparation_seconds() const
  {
    const smc::Shape_preprocessing_times& t = shape->preprocessing_times();
    py::dict d;
    d["mesh"] = t.mesh;
    d["spectrum"] = t.spectrum;
    d["descriptors"] = t.descriptors;
    d["distances"] = t.distances;
    d["initialization"] = t.initialization;
    d["total"] = t.total();
    return d;
  }
};

py::tuple match_prepared(const Shape& s1, const Shape& s2, const std::optional<std::pair<Index_array, Index_array> >& init,
                         const std::optional<Index_array>& landmarks, const Settings_dict& settings_dict, int threads,
                         py::object progress)
{
  const std::vector<std::pair<std::size_t, std::size_t> > pairs = landmark_pairs(landmarks);
  const smc::Matching_settings settings = matching_settings(settings_dict);
  smc::Vertex_index_map_vector x12, x21;
  Python_visitor visitor(std::move(progress));
  const auto np = smc::parameters::matching_settings(
      settings, smc::parameters::landmarks(pairs, smc::parameters::visitor(std::ref(visitor))));
  smc::Matching_result r;
  if(init)
  {
    const smc::Vertex_index_map_vector a = index_vector(init->first, "init[0] (the map 1 -> 2)"),
                                       b = index_vector(init->second, "init[1] (the map 2 -> 1)");
    r = run_from_python(visitor, threads, [&] {
      return smc::match_shapes<Concurrency>(*s1.shape, *s2.shape, x12, x21, smc::parameters::initial_maps(a, b, np));
    });
  }
  else
    r = run_from_python(visitor, threads,
                        [&] { return smc::match_shapes<Concurrency>(*s1.shape, *s2.shape, x12, x21, np); });
  return py::make_tuple(index_array(x12), index_array(x21), result_dict(r));
}

/// The registry: one dict per setting, in registry order.
py::list settings_registry()
{
  py::list out;
  for(const smc::Setting_info& i : smc::matching_settings_registry())
  {
    py::dict d;
    d["name"] = i.name;
    d["type"] = i.type;
    d["default"] = i.default_text;
    d["default_for_given_maps"] = i.given_default_text;
    d["range"] = i.range_text;
    d["stage"] = smc::to_string(i.stage);
    d["documentation"] = i.documentation;
    out.append(d);
  }
  return out;
}

// ------------------------------------------------------------------------------ files

py::tuple read_mesh(const std::string& file)
{
  std::vector<Kernel::Point_3> points;
  smc::Soup_polygons polygons;
  smc::Triangle_soup_origin origin;
  {
    py::gil_scoped_release release;
    smc::read_triangle_soup(file, points, polygons, origin);
    smc::inspect_triangle_soup(smc::Triangle_soup(points, polygons, origin));
  }
  py::array_t<double> v({py::ssize_t(points.size()), py::ssize_t(3)});
  auto pv = v.mutable_unchecked<2>();
  for(std::size_t i = 0; i < points.size(); ++i)
    for(int c = 0; c < 3; ++c) pv(py::ssize_t(i), c) = points[i][c];
  py::array_t<std::int64_t> f({py::ssize_t(polygons.size()), py::ssize_t(3)});
  auto pf = f.mutable_unchecked<2>();
  for(std::size_t k = 0; k < polygons.size(); ++k)
    for(int c = 0; c < 3; ++c) pf(py::ssize_t(k), c) = std::int64_t(polygons[k][std::size_t(c)]);
  return py::make_tuple(v, f);
}

py::array_t<std::int64_t> read_map(const std::string& file, int index_base)
{
  smc::Vertex_index_map_vector map;
  {
    py::gil_scoped_release release;
    map = smc::read_vertex_indices(file, index_base);
  }
  return index_array(map);
}

void write_map(const std::string& file, const Index_array& map, int index_base)
{
  const smc::Vertex_index_map_vector m = index_vector(map, "map");
  py::gil_scoped_release release;
  smc::write_vertex_indices(file, m, index_base);
}

// ------------------------------------------------------------------------------ evaluation

py::array_t<double> double_array(const std::vector<double>& v)
{
  py::array_t<double> out(py::ssize_t(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

py::array_t<double> geodesic_errors(const Points_array& v, const Index_array& f, const Index_array& map,
                                    const Index_array& gt_source, const Index_array& gt_target,
                                    const std::optional<Index_array>& gt_symmetric)
{
  const smc::Triangle_soup target = soup_of_arrays(v, f, "the target mesh");
  const smc::Vertex_index_map_vector m = index_vector(map, "map"), s = index_vector(gt_source, "gt_source"),
                                     t = index_vector(gt_target, "gt_target");
  smc::Vertex_index_map_vector sym;
  if(gt_symmetric) sym = index_vector(*gt_symmetric, "gt_target_symmetric");
  smc::Error_statistics e;
  {
    py::gil_scoped_release release;
    const smc::Map_evaluator<Concurrency> evaluator(target);
    e = gt_symmetric ? evaluator.symmetric_geodesic_errors(m, s, t, sym) : evaluator.geodesic_errors(m, s, t);
  }
  return double_array(e.errors);
}

py::array_t<double> cycle_errors(const Points_array& v, const Index_array& f, const Index_array& map_12,
                                 const Index_array& map_21)
{
  const smc::Triangle_soup source = soup_of_arrays(v, f, "the source mesh");
  const smc::Vertex_index_map_vector a = index_vector(map_12, "map_12"), b = index_vector(map_21, "map_21");
  smc::Cycle_consistency c;
  {
    py::gil_scoped_release release;
    c = smc::Map_evaluator<Concurrency>(source).cycle_consistency(a, b);
  }
  return double_array(c.distances.errors);
}

double coverage(const Index_array& map, std::size_t target_vertices)
{
  return smc::map_coverage(index_vector(map, "map"), target_vertices);
}

std::size_t inconsistent_vertices(const Index_array& map_12, const Index_array& map_21)
{
  const smc::Vertex_index_map_vector a = index_vector(map_12, "map_12"), b = index_vector(map_21, "map_21");
  smc::check_vertex_map(a, a.size(), b.size(), "map_12");
  smc::check_vertex_map(b, b.size(), a.size(), "map_21");
  return smc::number_of_inconsistent_vertices(a, b);
}

} // namespace

PYBIND11_MODULE(_comap, m)
{
  m.doc() = "The C++ half of the comap package (see comap.match).";
  static py::exception<smc::Matching_stopped> stopped(m, "Stopped", PyExc_RuntimeError);
  // The library's exceptions: bad input is a ValueError, files an OSError, the rest a RuntimeError;
  // the message is the library's.
  py::register_exception_translator([](std::exception_ptr p) {
    try
    {
      if(p) std::rethrow_exception(p);
    }
    catch(const smc::IO_error& e)
    {
      PyErr_SetString(PyExc_OSError, e.what());
    }
    catch(const smc::Matching_stopped& e)
    {
      PyErr_SetString(stopped.ptr(), e.what());
    }
    catch(const smc::Invalid_mesh_error& e)
    {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
    catch(const smc::Invalid_map_error& e)
    {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
    catch(const smc::Invalid_parameter_error& e)
    {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def("match", &match, py::arg("V1"), py::arg("F1"), py::arg("V2"), py::arg("F2"), py::arg("init"),
        py::arg("landmarks"), py::arg("settings"), py::arg("threads"), py::arg("progress"),
        "match(V1, F1, V2, F2, init, landmarks, settings, threads, progress) -> (map_12, map_21, info): see "
        "comap.match.");
  m.def("settings_registry", &settings_registry);
  m.def("read_settings", &read_settings, py::arg("file"));
  m.def("check_settings", [](const Settings_dict& settings) { matching_settings(settings); }, py::arg("settings"));
  py::class_<Shape>(m, "Shape")
      .def(py::init<const Points_array&, const Index_array&, const std::string&, const Settings_dict&, int>(),
           py::arg("V"), py::arg("F"), py::arg("name"), py::arg("settings"), py::arg("threads"))
      .def_property_readonly("number_of_vertices", &Shape::number_of_vertices)
      .def_property_readonly("preparation_seconds", &Shape::preparation_seconds);
  m.def("match_shapes", &match_prepared, py::arg("shape_1"), py::arg("shape_2"), py::arg("init"),
        py::arg("landmarks"), py::arg("settings"), py::arg("threads"), py::arg("progress"));
  m.def("read_mesh", &read_mesh, py::arg("file"));
  m.def("read_map", &read_map, py::arg("file"), py::arg("index_base"));
  m.def("write_map", &write_map, py::arg("file"), py::arg("map"), py::arg("index_base"));
  m.def("geodesic_errors", &geodesic_errors, py::arg("V"), py::arg("F"), py::arg("map"), py::arg("gt_source"),
        py::arg("gt_target"), py::arg("gt_target_symmetric") = py::none());
  m.def("cycle_errors", &cycle_errors, py::arg("V"), py::arg("F"), py::arg("map_12"), py::arg("map_21"));
  m.def("coverage", &coverage, py::arg("map"), py::arg("target_vertices"));
  m.def("inconsistent_vertices", &inconsistent_vertices, py::arg("map_12"), py::arg("map_21"));
  m.attr("has_tbb") =
#ifdef CGAL_LINKED_WITH_TBB
      true;
#else
      false;
#endif
}
