// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap match (the maps of a pair of meshes) and comap eval (a map against ground truth).

#include "comap_commands.h"
#include "comap_report.h"
#include "comap_settings.h"

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace comap {

namespace {

std::string index_base_help() { return "index of the first vertex in map and correspondence files (0 or 1)"; }

} // namespace

// ------------------------------------------------------------------------------------ match

int run_match(int argc, char** argv)
{
  smc::Matching_settings settings;
  Common_options common;
  std::string out_12, out_21, init_12, init_21, stats, landmarks_file;
  int index_base = 1;
  Option_parser p("match", "comap match SOURCE TARGET --out-12 FILE --out-21 FILE [options]",
                  "Computes dense point-to-point maps SOURCE -> TARGET and TARGET -> SOURCE with the library's "
                  "match_shapes(): automatic initial maps (functional maps + ZoomOut), or the given ones repaired and "
                  "compared with the automatic ones, then the coupled refinement of Azencot, Dubrovina and Guibas "
                  "(2019), kept where it makes the maps better. Meshes: OFF, PLY, OBJ or STL; connected triangle "
                  "meshes, non-manifold edges and vertices and faces of zero area included (reported). Map files: one target vertex index per line, line i for source vertex i.");
  p.section("Files");
  p.value("--out-12", "FILE", "output: the map SOURCE -> TARGET", "", [&](const std::string& v) { out_12 = v; });
  p.value("--out-21", "FILE", "output: the map TARGET -> SOURCE", "", [&](const std::string& v) { out_21 = v; });
  p.value("--init-12", "FILE", "initial map SOURCE -> TARGET (default: automatic)", "",
          [&](const std::string& v) { init_12 = v; });
  p.value("--init-21", "FILE", "initial map TARGET -> SOURCE (give both or neither)", "",
          [&](const std::string& v) { init_21 = v; });
  p.value("--landmarks", "FILE", "known correspondences for the automatic initialisation: one pair of vertex "
          "indices 'SOURCE TARGET' per line", "", [&](const std::string& v) { landmarks_file = v; });
  p.value("--index-base", "0|1", index_base_help(), "1",
          [&](const std::string& v) { index_base = parse_int("--index-base", v, 0, 1); });
  p.value("--stats", "FILE.json", "write the settings, the decisions, per-stage times and per-solve statistics as "
          "JSON", "", [&](const std::string& v) { stats = v; });
  bool verbose = false;
  p.flag("--verbose", "print on stderr what the input check found in each mesh: non-manifold edges and vertices, "
         "faces of zero area, with their indices", [&] { verbose = true; });
  p.section("Settings");
  std::vector<std::string> settings_files;
  add_settings_options(p, settings, &settings_files);
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> files = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(files.size() != 2)
    throw Usage_error("match needs two meshes, SOURCE and TARGET (" + std::to_string(files.size()) + " given)");
  if(out_12.empty() || out_21.empty()) throw Usage_error("match needs --out-12 FILE and --out-21 FILE");
  if(init_12.empty() != init_21.empty()) throw Usage_error("give both --init-12 and --init-21, or neither");
  if(!landmarks_file.empty() && !init_12.empty())
    throw Usage_error("--landmarks guide the automatic initial maps: give --landmarks or --init-12 and --init-21, "
                      "not both");
  std::vector<Named_file> inputs = {{"SOURCE", files[0]}, {"TARGET", files[1]}, {"--init-12", init_12},
                                    {"--init-21", init_21}, {"--landmarks", landmarks_file}};
  for(const std::string& f : settings_files) inputs.push_back({"--settings", f});
  check_outputs_are_new(inputs, {{"--out-12", out_12}, {"--out-21", out_21}, {"--stats", stats}});
  check_writable(out_12);
  check_writable(out_21);
  if(!stats.empty()) check_writable(stats);
  const Thread_limit limit(common.threads);
  const Progress progress(common.quiet);

  Stopwatch watch;
  const smc::Triangle_soup m1 = read_mesh_soup(files[0]);
  const smc::Triangle_soup m2 = read_mesh_soup(files[1]);
  const double load_seconds = watch.seconds();
  const std::size_t n1 = m1.number_of_vertices(), n2 = m2.number_of_vertices();
  progress.line("loaded " + files[0] + " (" + std::to_string(n1) + " vertices, " +
                std::to_string(m1.number_of_triangles()) + " triangles) and " + files[1] + " (" +
                std::to_string(n2) + " vertices, " + std::to_string(m2.number_of_triangles()) + " triangles)");
  std::vector<std::pair<std::size_t, std::size_t> > landmarks;
  if(!landmarks_file.empty()) landmarks = read_landmarks(landmarks_file, index_base, n1, n2);
  Vertex_map given_12, given_21;
  const bool given = !init_12.empty();
  if(given)
  {
    given_12 = read_vertex_map(init_12, index_base, n1, n2);
    given_21 = read_vertex_map(init_21, index_base, n2, n1);
  }
  Progress_visitor visitor(progress);
  const auto np = smc::parameters::matching_settings(
      settings, smc::parameters::landmarks(landmarks, smc::parameters::visitor(std::ref(visitor))));
  Vertex_map map_12, map_21;
  const smc::Matching_result r =
      match_soups(m1, m2, given ? &given_12 : nullptr, given ? &given_21 : nullptr, np, map_12, map_21);
  if(verbose)
    std::cerr << irregularities_report(files[0], r.irregularities_1, index_base)
              << irregularities_report(files[1], r.irregularities_2, index_base);
  // The maps and the statistics are all written before the first of them replaces its file.
  smc::Atomic_output_file file_12(out_12), file_21(out_21);
  smc::write_vertex_indices(file_12.stream(), map_12, index_base);
  smc::write_vertex_indices(file_21.stream(), map_21, index_base);
  std::optional<smc::Atomic_output_file> stats_file;
  if(!stats.empty())
  {
    stats_file.emplace(stats);
    Json_writer json(stats_file->stream());
    json.begin_object().value("command", "match").value("index_base", index_base);
    json.begin_object("source").value("file", files[0]).value("vertices", n1);
    write_irregularities(json, "irregularities", r.irregularities_1, index_base);
    json.end_object();
    json.begin_object("target").value("file", files[1]).value("vertices", n2);
    write_irregularities(json, "irregularities", r.irregularities_2, index_base);
    json.end_object();
    if(given) json.value("init_12", init_12).value("init_21", init_21);
    write_settings(json, "settings", settings, r.refined_maps);
    write_result(json, "result", r);
    json.begin_object("final_maps")
        .value("inconsistent_vertices", smc::number_of_inconsistent_vertices(map_12, map_21))
        .value("coverage_12", smc::map_coverage(map_12, n2))
        .value("coverage_21", smc::map_coverage(map_21, n1))
        .value("map_12", out_12)
        .value("map_21", out_21)
        .end_object();
    json.value("loading_seconds", load_seconds).value("total_seconds", load_seconds + r.total_seconds);
    json.value("peak_memory_mib", peak_memory_mib());
    json.end_object().finish();
  }
  if(stats_file)
    commit_outputs({&file_12, &file_21, &*stats_file});
  else
    commit_outputs({&file_12, &file_21});

  std::cout << "source: " << files[0] << " (" << n1 << " vertices)\n"
            << "target: " << files[1] << " (" << n2 << " vertices)\n";
  for(const std::string& d : r.decisions) std::cout << d << "\n";
  std::cout << "inconsistent vertices (T21(T12(x)) != x, both ways): " << r.inconsistent_vertices_before << " -> "
            << r.inconsistent_vertices_after << " of " << (n1 + n2) << "\n"
            << confidence_report(r)
            << "timings: loading " << duration(load_seconds);
  for(int s = 0; s <= int(smc::Matching_stage::selection); ++s)
    if(r.stage_seconds[std::size_t(s)] > 0)
      std::cout << ", " << smc::to_string(smc::Matching_stage(s)) << " " << duration(r.stage_seconds[std::size_t(s)]);
  std::cout << ", total " << duration(load_seconds + r.total_seconds) << "; peak memory "
            << fixed(peak_memory_mib(), 0) << " MiB\n"
            << "wrote " << out_12 << " (" << n1 << " lines) and " << out_21 << " (" << n2 << " lines), "
            << index_base << "-based" << (stats.empty() ? "" : "; statistics in " + stats) << "\n";
  return 0;
}

// ------------------------------------------------------------------------------------- eval

namespace {

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

} // namespace

int run_eval(int argc, char** argv)
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

  const smc::Triangle_soup ms = read_mesh_soup(source), mt = read_mesh_soup(target);
  const std::size_t ns = ms.number_of_vertices(), nt = mt.number_of_vertices();
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

} // namespace comap
