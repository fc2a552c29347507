// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap bench: the coupled refinement (or the whole automatic pipeline) on every pair of a
// benchmark dataset laid out like /work/shared/data/FAUST_r and TOSCA_r:
//   DIR/off/NAME.off, DIR/corres/NAME.vts (and NAME.sym.vts), a pairs file (two names per line,
//   tab separated), initial maps INIT/A_B.map and INIT/B_A.map (1-based).
// Both directions of a pair come from one coupled refinement. Outputs: the refined maps, a CSV
// with one row per direction, a JSON summary, the cumulative curves as CSV and SVG plots.

#include "comap_commands.h"
#include "comap_report.h"
#include "comap_settings.h"
#include "comap_svg.h"

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <limits>
#include <list>
#include <map>
#include <mutex>
#include <numeric>
#include <thread>

namespace comap {

namespace {

struct Bench_options
{
  std::string data, pairs, init, out, compare, label;
  int jobs = 1, limit = 0, cache = 0, ground_truth_landmarks = 0;
  bool verbose = false;
};

/// A prepared dataset shape (the library's Correspondence_shape) with its ground truth.
struct Bench_shape
{
  smc::Triangle_soup mesh;
  std::unique_ptr<Shape> shape;
  std::unique_ptr<Evaluator> evaluator;
  Vertex_map vts, sym;  ///< sym empty when the dataset has no .sym.vts
  double preparation_seconds = 0;
  std::size_t number_of_vertices() const { return mesh.number_of_vertices(); }
};

/// `count` landmarks from the ground truth of a pair: the ground-truth samples of `a` spread by
/// farthest-point sampling (Euclidean, from the first sample), each with its ground-truth match in
/// `b`, as (vertex of a, vertex of b).
std::vector<std::pair<std::size_t, std::size_t> > ground_truth_landmarks(const Bench_shape& a, const Bench_shape& b,
                                                                         int count)
{
  std::vector<std::pair<std::size_t, std::size_t> > out;
  const std::size_t n = std::min(a.vts.size(), b.vts.size());
  if(count <= 0 || n == 0) return out;
  const auto& points = a.mesh.points();
  auto distance = [&](std::size_t i, std::size_t j) {
    const auto& p = points[a.vts[i]];
    const auto& q = points[a.vts[j]];
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
  };
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  for(std::size_t next = 0; out.size() < std::min(n, std::size_t(count));)
  {
    out.emplace_back(a.vts[next], b.vts[next]);
    for(std::size_t i = 0; i < n; ++i) nearest[i] = std::min(nearest[i], distance(i, next));
    next = std::size_t(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
  }
  return out;
}

/// Prepared shapes shared by the jobs, at most `capacity` of them kept once unused (least
/// recently used first out). A shape asked for while another job prepares it is waited for.
class Shape_cache
{
public:
  typedef std::shared_ptr<const Bench_shape> Pointer;
  Shape_cache(std::size_t capacity, std::function<Pointer(const std::string&)> make)
      : capacity_(std::max<std::size_t>(capacity, 2)), make_(std::move(make))
  {}

  Pointer get(const std::string& name)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    auto it = entries_.find(name);
    if(it != entries_.end())
    {
      lru_.splice(lru_.begin(), lru_, it->second.second);
      std::shared_future<Pointer> f = it->second.first;
      lock.unlock();
      return f.get();
    }
    std::promise<Pointer> promise;
    std::shared_future<Pointer> f = promise.get_future().share();
    lru_.push_front(name);
    entries_[name] = std::make_pair(f, lru_.begin());
    while(entries_.size() > capacity_)
    {
      entries_.erase(lru_.back());  // users hold their own pointers
      lru_.pop_back();
    }
    lock.unlock();
    try
    {
      promise.set_value(make_(name));
    }
    catch(...)
    {
      promise.set_exception(std::current_exception());
    }
    return f.get();
  }

private:
  std::size_t capacity_;
  std::function<Pointer(const std::string&)> make_;
  std::mutex mutex_;
  std::list<std::string> lru_;
  std::map<std::string, std::pair<std::shared_future<Pointer>, std::list<std::string>::iterator> > entries_;
};

/// The quality of one map (one direction of a pair).
struct Map_quality
{
  smc::Error_statistics errors, symmetric;
  bool has_symmetric = false;
  smc::Cycle_consistency cycle;  ///< x -> back(forth(x)) on the source
  double coverage = 0;
};

struct Direction_result
{
  std::string source, target;
  /// The initial maps (given, or automatic), the maps that entered the refinement (the automatic
  /// maps, or the given maps after the repair and the comparison) and the final maps.
  Map_quality initial, unrefined, refined;
  /// The library's ground-truth-free diagnostics of the unrefined and the final maps, and the
  /// mean ground-truth error of each of their regions (NaN: no ground-truth sample in the region).
  bool has_diagnostics = false;
  double confidence = 1;  ///< the library's confidence score of the final map
  smc::Direction_diagnostics diagnostics_before, diagnostics_after;
  std::vector<double> region_error_before, region_error_after;
};

/// The mean error of the ground-truth samples of each region of the source (`gt_source[k]` is the
/// source vertex of sample k).
std::vector<double> region_errors(const smc::Error_statistics& e, const Vertex_map& gt_source,
                                  const std::vector<int>& regions, std::size_t count)
{
  std::vector<double> sum(count, 0.0), n(count, 0.0);
  for(std::size_t k = 0; k < e.errors.size() && k < gt_source.size(); ++k)
  {
    const std::size_t r = std::size_t(regions[gt_source[k]]);
    sum[r] += e.errors[k];
    n[r] += 1;
  }
  for(std::size_t r = 0; r < count; ++r) sum[r] = n[r] > 0 ? sum[r] / n[r] : std::numeric_limits<double>::quiet_NaN();
  return sum;
}

/// How well each ground-truth-free diagnostic tells the maps (or regions) that the refinement made
/// worse from those it made better: "worse" and "better" by the ground-truth error, changed by
/// more than 0.002; a diagnostic says "worse" when its value rose.
struct Diagnostic_separation
{
  static constexpr std::size_t measures = 8;
  static const char* name(std::size_t k)
  {
    static const char* names[measures] = {
        "inconsistent_fraction", "cycle_error",          "distortion",
        "global_distortion",     "descriptor_distance",  "orientation_reversal",
        "global_orientation_reversal", "energy"};
    return names[k];
  }
  static double value(const smc::Map_diagnostics& d, std::size_t k)
  {
    const double v[measures] = {d.inconsistent_fraction, d.cycle_error,         d.distortion,
                                d.global_distortion,     d.descriptor_distance, d.orientation_reversal,
                                d.global_orientation_reversal, d.energy};
    return v[k];
  }
  std::size_t worse = 0, better = 0;
  std::array<std::size_t, measures> worse_flagged{}, better_recognised{};

  void add(double error_before, double error_after, const smc::Map_diagnostics& before,
           const smc::Map_diagnostics& after)
  {
    if(!(std::isfinite(error_before) && std::isfinite(error_after))) return;
    const bool is_worse = error_after > error_before + 0.002, is_better = error_after < error_before - 0.002;
    if(!is_worse && !is_better) return;
    (is_worse ? worse : better) += 1;
    for(std::size_t k = 0; k < measures; ++k)
    {
      const double b = value(before, k), a = value(after, k);
      if(is_worse) worse_flagged[k] += a > b;
      else better_recognised[k] += a < b;
    }
  }
  static double share(std::size_t part, std::size_t whole) { return whole > 0 ? double(part) / double(whole) : 0.0; }
  void write(Json_writer& json, const std::string& key) const
  {
    json.begin_object(key).value("worse", worse).value("better", better);
    for(std::size_t k = 0; k < measures; ++k)
      json.begin_object(name(k))
          .value("worse_flagged", share(worse_flagged[k], worse))
          .value("better_recognised", share(better_recognised[k], better))
          .end_object();
    json.end_object();
  }
};

struct Pair_result
{
  std::size_t index = 0;
  std::string a, b;
  bool ok = false;
  std::string error;
  Direction_result direction[2];
  std::size_t inconsistent_before = 0, inconsistent_after = 0;
  int outer_iterations = 0, kept_iterations = 0;
  int repair_passes = 0;                          ///< tear repair passes kept
  double torn_fraction_before = 0, torn_fraction = 0;
  int extremity_hypotheses = 0, extremity_hypothesis = 0;  ///< tried and kept (0: none)
  int automatic_maps_kept = -1;                   ///< given maps: 1 when the automatic maps replaced them
  double given_maps_distortion = -1, automatic_maps_distortion = -1;  ///< given maps (-1: not computed)
  bool refined_as_automatic = false;              ///< the refinement used the defaults for automatic maps
  double refined_fraction_12 = 1, refined_fraction_21 = 1;  ///< the selection
  std::string termination;
  double preprocessing_seconds = 0, initialization_seconds = 0, data_preparation_seconds = 0, trws_seconds = 0,
         refinement_seconds = 0, selection_seconds = 0, evaluation_seconds = 0, match_seconds = 0;
  void set(const smc::Matching_result& m)
  {
    using smc::Matching_stage;
    initialization_seconds = m.seconds(Matching_stage::initialization) + m.seconds(Matching_stage::repair) +
                             m.seconds(Matching_stage::comparison);
    repair_passes = m.repair_passes;
    torn_fraction_before = m.initialization.torn_fraction_before;
    torn_fraction = m.initialization.torn_fraction;
    extremity_hypotheses = m.initialization.extremity_hypotheses;
    extremity_hypothesis = m.initialization.extremity_hypothesis;
    automatic_maps_kept = m.compared ? int(m.automatic_maps_kept) : -1;
    given_maps_distortion = m.compared ? m.given_maps_distortion : -1;
    automatic_maps_distortion = m.automatic_maps_computed ? m.automatic_maps_distortion : -1;
    refined_as_automatic = m.refined_maps == smc::Map_origin::automatic;
    refined_fraction_12 = m.selection.refined_fraction_12;
    refined_fraction_21 = m.selection.refined_fraction_21;
    inconsistent_before = m.inconsistent_vertices_before;
    inconsistent_after = m.inconsistent_vertices_after;
    outer_iterations = m.refinement.outer_iterations;
    kept_iterations = m.refinement.kept_outer_iterations;
    termination = smc::to_string(m.termination);
    data_preparation_seconds = m.refinement.data_preparation_seconds;
    trws_seconds = m.refinement.trws_seconds;
    refinement_seconds = m.seconds(Matching_stage::refinement);
    selection_seconds = m.seconds(Matching_stage::selection);
    match_seconds = m.total_seconds;
  }
};

std::vector<std::pair<std::string, std::string> > read_pairs(const std::string& file)
{
  std::ifstream in(file);
  if(!in) throw smc::IO_error("cannot open the pairs file " + file);
  std::vector<std::pair<std::string, std::string> > pairs;
  std::string line;
  std::size_t number = 0;
  while(std::getline(in, line))
  {
    ++number;
    if(!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::string a, b, extra;
    if(!(fields >> a)) continue;  // empty line
    if(a[0] == '#') continue;
    if(!(fields >> b) || (fields >> extra))
      throw smc::IO_error(file + ":" + std::to_string(number) + ": expected two shape names separated by a tab");
    pairs.emplace_back(a, b);
  }
  if(pairs.empty()) throw smc::IO_error(file + ": no pair in this file");
  return pairs;
}

Map_quality evaluate(const Bench_shape& source, const Bench_shape& target, const Vertex_map& forth,
                     const Vertex_map& back)
{
  Map_quality q;
  const Evaluator& on_target = *target.evaluator;
  q.errors = on_target.geodesic_errors(forth, source.vts, target.vts);
  if(!target.sym.empty())
  {
    q.symmetric = on_target.symmetric_geodesic_errors(forth, source.vts, target.vts, target.sym);
    q.has_symmetric = true;
  }
  q.cycle = source.evaluator->cycle_consistency(forth, back);
  q.coverage = smc::map_coverage(forth, target.number_of_vertices());
  return q;
}

double median(std::vector<double> v)
{
  if(v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Means over the directions of every figure of a Map_quality.
struct Aggregate
{
  double error = 0, median_error = 0, within_0025 = 0, within_005 = 0, symmetric_error = 0, cycle = 0,
         fixed_points = 0, coverage = 0;
  std::vector<double> curve, symmetric_curve, cycle_curve;
  std::size_t count = 0;
  std::size_t wrong = 0;  ///< maps whose median error is above 0.25: wrong as a whole
  bool has_symmetric = true;

  void add(const Map_quality& q)
  {
    ++count;
    wrong += q.errors.median > 0.25;
    error += q.errors.mean;
    median_error += q.errors.median;
    within_0025 += q.errors.fraction_below(0.025);
    within_005 += q.errors.fraction_below(0.05);
    symmetric_error += q.has_symmetric ? q.symmetric.mean : 0;
    has_symmetric = has_symmetric && q.has_symmetric;
    cycle += q.cycle.distances.mean;
    fixed_points += q.cycle.fixed_point_fraction;
    coverage += q.coverage;
    accumulate(curve, q.errors.cumulative);
    if(q.has_symmetric) accumulate(symmetric_curve, q.symmetric.cumulative);
    accumulate(cycle_curve, q.cycle.distances.cumulative);
  }
  void finish()
  {
    if(count == 0) return;
    const double c = static_cast<double>(count);
    for(double* x : {&error, &median_error, &within_0025, &within_005, &symmetric_error, &cycle, &fixed_points, &coverage})
      *x /= c;
    for(std::vector<double>* v : {&curve, &symmetric_curve, &cycle_curve})
      for(double& x : *v) x /= c;
  }
  static void accumulate(std::vector<double>& sum, const std::vector<double>& x)
  {
    if(sum.empty()) sum.assign(x.size(), 0.0);
    for(std::size_t i = 0; i < x.size() && i < sum.size(); ++i) sum[i] += x[i];
  }
};

void write_aggregate(Json_writer& json, const std::string& key, const Aggregate& a)
{
  json.begin_object(key)
      .value("mean_error", a.error)
      .value("mean_median_error", a.median_error)
      .value("fraction_within_0.025", a.within_0025)
      .value("fraction_within_0.05", a.within_005)
      .value("wrong_maps", a.wrong);
  if(a.has_symmetric) json.value("mean_symmetric_error", a.symmetric_error);
  json.value("mean_cycle_error", a.cycle)
      .value("fixed_point_fraction", a.fixed_points)
      .value("coverage", a.coverage)
      .end_object();
}

/// Curves of another run (its curves.csv), for the comparison plots.
struct Run_curves
{
  std::string label;
  std::vector<double> thresholds, refined, cycle_after;
};

Run_curves read_run_curves(const std::string& dir)
{
  const std::string file = dir + "/curves.csv";
  std::ifstream in(file);
  if(!in) throw smc::IO_error("--compare: cannot open " + file + " (run comap bench with --out " + dir + " first)");
  Run_curves r;
  std::string line;
  while(std::getline(in, line))
  {
    if(line.rfind("# label: ", 0) == 0)
    {
      r.label = line.substr(9);
      continue;
    }
    if(line.empty() || line[0] == '#' || line[0] == 't') continue;
    const std::vector<std::string> f = split(line, ',');
    if(f.size() < 7) throw smc::IO_error(file + ": malformed line \"" + line + "\"");
    r.thresholds.push_back(std::atof(f[0].c_str()));
    r.refined.push_back(std::atof(f[2].c_str()));
    r.cycle_after.push_back(std::atof(f[6].c_str()));
  }
  if(r.thresholds.empty()) throw smc::IO_error(file + ": no curve in this file");
  if(r.label.empty()) r.label = dir;
  return r;
}

/// The separation table of the standard output (empty when no map or region changed by more
/// than 0.002).
std::string diagnostics_table(const Diagnostic_separation& maps, const Diagnostic_separation& regions)
{
  if(maps.worse + maps.better + regions.worse + regions.better == 0) return "";
  std::ostringstream out;
  auto cell = [](std::size_t part, std::size_t whole) {
    return whole > 0 ? percent(double(part) / double(whole)) : std::string("-");
  };
  out << "ground-truth-free diagnostics, final against unrefined maps: the share of the maps (regions) made worse\n"
      << "by more than 0.002 whose diagnostic rose, and of those made better whose diagnostic fell\n";
  char line[200];
  std::snprintf(line, sizeof(line), "%-28s %-25s %s\n", "", "maps", "regions");
  out << line;
  std::snprintf(line, sizeof(line), "%-28s %-12s %-12s %-12s %s\n", "",
                ("worse " + std::to_string(maps.worse)).c_str(), ("better " + std::to_string(maps.better)).c_str(),
                ("worse " + std::to_string(regions.worse)).c_str(), ("better " + std::to_string(regions.better)).c_str());
  out << line;
  for(std::size_t k = 0; k < Diagnostic_separation::measures; ++k)
  {
    std::snprintf(line, sizeof(line), "%-28s %-12s %-12s %-12s %s\n", Diagnostic_separation::name(k),
                  cell(maps.worse_flagged[k], maps.worse).c_str(), cell(maps.better_recognised[k], maps.better).c_str(),
                  cell(regions.worse_flagged[k], regions.worse).c_str(),
                  cell(regions.better_recognised[k], regions.better).c_str());
    out << line;
  }
  return out.str();
}

} // namespace

int run_bench(int argc, char** argv)
{
  smc::Matching_settings settings;
  Common_options common;
  Bench_options o;
  Option_parser p("bench", "comap bench --data DIR --out DIR [--pairs FILE] [--init DIR] [options]",
                  "Runs match_shapes() on every pair of a benchmark dataset (layout of FAUST_r and TOSCA_r: "
                  "DIR/off/NAME.off, DIR/corres/NAME.vts and NAME.sym.vts, a pairs file with two names per line), "
                  "from the initial maps INIT/A_B.map and INIT/B_A.map (1-based), or from automatic initial maps "
                  "without --init. Evaluates both directions against the ground truth and writes OUT/maps/A_B.map "
                  "and B_A.map (1-based), OUT/pairs.csv (one row per direction), OUT/summary.json, OUT/curves.csv "
                  "and the plots OUT/cumulative_error.svg, OUT/cycle_consistency.svg, OUT/per_pair_error.svg.");
  p.section("Benchmark");
  p.value("--data", "DIR", "the dataset directory (off/, corres/, test_pairs.txt)", "", [&](const std::string& v) { o.data = v; });
  p.value("--pairs", "FILE", "the pairs to run", "DIR/test_pairs.txt", [&](const std::string& v) { o.pairs = v; });
  p.value("--init", "DIR", "initial maps A_B.map and B_A.map, 1-based (default: automatic initialisation)", "",
          [&](const std::string& v) { o.init = v; });
  p.value("--out", "DIR", "output directory (created)", "", [&](const std::string& v) { o.out = v; });
  p.value("--ground-truth-landmarks", "K",
          "automatic initial maps from K landmarks: ground-truth samples of the first shape of each pair spread "
          "by farthest-point sampling, with their ground-truth matches (0: none)",
          "0", [&](const std::string& v) {
            o.ground_truth_landmarks = parse_int("--ground-truth-landmarks", v, 0, 100000);
          });
  p.value("--jobs", "N", "pairs run at once (each on threads / N threads)", "1",
          [&](const std::string& v) { o.jobs = parse_int("--jobs", v, 1, 256); });
  p.value("--limit", "N", "only the first N pairs (0: all)", "0",
          [&](const std::string& v) { o.limit = parse_int("--limit", v, 0, INT_MAX); });
  p.value("--cache", "N", "prepared shapes kept in memory (0: 2 jobs + 2)", "0",
          [&](const std::string& v) { o.cache = parse_int("--cache", v, 0, 100000); });
  p.value("--compare", "DIR", "another run's output directory: its refined curves are added to the plots "
          "(e.g. the non-coupled ablation)", "", [&](const std::string& v) { o.compare = v; });
  p.value("--label", "NAME", "name of this run in the plots", "coupled or non-coupled",
          [&](const std::string& v) { o.label = v; });
  p.flag("--verbose", "a progress line for every MRF solve", [&] { o.verbose = true; });
  p.section("Settings");
  std::vector<std::string> settings_files;
  add_settings_options(p, settings, &settings_files);
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> extra = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(!extra.empty()) throw Usage_error("unexpected argument " + extra.front());
  if(o.data.empty() || o.out.empty()) throw Usage_error("bench needs --data DIR and --out DIR");
  const bool automatic = o.init.empty();
  if(o.label.empty()) o.label = !settings.use_refinement ? "no" : settings.use_coupling ? "coupled" : "non-coupled";
  if(o.pairs.empty()) o.pairs = o.data + "/test_pairs.txt";
  if(!directory_exists(o.data)) throw Input_error("--data: " + o.data + " is not a directory");
  if(!automatic && !directory_exists(o.init)) throw Input_error("--init: " + o.init + " is not a directory");
  if(!automatic && o.ground_truth_landmarks > 0)
    throw Usage_error("--ground-truth-landmarks guide the automatic initial maps: give them or --init, not both");
  // Nothing bench writes under --out may be one of its inputs.
  std::vector<Named_file> inputs = {{"--data", o.data}, {"--pairs", o.pairs}, {"--init", o.init}, {"--compare", o.compare}};
  for(const std::string& f : settings_files) inputs.push_back({"--settings", f});
  std::vector<Named_file> outputs = {{"--out", o.out}};
  for(const char* name : {"maps", "unrefined_maps", "pairs.csv", "summary.json", "curves.csv", "failures.txt",
                          "cumulative_error.svg", "cycle_consistency.svg", "per_pair_error.svg"})
    outputs.push_back({"--out (its " + std::string(name) + ")", o.out + "/" + name});
  check_outputs_are_new(inputs, outputs);
  std::vector<std::pair<std::string, std::string> > pairs = read_pairs(o.pairs);
  if(o.limit > 0 && static_cast<std::size_t>(o.limit) < pairs.size()) pairs.resize(static_cast<std::size_t>(o.limit));
  auto mesh_file = [&](const std::string& name) { return o.data + "/off/" + name + ".off"; };
  auto vts_file = [&](const std::string& name) { return o.data + "/corres/" + name + ".vts"; };
  auto sym_file = [&](const std::string& name) { return o.data + "/corres/" + name + ".sym.vts"; };
  auto map_file = [&](const std::string& dir, const std::string& a, const std::string& b) {
    return dir + "/" + a + "_" + b + ".map";
  };
  // Check every input before the long run.
  for(const auto& pr : pairs)
    for(const std::string& name : {pr.first, pr.second})
    {
      if(!file_exists(mesh_file(name))) throw Input_error("missing mesh " + mesh_file(name) + " (listed in " + o.pairs + ")");
      if(!file_exists(vts_file(name))) throw Input_error("missing ground truth " + vts_file(name));
    }
  if(!automatic)
    for(const auto& pr : pairs)
      for(const std::string& f : {map_file(o.init, pr.first, pr.second), map_file(o.init, pr.second, pr.first)})
        if(!file_exists(f)) throw Input_error("missing initial map " + f);
  Run_curves other;
  if(!o.compare.empty()) other = read_run_curves(o.compare);
  make_directories(o.out + "/maps");
  make_directories(o.out + "/unrefined_maps");

  const Thread_limit limit(common.threads);
  const Progress progress(common.quiet);
  const int threads = common.threads > 0 ? common.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int jobs = std::min<int>(o.jobs, static_cast<int>(pairs.size()));
  const int threads_per_job = std::max(1, threads / jobs);
  const Progress quiet_progress(true);
  const Progress& step_progress = o.verbose ? progress : quiet_progress;
  progress.line("bench: " + std::to_string(pairs.size()) + " pairs of " + o.data +
                (automatic ? ", automatic initial maps" : ", initial maps from " + o.init) +
                (o.ground_truth_landmarks > 0
                     ? " from " + std::to_string(o.ground_truth_landmarks) + " ground-truth landmarks"
                     : std::string()) +
                ", " + o.label +
                " refinement, " + std::to_string(jobs) + " job(s) x " + std::to_string(threads_per_job) + " thread(s)");

  Shape_cache cache(o.cache > 0 ? static_cast<std::size_t>(o.cache) : static_cast<std::size_t>(2 * jobs + 2),
                    [&](const std::string& name) {
                      std::shared_ptr<Bench_shape> s(new Bench_shape);
                      const Stopwatch t;
                      s->mesh = read_mesh_soup(mesh_file(name));
                      s->shape.reset(new Shape(s->mesh, smc::parameters::matching_settings(settings), name));
                      s->preparation_seconds = t.seconds();
                      const std::size_t n = s->number_of_vertices();
                      s->vts = read_correspondences(vts_file(name), 1, n);
                      if(file_exists(sym_file(name))) s->sym = read_correspondences(sym_file(name), 1, n);
                      s->evaluator.reset(new Evaluator(s->mesh));
                      return std::shared_ptr<const Bench_shape>(s);
                    });

  std::vector<Pair_result> results(pairs.size());
  std::atomic<std::size_t> next(0), done(0);
  const Stopwatch wall;
  auto process = [&](std::size_t i) {
    Pair_result& r = results[i];
    r.index = i;
    r.a = pairs[i].first;
    r.b = pairs[i].second;
    try
    {
      const Shape_cache::Pointer A = cache.get(r.a), B = cache.get(r.b);
      if(A->vts.size() != B->vts.size())
        throw Input_error(vts_file(r.a) + " and " + vts_file(r.b) + " have different numbers of samples");
      r.preprocessing_seconds = A->preparation_seconds + B->preparation_seconds;
      Progress_visitor visitor(step_progress, r.a + " - " + r.b + ": ");
      const auto np = smc::parameters::matching_settings(
          settings, smc::parameters::landmarks(ground_truth_landmarks(*A, *B, o.ground_truth_landmarks),
                                               smc::parameters::visitor(std::ref(visitor))));
      Vertex_map m12, m21, g12, g21;
      smc::Matching_result m;
      if(automatic)
        m = smc::match_shapes<Concurrency>(*A->shape, *B->shape, m12, m21, np);
      else
      {
        g12 = read_vertex_map(map_file(o.init, r.a, r.b), 1, A->number_of_vertices(), B->number_of_vertices());
        g21 = read_vertex_map(map_file(o.init, r.b, r.a), 1, B->number_of_vertices(), A->number_of_vertices());
        m = smc::match_shapes<Concurrency>(*A->shape, *B->shape, m12, m21, smc::parameters::initial_maps(g12, g21, np));
      }
      r.set(m);
      Stopwatch eval_watch;
      r.direction[0].source = r.direction[1].target = r.a;
      r.direction[0].target = r.direction[1].source = r.b;
      r.direction[0].unrefined = evaluate(*A, *B, m.unrefined_map_12, m.unrefined_map_21);
      r.direction[1].unrefined = evaluate(*B, *A, m.unrefined_map_21, m.unrefined_map_12);
      r.direction[0].initial = automatic ? r.direction[0].unrefined : evaluate(*A, *B, g12, g21);
      r.direction[1].initial = automatic ? r.direction[1].unrefined : evaluate(*B, *A, g21, g12);
      r.direction[0].refined = evaluate(*A, *B, m12, m21);
      r.direction[1].refined = evaluate(*B, *A, m21, m12);
      if(m.diagnostics.computed)
        for(int d = 0; d < 2; ++d)
        {
          Direction_result& x = r.direction[d];
          const Bench_shape& source = d == 0 ? *A : *B;
          const std::vector<int>& regions = d == 0 ? m.diagnostics.regions_1 : m.diagnostics.regions_2;
          x.has_diagnostics = true;
          x.confidence = m.confidence.direction_scores[std::size_t(d)];
          x.diagnostics_before = m.diagnostics.before[d];
          x.diagnostics_after = m.diagnostics.after[d];
          const std::size_t count = x.diagnostics_before.regions.size();
          x.region_error_before = region_errors(x.unrefined.errors, source.vts, regions, count);
          x.region_error_after = region_errors(x.refined.errors, source.vts, regions, count);
        }
      r.evaluation_seconds = eval_watch.seconds();
      write_vertex_maps(map_file(o.out + "/unrefined_maps", r.a, r.b), m.unrefined_map_12,
                        map_file(o.out + "/unrefined_maps", r.b, r.a), m.unrefined_map_21, 1);
      write_vertex_maps(map_file(o.out + "/maps", r.a, r.b), m12, map_file(o.out + "/maps", r.b, r.a), m21, 1);
      r.ok = true;
    }
    catch(const std::exception& e)
    {
      r.error = one_line(e.what());
    }
    const std::size_t k = ++done;
    std::string line = "[" + std::to_string(k) + "/" + std::to_string(pairs.size()) + "] " + r.a + " - " + r.b + ": ";
    if(r.ok)
      line += "error " + fixed(r.direction[0].unrefined.errors.mean, 4) + " " +
              fixed(r.direction[1].unrefined.errors.mean, 4) + " -> " + fixed(r.direction[0].refined.errors.mean, 4) +
              " " + fixed(r.direction[1].refined.errors.mean, 4) + ", inconsistent " +
              std::to_string(r.inconsistent_before) + " -> " + std::to_string(r.inconsistent_after) + ", refined on " +
              percent(r.refined_fraction_12) + " / " + percent(r.refined_fraction_21) + ", " + duration(r.match_seconds);
    else
      line += "FAILED: " + r.error;
    progress.line(line);
  };
  auto worker = [&] {
#ifdef CGAL_LINKED_WITH_TBB
    tbb::task_arena arena(threads_per_job);
#endif
    for(std::size_t i = next++; i < pairs.size(); i = next++)
    {
#ifdef CGAL_LINKED_WITH_TBB
      arena.execute([&] { process(i); });
#else
      process(i);
#endif
    }
  };
  if(jobs == 1)
    worker();
  else
  {
    std::vector<std::thread> workers;
    for(int j = 0; j < jobs; ++j) workers.emplace_back(worker);
    for(std::thread& t : workers) t.join();
  }
  const double wall_seconds = wall.seconds();

  // ---------------------------------------------------------------- outputs
  Aggregate initial, unrefined, refined;
  std::vector<double> pair_seconds, pair_seconds_with_preprocessing;
  std::size_t failed = 0, worsened = 0, maps = 0;
  Diagnostic_separation map_separation, region_separation;
  // The confidence against the ground truth: wrong maps (median error above 0.25) and the others.
  std::size_t wrong_maps = 0, wrong_flagged = 0, good_maps = 0, good_flagged = 0;
  double initialization_sum = 0, data_sum = 0, trws_sum = 0, refinement_sum = 0, selection_sum = 0;
  {
    smc::Atomic_output_file csv_file(o.out + "/pairs.csv");
    std::ostream& csv = csv_file.stream();
    csv << "pair,direction,source,target,samples,initial_error,unrefined_error,refined_error,initial_median,"
           "refined_median,initial_within_0.025,unrefined_within_0.025,refined_within_0.025,initial_within_0.05,"
           "refined_within_0.05,initial_sym_error,refined_sym_error,initial_cycle_error,unrefined_cycle_error,"
           "refined_cycle_error,initial_fixed_points,refined_fixed_points,initial_coverage,refined_coverage,"
           "inconsistent_before,inconsistent_after,refined_fraction,outer_iterations,kept_iterations,termination,"
           "preprocessing_seconds,initialization_seconds,data_preparation_seconds,trws_seconds,refinement_seconds,"
           "selection_seconds,match_seconds,evaluation_seconds,repair_passes,torn_fraction_before,torn_fraction,"
           "automatic_maps_kept,refined_as_automatic,given_maps_distortion,automatic_maps_distortion";
    csv << ",confidence,extremity_hypotheses,extremity_hypothesis";
    for(const char* phase : {"unrefined", "final"})
      for(std::size_t k = 0; k < Diagnostic_separation::measures; ++k)
        csv << "," << phase << "_" << Diagnostic_separation::name(k);
    csv << "\n";
    for(const Pair_result& r : results)
    {
      if(!r.ok)
      {
        ++failed;
        continue;
      }
      pair_seconds.push_back(r.match_seconds);
      pair_seconds_with_preprocessing.push_back(r.preprocessing_seconds + r.match_seconds);
      initialization_sum += r.initialization_seconds;
      data_sum += r.data_preparation_seconds;
      trws_sum += r.trws_seconds;
      refinement_sum += r.refinement_seconds;
      selection_sum += r.selection_seconds;
      for(int d = 0; d < 2; ++d)
      {
        const Direction_result& x = r.direction[d];
        initial.add(x.initial);
        unrefined.add(x.unrefined);
        refined.add(x.refined);
        ++maps;
        worsened += x.refined.errors.mean > x.unrefined.errors.mean + 0.002;
        const bool wrong = x.refined.errors.median > 0.25, flagged = x.confidence < settings.confidence_threshold;
        (wrong ? wrong_maps : good_maps) += 1;
        (wrong ? wrong_flagged : good_flagged) += flagged;
        if(x.has_diagnostics)
        {
          map_separation.add(x.unrefined.errors.mean, x.refined.errors.mean, x.diagnostics_before.whole,
                             x.diagnostics_after.whole);
          for(std::size_t k = 0; k < x.region_error_before.size(); ++k)
            region_separation.add(x.region_error_before[k], x.region_error_after[k], x.diagnostics_before.regions[k],
                                  x.diagnostics_after.regions[k]);
        }
        auto sym = [](const Map_quality& q) { return q.has_symmetric ? shortest(q.symmetric.mean) : std::string(""); };
        auto optional_value = [](double v) { return v < 0 ? std::string("") : shortest(v); };
        csv << r.a << "_" << r.b << "," << (d == 0 ? "12" : "21") << "," << x.source << "," << x.target << ","
            << x.initial.errors.errors.size() << "," << shortest(x.initial.errors.mean) << ","
            << shortest(x.unrefined.errors.mean) << "," << shortest(x.refined.errors.mean) << ","
            << shortest(x.initial.errors.median) << "," << shortest(x.refined.errors.median) << ","
            << shortest(x.initial.errors.fraction_below(0.025)) << ","
            << shortest(x.unrefined.errors.fraction_below(0.025)) << ","
            << shortest(x.refined.errors.fraction_below(0.025)) << "," << shortest(x.initial.errors.fraction_below(0.05))
            << "," << shortest(x.refined.errors.fraction_below(0.05)) << "," << sym(x.initial) << "," << sym(x.refined)
            << "," << shortest(x.initial.cycle.distances.mean) << "," << shortest(x.unrefined.cycle.distances.mean)
            << "," << shortest(x.refined.cycle.distances.mean) << "," << shortest(x.initial.cycle.fixed_point_fraction)
            << "," << shortest(x.refined.cycle.fixed_point_fraction) << "," << shortest(x.initial.coverage) << ","
            << shortest(x.refined.coverage) << "," << r.inconsistent_before << "," << r.inconsistent_after << ","
            << shortest(d == 0 ? r.refined_fraction_12 : r.refined_fraction_21) << "," << r.outer_iterations << ","
            << r.kept_iterations << "," << r.termination << "," << shortest(r.preprocessing_seconds) << ","
            << shortest(r.initialization_seconds) << "," << shortest(r.data_preparation_seconds) << ","
            << shortest(r.trws_seconds) << "," << shortest(r.refinement_seconds) << ","
            << shortest(r.selection_seconds) << "," << shortest(r.match_seconds) << ","
            << shortest(r.evaluation_seconds) << "," << r.repair_passes << "," << shortest(r.torn_fraction_before)
            << "," << shortest(r.torn_fraction) << ","
            << (r.automatic_maps_kept < 0 ? std::string("") : std::to_string(r.automatic_maps_kept)) << ","
            << int(r.refined_as_automatic) << "," << optional_value(r.given_maps_distortion) << ","
            << optional_value(r.automatic_maps_distortion) << "," << shortest(x.confidence) << ","
            << r.extremity_hypotheses << "," << r.extremity_hypothesis;
        for(const smc::Map_diagnostics* g : {&x.diagnostics_before.whole, &x.diagnostics_after.whole})
          for(std::size_t k = 0; k < Diagnostic_separation::measures; ++k)
            csv << "," << (x.has_diagnostics ? shortest(Diagnostic_separation::value(*g, k)) : std::string(""));
        csv << "\n";
      }
    }
    commit_outputs({&csv_file});
  }
  unrefined.finish();
  initial.finish();
  refined.finish();
  const std::size_t succeeded = results.size() - failed;
  if(failed > 0)
  {
    smc::Atomic_output_file f(o.out + "/failures.txt");
    for(const Pair_result& r : results)
      if(!r.ok) f.stream() << r.a << "\t" << r.b << "\t" << r.error << "\n";
    commit_outputs({&f});
  }
  const std::vector<double> thresholds =
      succeeded > 0 ? results[std::find_if(results.begin(), results.end(), [](const Pair_result& r) { return r.ok; }) -
                              results.begin()]
                          .direction[0]
                          .initial.errors.thresholds
                    : std::vector<double>();
  const std::string init_label = automatic ? "automatic" : o.init.substr(o.init.find_last_of('/') + 1);
  if(succeeded > 0)
  {
    {
      smc::Atomic_output_file curves(o.out + "/curves.csv");
      std::ostream& c = curves.stream();
      c << "# label: " << o.label << "\n"
        << "threshold,initial,refined,initial_symmetric,refined_symmetric,cycle_before,cycle_after\n";
      for(std::size_t k = 0; k < thresholds.size(); ++k)
      {
        auto at = [k](const std::vector<double>& v) { return k < v.size() ? shortest(v[k]) : std::string(""); };
        c << shortest(thresholds[k]) << "," << at(initial.curve) << "," << at(refined.curve) << ","
          << at(initial.symmetric_curve) << "," << at(refined.symmetric_curve) << "," << at(initial.cycle_curve) << ","
          << at(refined.cycle_curve) << "\n";
      }
      commit_outputs({&curves});
    }
    Plot errors;
    errors.title = "Cumulative geodesic error, " + std::to_string(2 * succeeded) + " maps";
    errors.x_label = "geodesic error / sqrt(area)";
    errors.y_label = "fraction of correspondences";
    errors.x_max = thresholds.back();
    errors.series.push_back({"initial (" + init_label + ")", thresholds, initial.curve, series_color(6), true, false});
    errors.series.push_back({"refined (" + o.label + ")", thresholds, refined.curve, series_color(0), false, false});
    if(!o.compare.empty())
      errors.series.push_back({"refined (" + other.label + ")", other.thresholds, other.refined, series_color(1), false, false});
    write_svg(o.out + "/cumulative_error.svg", errors);
    Plot cycle = errors;
    cycle.title = "Cycle consistency: distance from x to T21(T12(x)), " + std::to_string(2 * succeeded) + " maps";
    cycle.x_label = "geodesic distance / sqrt(area)";
    cycle.y_label = "fraction of vertices";
    cycle.series[0].y = initial.cycle_curve;
    cycle.series[1].y = refined.cycle_curve;
    if(!o.compare.empty()) cycle.series[2].y = other.cycle_after;
    write_svg(o.out + "/cycle_consistency.svg", cycle);
    // Per map, sorted by the initial error (the paper's Fig. 13).
    std::vector<std::pair<double, double> > per_map;
    for(const Pair_result& r : results)
      if(r.ok)
        for(int d = 0; d < 2; ++d) per_map.emplace_back(r.direction[d].initial.errors.mean, r.direction[d].refined.errors.mean);
    std::sort(per_map.begin(), per_map.end());
    Plot per_pair;
    per_pair.title = "Mean geodesic error per map, sorted by the initial error";
    per_pair.x_label = "map (pair and direction)";
    per_pair.y_label = "mean geodesic error / sqrt(area)";
    per_pair.x_max = static_cast<double>(per_map.size());
    per_pair.legend_bottom_right = false;
    Plot_series a{"initial (" + init_label + ")", {}, {}, series_color(6), false, false};
    Plot_series b{"refined (" + o.label + ")", {}, {}, series_color(0), false, true};
    double top = 0;
    for(std::size_t i = 0; i < per_map.size(); ++i)
    {
      a.x.push_back(i + 0.5);
      a.y.push_back(per_map[i].first);
      b.x.push_back(i + 0.5);
      b.y.push_back(per_map[i].second);
      top = std::max({top, per_map[i].first, per_map[i].second});
    }
    per_pair.y_max = std::min(0.25, top > 0 ? top * 1.05 : 1.0);
    per_pair.series = {a, b};
    write_svg(o.out + "/per_pair_error.svg", per_pair);
  }
  {
    smc::Atomic_output_file summary(o.out + "/summary.json");
    Json_writer json(summary.stream());
    json.begin_object()
        .value("label", o.label)
        .value("data", o.data)
        .value("pairs_file", o.pairs)
        .value("initial_maps", automatic ? std::string("automatic") : o.init)
        .value("ground_truth_landmarks", o.ground_truth_landmarks)
        .value("pairs", succeeded)
        .value("maps", 2 * succeeded)
        .value("failed_pairs", failed);
    write_settings(json, "settings", settings, automatic ? smc::Map_origin::automatic : smc::Map_origin::given);
    write_aggregate(json, "initial", initial);
    write_aggregate(json, "unrefined", unrefined);
    json.value("fraction_worsened_by_more_than_0.002", maps > 0 ? double(worsened) / double(maps) : 0.0);
    write_aggregate(json, "refined", refined);
    json.begin_object("confidence")
        .value("threshold", settings.confidence_threshold)
        .value("wrong_maps", wrong_maps)
        .value("wrong_maps_flagged", wrong_flagged)
        .value("good_maps", good_maps)
        .value("good_maps_flagged", good_flagged)
        .end_object();
    json.begin_object("diagnostics_separation");
    map_separation.write(json, "maps");
    region_separation.write(json, "regions");
    json.end_object();
    const double n = succeeded > 0 ? static_cast<double>(succeeded) : 1.0;
    json.begin_object("timings")
        .value("median_seconds_per_pair", median(pair_seconds))
        .value("median_seconds_per_pair_with_preprocessing", median(pair_seconds_with_preprocessing))
        .value("mean_initialization_seconds", initialization_sum / n)
        .value("mean_data_preparation_seconds", data_sum / n)
        .value("mean_trws_seconds", trws_sum / n)
        .value("mean_refinement_seconds", refinement_sum / n)
        .value("mean_selection_seconds", selection_sum / n)
        .value("wall_seconds", wall_seconds)
        .value("peak_memory_mib", peak_memory_mib())
        .value("jobs", jobs)
        .value("threads_per_job", threads_per_job)
        .end_object();
    json.end_object().finish();
    commit_outputs({&summary});
  }

  std::cout << "comap bench: " << succeeded << " pairs (" << 2 * succeeded << " maps) of " << o.data << ", initial maps: "
            << (automatic ? std::string("automatic") : o.init) << ", " << o.label << " refinement\n"
            << "           mean error  median error  within 0.025  within 0.05"
            << (initial.has_symmetric ? "  sym. error" : "") << "  cycle error  fixed points\n";
  std::vector<std::pair<const char*, const Aggregate*> > rows{{"initial", &initial}};
  if(!automatic) rows.emplace_back("unrefined", &unrefined);
  rows.emplace_back("final", &refined);
  for(const auto& row : rows)
  {
    const Aggregate& g = *row.second;
    char line[200];
    std::snprintf(line, sizeof(line), "%-9s  %10.4f  %12.4f  %12s  %11s", row.first, g.error, g.median_error,
                  percent(g.within_0025).c_str(), percent(g.within_005).c_str());
    std::cout << line;
    if(initial.has_symmetric) std::cout << "  " << std::setw(10) << fixed(g.symmetric_error, 4);
    std::snprintf(line, sizeof(line), "  %11.4f  %12s\n", g.cycle, percent(g.fixed_points).c_str());
    std::cout << line;
  }
  std::cout << "wrong maps (median error above 0.25): " << initial.wrong << " initial, "
            << (automatic ? std::string() : std::to_string(unrefined.wrong) + " unrefined, ") << refined.wrong
            << " final, of " << maps << "\n"
            << "confidence below " << shortest(settings.confidence_threshold) << ": " << wrong_flagged << " of "
            << wrong_maps << " wrong maps, " << good_flagged << " of " << good_maps << " others\n"
            << "maps whose final error exceeds the unrefined maps' error by more than 0.002: " << worsened << " of "
            << maps << " (" << percent(maps > 0 ? double(worsened) / double(maps) : 0.0) << ")\n"
            << diagnostics_table(map_separation, region_separation)
            << "median time per pair: " << duration(median(pair_seconds)) << " (match_shapes() on prepared shapes), "
            << duration(median(pair_seconds_with_preprocessing)) << " with the preparation of both shapes; wall time "
            << duration(wall_seconds) << "; peak memory " << fixed(peak_memory_mib(), 0) << " MiB (the whole run: "
            << jobs << " pair(s) at once and the cache of prepared shapes)\n"
            << "outputs: " << o.out << "/pairs.csv, summary.json, curves.csv, cumulative_error.svg, "
            << "cycle_consistency.svg, per_pair_error.svg, maps/, unrefined_maps/\n";
  if(failed > 0)
    throw Input_error(std::to_string(failed) + " of " + std::to_string(results.size()) + " pairs failed (see " + o.out +
                      "/failures.txt); first: " +
                      std::find_if(results.begin(), results.end(), [](const Pair_result& r) { return !r.ok; })->error);
  return 0;
}

} // namespace comap
