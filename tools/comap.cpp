// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: dense, accurate and cycle-consistent maps between two triangle meshes from the command
// line (Azencot, Dubrovina and Guibas 2019, with automatic initial maps).
//
//   comap match SOURCE TARGET --out-12 FILE --out-21 FILE [--init-12 FILE --init-21 FILE] ...
//   comap eval --source S --target T --map FILE --gt-source FILE --gt-target FILE ...
//   comap transfer --source S --target T --map-12 FILE --out FILE.ply [--texture IMAGE.png]
//   comap bench --data DIR --pairs FILE [--init DIR] --out DIR [--jobs N] [--limit N]
//   comap demo [--out DIR]
//
// See doc/cli.md.

#include "comap_commands.h"
#include "comap_pipeline.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <new>

namespace comap {

void add_common_options(Option_parser& p, Common_options& o)
{
  p.section("General");
  p.flag("--quiet", "no progress lines on stderr", [&o] { o.quiet = true; });
  p.value("--threads", "N", std::string("threads to use (0: all cores)") + (has_tbb ? "" : "; this build has no TBB"),
          "0", [&o](const std::string& v) { o.threads = parse_int("--threads", v, 0, 4096); });
}

Thread_limit::Thread_limit(int threads)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(threads > 0)
    control_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<std::size_t>(threads));
#else
  (void)threads;
#endif
}

Thread_limit::~Thread_limit() = default;

void check_writable(const std::string& file)
{
  const std::size_t slash = file.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : file.substr(0, slash));
  if(!directory_exists(dir)) throw Input_error("cannot write " + file + ": directory " + dir + " does not exist");
  if(::access(dir.c_str(), W_OK) != 0) throw Input_error("cannot write " + file + ": directory " + dir + " is not writable");
  if(directory_exists(file)) throw Input_error("cannot write " + file + ": it is a directory");
}

namespace {

/// Pairs "i j" of vertex indices, one per line ('#' starts a comment), checked against the sizes.
std::vector<std::pair<std::size_t, std::size_t> > read_landmarks(const std::string& file, int index_base,
                                                                 std::size_t n1, std::size_t n2)
{
  std::ifstream in(file);
  if(!in) throw Input_error("cannot open the landmark file " + file);
  std::vector<std::pair<std::size_t, std::size_t> > out;
  std::string line;
  for(int number = 1; std::getline(in, line); ++number)
  {
    const std::string content = line.substr(0, line.find('#'));
    if(content.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(content);
    long long a = 0, b = 0;
    std::string rest;
    if(!(fields >> a >> b) || (fields >> rest))
      throw Input_error(file + ":" + std::to_string(number) + ": expected two vertex indices, found '" + content + "'");
    if(a < index_base || b < index_base || std::size_t(a - index_base) >= n1 || std::size_t(b - index_base) >= n2)
      throw Input_error(file + ":" + std::to_string(number) + ": landmark (" + std::to_string(a) + ", " +
                        std::to_string(b) + ") is out of range (" + std::to_string(index_base) + "-based; " +
                        std::to_string(n1) + " and " + std::to_string(n2) + " vertices)");
    out.emplace_back(std::size_t(a - index_base), std::size_t(b - index_base));
  }
  if(out.empty()) throw Input_error("the landmark file " + file + " has no landmarks");
  return out;
}

std::string index_base_help() { return "index of the first vertex in map and correspondence files (0 or 1)"; }

// ------------------------------------------------------------------------------------ match

int match(int argc, char** argv)
{
  Settings settings;
  Common_options common;
  std::string out_12, out_21, init_12, init_21, stats;
  int index_base = 1;
  bool no_refine = false, repair = false, compare = false;
  Option_parser p("match", "comap match SOURCE TARGET --out-12 FILE --out-21 FILE [options]",
                  "Computes dense point-to-point maps SOURCE -> TARGET and TARGET -> SOURCE: from the given initial maps, "
                  "or from automatic ones (functional maps + ZoomOut), refined jointly by the coupled optimisation of "
                  "Azencot, Dubrovina and Guibas (2019). Meshes: OFF, PLY, OBJ or STL; connected, manifold triangle "
                  "meshes. Map files: one target vertex index per line, line i for source vertex i.");
  p.section("Files");
  p.value("--out-12", "FILE", "output: the map SOURCE -> TARGET", "", [&](const std::string& v) { out_12 = v; });
  p.value("--out-21", "FILE", "output: the map TARGET -> SOURCE", "", [&](const std::string& v) { out_21 = v; });
  p.value("--init-12", "FILE", "initial map SOURCE -> TARGET (default: automatic)", "",
          [&](const std::string& v) { init_12 = v; });
  p.value("--init-21", "FILE", "initial map TARGET -> SOURCE (give both or neither)", "",
          [&](const std::string& v) { init_21 = v; });
  p.value("--index-base", "0|1", index_base_help(), "1",
          [&](const std::string& v) { index_base = parse_int("--index-base", v, 0, 1); });
  p.value("--stats", "FILE.json", "write the parameters, per-step statistics and timings as JSON", "",
          [&](const std::string& v) { stats = v; });
  std::string landmarks_file;
  p.value("--landmarks", "FILE", "known correspondences for the automatic initialisation: one pair of vertex "
          "indices 'SOURCE TARGET' per line (--index-base applies)", "",
          [&](const std::string& v) { landmarks_file = v; });
  p.flag("--no-refine", "write the initial (automatic) maps without refining them", [&] { no_refine = true; });
  p.flag("--repair", "given initial maps: when their tears cut off parts of a mesh (swapped limbs), recompute "
         "them with landmarks from their consistent core (automatic maps are always repaired, see "
         "--init-repair-passes)", [&] { repair = true; });
  p.flag("--compare-automatic", "given initial maps (after the repair with --repair): compare them with the "
         "automatic maps of the pair and keep the less distorted ones (the time of one more initialisation; maps "
         "distorted at most --compare-automatic-above are kept without it)",
         [&] { compare = settings.initialization.compare_with_automatic_maps = true; });
  add_algorithm_options(p, settings, true);
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> files = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(files.size() != 2)
    throw Usage_error("match needs two meshes, SOURCE and TARGET (" + std::to_string(files.size()) + " given)");
  if(out_12.empty() || out_21.empty()) throw Usage_error("match needs --out-12 FILE and --out-21 FILE");
  if(init_12.empty() != init_21.empty()) throw Usage_error("give both --init-12 and --init-21, or neither");
  const bool automatic = init_12.empty();
  if(!automatic && !landmarks_file.empty())
    throw Usage_error("--landmarks guides the automatic initialisation: do not combine it with --init-12/--init-21");
  if(automatic && compare)
    throw Usage_error("--compare-automatic compares given maps (--init-12/--init-21) with the automatic ones");
  const bool repair_step = repair || compare;  // both need the initialisation's data
  check_settings(settings, automatic || repair_step);
  check_writable(out_12);
  check_writable(out_21);
  if(!stats.empty()) check_writable(stats);
  const Thread_limit limit(common.threads);
  const Progress progress(common.quiet);
  const Stopwatch total;

  Stopwatch watch;
  Mesh m1 = read_triangle_mesh(files[0]);
  Mesh m2 = read_triangle_mesh(files[1]);
  const double load_seconds = watch.seconds();
  const std::size_t n1 = num_vertices(m1), n2 = num_vertices(m2);
  progress.line("loaded " + files[0] + " (" + std::to_string(n1) + " vertices, " + std::to_string(num_faces(m1)) +
                " triangles) and " + files[1] + " (" + std::to_string(n2) + " vertices, " +
                std::to_string(num_faces(m2)) + " triangles)");
  if(!landmarks_file.empty())
    settings.initialization.landmarks = read_landmarks(landmarks_file, index_base, n1, n2);
  Vertex_map map_12, map_21;
  if(!automatic)
  {
    map_12 = read_vertex_map(init_12, index_base, n1, n2);
    map_21 = read_vertex_map(init_21, index_base, n2, n1);
  }

  const bool refine = !no_refine;
  const bool initialization_data = automatic || repair_step;
  // Both shapes at once (their eigensolvers are sequential).
  std::unique_ptr<Prepared_shape> s1, s2;
  smc::internal::invoke_both<Concurrency>(
      [&] { s1 = prepare_shape(files[0], std::move(m1), settings, refine, initialization_data, progress); },
      [&] { s2 = prepare_shape(files[1], std::move(m2), settings, refine, initialization_data, progress); });

  smc::Automatic_initialization_result initialization;
  if(automatic)
  {
    progress.line("computing automatic initial maps (functional maps + ZoomOut)");
    initialization = initialize_maps(*s1, *s2, settings, map_12, map_21);
    progress.line("automatic initial maps in " + duration(initialization.total_seconds) + ": cycle fixed points " +
                  percent(initialization.cycle_fixed_fraction) + ", orientation agreement " +
                  percent(initialization.orientation_agreement) + ", " + initialization_summary(initialization));
  }
  else if(repair_step)
  {
    progress.line(!compare ? "repairing the tears of the initial maps"
                  : repair ? "repairing the tears of the initial maps, then comparing them with the automatic maps"
                           : "comparing the initial maps with the automatic maps");
    initialization = repair_maps(*s1, *s2, settings, map_12, map_21, repair);
    progress.line((repair ? "repair in " : "comparison in ") + duration(initialization.total_seconds) + ": " +
                  initialization_summary(initialization));
  }
  // Maps of the automatic initialisation that replaced the given ones (a kept repair pass, or the
  // automatic maps of --compare-automatic) are refined as automatic maps.
  const bool automatic_maps = automatic || repaired_maps_are_automatic(initialization);
  const std::size_t inconsistent_initial = smc::number_of_inconsistent_vertices(map_12, map_21);
  const double coverage_12_initial = smc::map_coverage(map_12, n2), coverage_21_initial = smc::map_coverage(map_21, n1);
  smc::Coupled_refinement_result refinement;
  if(refine)
  {
    const smc::Refinement_settings resolved = resolved_refinement(settings, automatic_maps);
    progress.line("coupled refinement: " + std::to_string(resolved.outer_iterations()) +
                  " outer iterations at most, rings " + join(resolved.ring_schedule) + ", " +
                  std::to_string(resolved.number_of_candidates) + " candidates");
    refinement = refine_maps(*s1, *s2, map_12, map_21, settings, automatic_maps, progress);
    progress.line("refinement done in " + duration(refinement.total_seconds) + " (" +
                  smc::to_string(refinement.termination) + ")");
  }
  write_vertex_map(out_12, map_12, index_base);
  write_vertex_map(out_21, map_21, index_base);
  const double total_seconds = total.seconds();

  if(!stats.empty())
  {
    std::ofstream out(stats);
    if(!out) throw smc::IO_error("cannot open " + stats + " for writing");
    Json_writer json(out);
    json.begin_object().value("command", "match").value("index_base", index_base);
    write_preparation(json, "source", *s1);
    write_preparation(json, "target", *s2);
    write_settings(json, "settings", settings, initialization_data, automatic_maps);
    if(automatic)
      write_initialization(json, "initialization", initialization);
    else
      json.begin_object("initialization").value("map_12", init_12).value("map_21", init_21).end_object();
    if(repair_step) write_initialization(json, "repair", initialization);
    json.begin_object("initial_maps")
        .value("inconsistent_vertices", inconsistent_initial)
        .value("coverage_12", coverage_12_initial)
        .value("coverage_21", coverage_21_initial)
        .end_object();
    if(refine) write_refinement(json, "refinement", refinement);
    json.begin_object("final_maps")
        .value("inconsistent_vertices", smc::number_of_inconsistent_vertices(map_12, map_21))
        .value("coverage_12", smc::map_coverage(map_12, n2))
        .value("coverage_21", smc::map_coverage(map_21, n1))
        .value("map_12", out_12)
        .value("map_21", out_21)
        .end_object();
    json.begin_object("timings")
        .value("loading_seconds", load_seconds)
        .value("preprocessing_seconds", s1->total_seconds + s2->total_seconds)
        .value("initialization_seconds", initialization_data ? initialization.total_seconds : 0.0)
        .value("data_preparation_seconds", refinement.data_preparation_seconds)
        .value("trws_seconds", refinement.trws_seconds)
        .value("refinement_seconds", refinement.total_seconds)
        .value("total_seconds", total_seconds)
        .end_object();
    json.end_object().finish();
    if(!out) throw smc::IO_error("error while writing " + stats);
  }

  std::cout << "source: " << files[0] << " (" << n1 << " vertices)\n"
            << "target: " << files[1] << " (" << n2 << " vertices)\n";
  if(automatic)
    std::cout << "initial maps: automatic (functional maps + ZoomOut) in " << duration(initialization.total_seconds)
              << "\n";
  else
    std::cout << "initial maps: " << init_12 << ", " << init_21
              << (repair_step ? std::string(repair ? ", repaired" : ", compared") + " in " +
                                    duration(initialization.total_seconds) + ": " +
                                    initialization_summary(initialization)
                              : std::string())
              << "\n";
  const std::size_t inconsistent_final = smc::number_of_inconsistent_vertices(map_12, map_21);
  if(refine)
    std::cout << "refinement: " << refinement.kept_outer_iterations << " of " << refinement.outer_iterations
              << " outer iterations kept (" << smc::to_string(refinement.termination) << ")\n";
  std::cout << "inconsistent vertices (T21(T12(x)) != x, both ways): " << inconsistent_initial;
  if(refine) std::cout << " -> " << inconsistent_final;
  std::cout << " of " << (n1 + n2) << "\n"
            << "coverage of the target by map 1->2: " << percent(coverage_12_initial);
  if(refine) std::cout << " -> " << percent(smc::map_coverage(map_12, n2));
  std::cout << "\ntimings: loading " << duration(load_seconds) << ", preprocessing "
            << duration(s1->total_seconds) << " + " << duration(s2->total_seconds);
  if(initialization_data)
    std::cout << (automatic ? ", initialisation " : ", repair ") << duration(initialization.total_seconds);
  if(refine)
    std::cout << ", data preparation " << duration(refinement.data_preparation_seconds) << ", TRW-S "
              << duration(refinement.trws_seconds);
  std::cout << ", total " << duration(total_seconds) << "\n"
            << "wrote " << out_12 << " (" << n1 << " lines) and " << out_21 << " (" << n2 << " lines), "
            << index_base << "-based" << (stats.empty() ? "" : "; statistics in " + stats) << "\n";
  return 0;
}

// ------------------------------------------------------------------------------------- eval

void print_errors(const std::string& title, const smc::Error_statistics& e, const smc::Error_statistics* symmetric)
{
  std::cout << title << ", " << e.errors.size() << " ground-truth samples:\n"
            << "  geodesic error / sqrt(area): mean " << fixed(e.mean, 4) << ", median " << fixed(e.median, 4)
            << ", max " << fixed(e.maximum, 4) << "\n"
            << "  within 0.025: " << percent(e.fraction_below(0.025)) << ", within 0.05: "
            << percent(e.fraction_below(0.05)) << ", within 0.1: " << percent(e.fraction_below(0.1)) << "\n";
  if(symmetric)
    std::cout << "  symmetry-tolerant: mean " << fixed(symmetric->mean, 4) << ", median "
              << fixed(symmetric->median, 4) << ", within 0.05: " << percent(symmetric->fraction_below(0.05)) << "\n";
}

int eval(int argc, char** argv)
{
  Common_options common;
  std::string source, target, map_file, map_21_file, gt_source, gt_target, gt_target_sym, gt_source_sym;
  int index_base = 1;
  bool json_output = false;
  Option_parser p("eval",
                  "comap eval --source S --target T --map FILE --gt-source FILE --gt-target FILE [options]",
                  "Evaluates a map S -> T against ground-truth correspondences: sample k says that vertex gt-source[k] "
                  "of S corresponds to vertex gt-target[k] of T (the .vts files of the FAUST/TOSCA benchmarks). "
                  "Errors are geodesic distances on the target divided by sqrt(area of the target). With --map-21, "
                  "also the map T -> S, cycle consistency, fixed points and coverage.");
  p.section("Files");
  p.value("--source", "MESH", "the source mesh S", "", [&](const std::string& v) { source = v; });
  p.value("--target", "MESH", "the target mesh T", "", [&](const std::string& v) { target = v; });
  p.value("--map", "FILE", "the map S -> T", "", [&](const std::string& v) { map_file = v; });
  p.value("--map-21", "FILE", "the map T -> S (optional)", "", [&](const std::string& v) { map_21_file = v; });
  p.value("--gt-source", "FILE", "ground-truth samples on S", "", [&](const std::string& v) { gt_source = v; });
  p.value("--gt-target", "FILE", "ground-truth samples on T", "", [&](const std::string& v) { gt_target = v; });
  p.value("--gt-target-sym", "FILE", "mirrored ground truth on T, for the symmetry-tolerant error", "",
          [&](const std::string& v) { gt_target_sym = v; });
  p.value("--gt-source-sym", "FILE", "mirrored ground truth on S (symmetry-tolerant error of the map T -> S)", "",
          [&](const std::string& v) { gt_source_sym = v; });
  p.value("--index-base", "0|1", index_base_help(), "1",
          [&](const std::string& v) { index_base = parse_int("--index-base", v, 0, 1); });
  p.flag("--json", "print the results as JSON (with the cumulative curves) instead of text",
         [&] { json_output = true; });
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> extra = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(!extra.empty()) throw Usage_error("unexpected argument " + extra.front());
  for(const auto& required : {std::make_pair(&source, "--source"), std::make_pair(&target, "--target"),
                              std::make_pair(&map_file, "--map"), std::make_pair(&gt_source, "--gt-source"),
                              std::make_pair(&gt_target, "--gt-target")})
    if(required.first->empty()) throw Usage_error(std::string("eval needs ") + required.second + " FILE");
  const Thread_limit limit(common.threads);
  const Progress progress(common.quiet || json_output);

  const Mesh ms = read_triangle_mesh(source), mt = read_triangle_mesh(target);
  const std::size_t ns = num_vertices(ms), nt = num_vertices(mt);
  const Vertex_map map_12 = read_vertex_map(map_file, index_base, ns, nt);
  const Vertex_map gs = read_correspondences(gt_source, index_base, ns);
  const Vertex_map gt = read_correspondences(gt_target, index_base, nt);
  if(gs.size() != gt.size())
    throw Input_error(gt_source + " has " + std::to_string(gs.size()) + " samples but " + gt_target + " has " +
                      std::to_string(gt.size()));
  Vertex_map gt_sym, gs_sym, map_21;
  if(!gt_target_sym.empty()) gt_sym = read_correspondences(gt_target_sym, index_base, nt);
  if(!gt_source_sym.empty()) gs_sym = read_correspondences(gt_source_sym, index_base, ns);
  if(!map_21_file.empty()) map_21 = read_vertex_map(map_21_file, index_base, nt, ns);
  for(const auto& s : {std::make_pair(&gt_sym, &gt_target_sym), std::make_pair(&gs_sym, &gt_source_sym)})
    if(!s.first->empty() && s.first->size() != gt.size())
      throw Input_error(*s.second + " has " + std::to_string(s.first->size()) + " samples but " + gt_target +
                        " has " + std::to_string(gt.size()));

  progress.line("evaluating " + map_file);
  const Evaluator on_target(mt), on_source(ms);
  const smc::Error_statistics e12 = on_target.geodesic_errors(map_12, gs, gt);
  smc::Error_statistics s12, e21, s21;
  if(!gt_sym.empty()) s12 = on_target.symmetric_geodesic_errors(map_12, gs, gt, gt_sym);
  smc::Cycle_consistency c1, c2;
  const bool both = !map_21.empty();
  if(both)
  {
    e21 = on_source.geodesic_errors(map_21, gt, gs);
    if(!gs_sym.empty()) s21 = on_source.symmetric_geodesic_errors(map_21, gt, gs, gs_sym);
    c1 = on_source.cycle_consistency(map_12, map_21);
    c2 = on_target.cycle_consistency(map_21, map_12);
  }

  if(json_output)
  {
    Json_writer json(std::cout);
    json.begin_object().value("source", source).value("target", target);
    json.begin_object("map_12").value("file", map_file).value("coverage", smc::map_coverage(map_12, nt));
    write_error_statistics(json, "errors", e12, true);
    if(!gt_sym.empty()) write_error_statistics(json, "symmetric_errors", s12, true);
    json.end_object();
    if(both)
    {
      json.begin_object("map_21").value("file", map_21_file).value("coverage", smc::map_coverage(map_21, ns));
      write_error_statistics(json, "errors", e21, true);
      if(!gs_sym.empty()) write_error_statistics(json, "symmetric_errors", s21, true);
      json.end_object();
      json.begin_object("cycle_consistency");
      json.begin_object("source").value("fixed_point_fraction", c1.fixed_point_fraction);
      write_error_statistics(json, "distances", c1.distances, true);
      json.end_object();
      json.begin_object("target").value("fixed_point_fraction", c2.fixed_point_fraction);
      write_error_statistics(json, "distances", c2.distances, true);
      json.end_object();
      json.value("inconsistent_vertices", smc::number_of_inconsistent_vertices(map_12, map_21));
      json.end_object();
    }
    json.end_object().finish();
    return 0;
  }
  print_errors("map 1->2 (" + source + " -> " + target + ")", e12, gt_sym.empty() ? nullptr : &s12);
  std::cout << "  coverage: " << percent(smc::map_coverage(map_12, nt)) << " of the target's vertices are hit\n";
  if(both)
  {
    print_errors("map 2->1 (" + target + " -> " + source + ")", e21, gs_sym.empty() ? nullptr : &s21);
    std::cout << "  coverage: " << percent(smc::map_coverage(map_21, ns)) << " of the source's vertices are hit\n"
              << "cycle consistency (geodesic distance from x to T21(T12(x)) / sqrt(area)):\n"
              << "  on the source: mean " << fixed(c1.distances.mean, 4) << ", median " << fixed(c1.distances.median, 4)
              << ", fixed points " << percent(c1.fixed_point_fraction) << "\n"
              << "  on the target: mean " << fixed(c2.distances.mean, 4) << ", median " << fixed(c2.distances.median, 4)
              << ", fixed points " << percent(c2.fixed_point_fraction) << "\n";
  }
  std::cout << "cumulative error curve (fraction of samples with error <= t):\n  t       1->2" << (both ? "    2->1" : "")
            << "\n";
  for(std::size_t k = 0; k < e12.thresholds.size(); k += 10)
  {
    std::cout << "  " << fixed(e12.thresholds[k], 3) << "  " << fixed(e12.cumulative[k], 4);
    if(both) std::cout << "  " << fixed(e21.cumulative[k], 4);
    std::cout << "\n";
  }
  return 0;
}

bool is_command(const std::string& c)
{
  return c == "match" || c == "eval" || c == "transfer" || c == "bench" || c == "demo";
}

void print_usage(std::ostream& out)
{
  out << "usage: comap COMMAND [options]   (comap COMMAND --help for the options)\n\n"
         "Dense, accurate and cycle-consistent maps between triangle meshes (coupled optimisation of\n"
         "Azencot, Dubrovina and Guibas 2019, with automatic initial maps).\n\n"
         "commands:\n"
         "  match      compute the maps SOURCE -> TARGET and TARGET -> SOURCE\n"
         "  eval       evaluate a map against ground-truth correspondences\n"
         "  transfer   colour the source through a map from the target (PLY with vertex colours)\n"
         "  bench      run and evaluate the refinement on a benchmark dataset (FAUST_r, TOSCA_r layout)\n"
         "  demo       the whole pipeline on a mesh from libcgal-demo and a deformed, remeshed copy\n";
}

} // namespace
} // namespace comap

int main(int argc, char** argv)
{
  using namespace comap;
  const std::string command = argc > 1 ? argv[1] : "";
  try
  {
    if(command == "match") return match(argc, argv);
    if(command == "eval") return eval(argc, argv);
    if(command == "transfer") return run_transfer(argc, argv);
    if(command == "bench") return run_bench(argc, argv);
    if(command == "demo") return run_demo(argc, argv);
    if(command == "-h" || command == "--help" || command == "help")
    {
      print_usage(std::cout);
      return 0;
    }
    if(command.empty())
    {
      print_usage(std::cerr);
      return 2;
    }
    throw Usage_error("unknown command \"" + command + "\" (commands: match, eval, transfer, bench, demo)");
  }
  catch(const Usage_error& e)
  {
    std::cerr << "comap: " << one_line(e.what())
              << (is_command(command) ? " (see comap " + command + " --help)" : std::string(" (see comap --help)"))
              << std::endl;
    return 2;
  }
  catch(const std::bad_alloc&)
  {
    std::cerr << "comap: out of memory" << std::endl;
    return 1;
  }
  catch(const std::exception& e)
  {
    std::cerr << "comap: error: " << one_line(e.what()) << std::endl;
    return 1;
  }
  catch(...)
  {
    std::cerr << "comap: error: unknown exception" << std::endl;
    return 1;
  }
}
