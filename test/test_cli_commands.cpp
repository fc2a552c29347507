// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap round trips on a small generated pair (a bumpy capsule and a bent, remeshed copy):
// match with and without initial maps, 0- and 1-based files, eval against values computed with
// the library, transfer with coordinate colours and with a PNG texture.

#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include "damaged_meshes.h"
#include "test_cli_helpers.h"

#include <boost/test/unit_test.hpp>

#include <limits>
#include <regex>

namespace smc = CGAL::Surface_mesh_correspondence;
using namespace smc_cli_test;

namespace {

#ifdef CGAL_LINKED_WITH_TBB
typedef CGAL::Parallel_tag Tag;  // comap's
#else
typedef CGAL::Sequential_tag Tag;
#endif

double mean_error(const Mesh& target, const std::vector<std::size_t>& map, const std::vector<std::size_t>& gt)
{
  return smc::Map_evaluator<>(target).geodesic_errors(map, identity(map.size()), gt).mean;
}

/// The first "mean X" printed after `label`.
double printed_mean(const std::string& text, const std::string& label = "geodesic error / sqrt(area): mean ")
{
  const std::size_t at = text.find(label);
  BOOST_REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + label.size()));
}

void check_map_file(const std::string& file, std::size_t size, std::size_t target_size, int base)
{
  const std::vector<std::size_t> m = read_map(file, base);
  BOOST_TEST(m.size() == size);
  for(std::size_t t : m) BOOST_TEST_REQUIRE(t < target_size);
}

} // namespace

BOOST_AUTO_TEST_SUITE(cli_round_trip)

BOOST_AUTO_TEST_CASE(help_is_short_and_lists_the_registry)
{
  const Run r = comap("match --help");
  BOOST_TEST(r.code == 0);
  // The common options only (at most 25), then every setting of the registry with its defaults.
  std::size_t options = 0;
  for(const std::string& line : lines_of(r.out))
    options += std::regex_search(line, std::regex("^ *--"));
  BOOST_TEST_MESSAGE("comap match --help: " << options << " options");
  BOOST_TEST(options <= 25u);
  BOOST_TEST(r.out.find("--settings FILE.json") != std::string::npos);
  BOOST_TEST(r.out.find("--set NAME=VALUE") != std::string::npos);
  for(const smc::Setting_info& s : smc::matching_settings_registry())
  {
    const std::string entry = "  " + s.name + " (" + s.type + ", " + s.range_text + ") [" + s.default_text;
    BOOST_TEST(r.out.find(entry) != std::string::npos, "missing: " << entry);
    if(s.given_default_text != s.default_text)
      BOOST_TEST(r.out.find("given maps: " + s.given_default_text + "]") != std::string::npos, s.name);
  }
  BOOST_TEST(r.out.find("[40; given maps: 20]") != std::string::npos);  // number_of_candidates
  const Run top = comap("--help");
  BOOST_TEST(top.code == 0);
  BOOST_TEST(top.out.find("bench") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(settings_file_round_trip)
{
  // comap settings prints every setting of the registry with its default (null where the default
  // depends on the maps' origin), with comments; read back, it changes nothing; edited, it does.
  const Run printed = comap("settings");
  BOOST_TEST_REQUIRE(printed.code == 0, printed.err);
  for(const smc::Setting_info& s : smc::matching_settings_registry())
  {
    const std::string value = s.given_default_text != s.default_text ? std::string("null")
                              : s.type == "word"                     ? "\"" + s.default_text + "\""
                                                                     : s.default_text;
    BOOST_TEST(printed.out.find("\"" + s.name + "\": " + value) != std::string::npos, s.name << ": " << value);
    BOOST_TEST(printed.out.find("  // " + s.documentation + "\n") != std::string::npos, s.name);
  }
  write_text(in_scratch("all.json"), printed.out);
  const Cli_pair& p = cli_pair();
  auto run = [&](const std::string& options, const std::string& tag) {
    const Run r = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch(tag + "12.map") + " --out-21 " +
                        in_scratch(tag + "21.map") + " --stats " + in_scratch(tag + ".json") + options);
    BOOST_TEST_REQUIRE(r.code == 0, r.err);
    return read_text(in_scratch(tag + "12.map")) + read_text(in_scratch(tag + "21.map"));
  };
  // The printed file, then the fast settings (the later file wins): the maps of the fast settings.
  const std::string fast = run(fast_options(), "quick");
  const std::string template_then_fast = run(" --settings " + in_scratch("all.json") + fast_options(), "template");
  BOOST_TEST((template_then_fast == fast));
  // Edited: a setting whose default depends on the maps' origin, set for both.
  std::string edited = printed.out;
  const std::string null_candidates = "\"number_of_candidates\": null";
  BOOST_TEST_REQUIRE(edited.find(null_candidates) != std::string::npos);
  edited.replace(edited.find(null_candidates), null_candidates.size(), "\"number_of_candidates\": 12");
  write_text(in_scratch("edited_settings.json"), edited);
  const std::string twelve =
      run(" --settings " + in_scratch("edited_settings.json") + fast_options({"number_of_candidates"}), "twelve");
  const std::string stats = read_text(in_scratch("twelve.json")), fast_stats = read_text(in_scratch("quick.json"));
  BOOST_TEST(stats.find("\"number_of_candidates\": 12,") != std::string::npos);
  BOOST_TEST(fast_stats.find("\"number_of_candidates\": 10,") != std::string::npos);
  BOOST_TEST((twelve != fast));
  // Unknown names and bad values in the file are named, with its line and column for syntax errors.
  write_text(in_scratch("broken.json"), "{\n  // a comment\n  \"number_of_candidates\": nul\n}\n");
  const Run broken = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch("x12.map") + " --out-21 " +
                           in_scratch("x21.map") + " --settings " + in_scratch("broken.json"));
  BOOST_TEST(broken.code == 1);
  BOOST_TEST(broken.err.find("broken.json:3:") != std::string::npos, broken.err);
}

BOOST_AUTO_TEST_CASE(match_refines_given_maps_0_and_1_based)
{
  const Cli_pair& p = cli_pair();
  const std::size_t n1 = num_vertices(p.pair.m1), n2 = num_vertices(p.pair.m2);
  BOOST_TEST_MESSAGE("test pair: " << n1 << " and " << n2 << " vertices");
  BOOST_TEST(n1 >= 500u);
  BOOST_TEST(n1 <= 1500u);
  write_map(in_scratch("noisy12_0.map"), p.noisy_12, 0);
  write_map(in_scratch("noisy21_0.map"), p.noisy_21, 0);
  write_map(in_scratch("noisy12_1.map"), p.noisy_12, 1);
  write_map(in_scratch("noisy21_1.map"), p.noisy_21, 1);
  const Run r0 = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("noisy12_0.map") + " --init-21 " +
                       in_scratch("noisy21_0.map") + " --index-base 0 --out-12 " + in_scratch("r12_0.map") +
                       " --out-21 " + in_scratch("r21_0.map") + " --stats " + in_scratch("stats.json") + fast_options());
  BOOST_TEST_REQUIRE(r0.code == 0, r0.err);
  BOOST_TEST(r0.err.empty());  // --quiet
  check_map_file(in_scratch("r12_0.map"), n1, n2, 0);
  check_map_file(in_scratch("r21_0.map"), n2, n1, 0);
  const std::vector<std::size_t> r12 = read_map(in_scratch("r12_0.map"), 0), r21 = read_map(in_scratch("r21_0.map"), 0);
  // The refinement returns its most consistent maps, and improves these noisy ones.
  BOOST_TEST(smc::number_of_inconsistent_vertices(r12, r21) <= smc::number_of_inconsistent_vertices(p.noisy_12, p.noisy_21));
  const double before = mean_error(p.pair.m2, p.noisy_12, p.pair.gt_12), after = mean_error(p.pair.m2, r12, p.pair.gt_12);
  BOOST_TEST_MESSAGE("mean error 1->2: " << before << " -> " << after);
  BOOST_TEST(after < before);
  const std::string stats = read_text(in_scratch("stats.json"));
  for(const char* key : {"\"settings\"", "\"refinement\"", "\"steps\"", "\"stage_seconds\"", "\"data_preparation_seconds\"",
                         "\"decisions\"", "\"selection\""})
    BOOST_TEST(stats.find(key) != std::string::npos, key);
  BOOST_TEST(r0.out.find("0-based") != std::string::npos);
  // These noisy maps stay the given ones (too little distorted for the comparison with the
  // automatic maps, no tear), refined with the defaults for given maps: the whole schedule
  // (ring_schedule [3, 2]: 2 outer iterations).
  BOOST_TEST(stats.find("\"initial_maps\": \"given\"") != std::string::npos);
  BOOST_TEST(stats.find("\"refined_maps\": \"given\"") != std::string::npos);
  BOOST_TEST(stats.find("\"outer_iterations\": 2,") != std::string::npos);

  // The same maps 1-based give the same result, written 1-based.
  const Run r1 = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("noisy12_1.map") + " --init-21 " +
                       in_scratch("noisy21_1.map") + " --out-12 " + in_scratch("r12_1.map") + " --out-21 " +
                       in_scratch("r21_1.map") + fast_options());
  BOOST_TEST_REQUIRE(r1.code == 0, r1.err);
  BOOST_TEST(read_text(in_scratch("r12_1.map")).find("\n0\n") == std::string::npos);
  BOOST_TEST(read_map(in_scratch("r12_1.map"), 1) == r12);
  BOOST_TEST(read_map(in_scratch("r21_1.map"), 1) == r21);
}

BOOST_AUTO_TEST_CASE(match_without_initial_maps)
{
  const Cli_pair& p = cli_pair();
  const std::size_t n1 = num_vertices(p.pair.m1), n2 = num_vertices(p.pair.m2);
  // use_refinement=false: exactly the maps of the library's automatic_initial_maps() with the same
  // settings.
  const Run init = comap("match " + p.a + " " + p.b + " --set use_refinement=false --set zoomout_final_size=40 --quiet" +
                         " --out-12 " + in_scratch("a12.map") + " --out-21 " + in_scratch("a21.map"));
  BOOST_TEST_REQUIRE(init.code == 0, init.err);
  BOOST_TEST(init.out.find("automatic") != std::string::npos);
  check_map_file(in_scratch("a12.map"), n1, n2, 1);
  check_map_file(in_scratch("a21.map"), n2, n1, 1);
  std::vector<std::size_t> l12, l21;
  smc::automatic_initial_maps<Tag>(p.pair.m1, p.pair.m2, l12, l21, smc::parameters::zoomout_final_size(40));
  BOOST_TEST(read_map(in_scratch("a12.map"), 1) == l12);
  BOOST_TEST(read_map(in_scratch("a21.map"), 1) == l21);
  BOOST_TEST_MESSAGE("automatic initial map 1->2: mean error " << mean_error(p.pair.m2, l12, p.pair.gt_12));
  // Passes that end at 40 and maps that grow to 60, as in the library; set from a settings file
  // and overridden by --set (the later one wins).
  write_text(in_scratch("grow.json"), "{\"zoomout_final_size\": 50, \"zoomout_pass_size\": 40,\n"
                                      " \"use_refinement\": false}\n");
  const Run grown = comap("match " + p.a + " " + p.b + " --settings " + in_scratch("grow.json") +
                          " --set zoomout_final_size=60 --quiet --out-12 " + in_scratch("g12.map") + " --out-21 " +
                          in_scratch("g21.map"));
  BOOST_TEST_REQUIRE(grown.code == 0, grown.err);
  std::vector<std::size_t> g12, g21;
  smc::automatic_initial_maps<Tag>(p.pair.m1, p.pair.m2, g12, g21,
                                   smc::parameters::zoomout_final_size(60, smc::parameters::zoomout_pass_size(40)));
  BOOST_TEST(read_map(in_scratch("g12.map"), 1) == g12);
  BOOST_TEST(read_map(in_scratch("g21.map"), 1) == g21);
  BOOST_TEST(g12 != l12);

  // Automatic maps are refined with the registry's defaults for automatic maps (ring_schedule
  // [4, 3, 2, 1], 40 candidates, 15 TRW-S iterations), given maps with those for given maps
  // ([6, 4, 3, 2, 1], 20, 100); a setting given by the user holds for both.
  const std::vector<std::string> refinement = {"ring_schedule", "number_of_candidates", "trws_number_of_iterations"};
  const std::string defaults = fast_options(refinement);
  const Run automatic = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch("s12.map") + " --out-21 " +
                              in_scratch("s21.map") + " --stats " + in_scratch("automatic.json") +
                              " --set consistency_weight=0.75" + defaults);
  BOOST_TEST_REQUIRE(automatic.code == 0, automatic.err);
  const std::string automatic_stats = read_text(in_scratch("automatic.json"));
  BOOST_TEST(automatic_stats.find("\"ring_schedule\": [4, 3, 2, 1]") != std::string::npos);
  BOOST_TEST(automatic_stats.find("\"number_of_candidates\": 40,") != std::string::npos);
  BOOST_TEST(automatic_stats.find("\"trws_number_of_iterations\": 15,") != std::string::npos);
  BOOST_TEST(automatic_stats.find("\"consistency_weight\": 0.75") != std::string::npos);
  const Run given = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("s12.map") + " --init-21 " +
                          in_scratch("s21.map") + " --out-12 " + in_scratch("d12.map") + " --out-21 " +
                          in_scratch("d21.map") + " --stats " + in_scratch("given.json") +
                          " --set number_of_outer_iterations=1 --set repair_given_maps=false"
                          " --set compare_with_automatic_maps=false" + defaults);
  BOOST_TEST_REQUIRE(given.code == 0, given.err);
  const std::string given_stats = read_text(in_scratch("given.json"));
  BOOST_TEST(given_stats.find("\"refined_maps\": \"given\"") != std::string::npos);
  BOOST_TEST(given_stats.find("\"ring_schedule\": [6, 4, 3, 2, 1]") != std::string::npos);
  BOOST_TEST(given_stats.find("\"number_of_candidates\": 20,") != std::string::npos);
  BOOST_TEST(given_stats.find("\"trws_number_of_iterations\": 100,") != std::string::npos);
  BOOST_TEST(given_stats.find("\"consistency_weight\": 1,") != std::string::npos);
  BOOST_TEST(given_stats.find("\"outer_iterations\": 1,") != std::string::npos);

  // The selection: "consistency" (the paper's rule) returns the refined maps only when they are
  // more consistent than the automatic maps, so never less consistent maps; "refined" returns the
  // refined maps whatever they are; the default ("regions") is more accurate than the automatic
  // maps on this pair.
  const Run unrefined = comap("match " + p.a + " " + p.b + " --set use_refinement=false --out-12 " +
                              in_scratch("b12.map") + " --out-21 " + in_scratch("b21.map") + fast_options());
  BOOST_TEST_REQUIRE(unrefined.code == 0, unrefined.err);
  const std::vector<std::size_t> b12 = read_map(in_scratch("b12.map"), 1), b21 = read_map(in_scratch("b21.map"), 1);
  auto run = [&](const std::string& options, const std::string& tag) {
    const Run r = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch(tag + "12.map") + " --out-21 " +
                        in_scratch(tag + "21.map") + " --stats " + in_scratch(tag + ".json") + fast_options() + options);
    BOOST_TEST_REQUIRE(r.code == 0, r.err);
    return std::make_pair(read_map(in_scratch(tag + "12.map"), 1), read_map(in_scratch(tag + "21.map"), 1));
  };
  const auto regions = run("", "regions");
  const auto consistency = run(" --set refinement_selection=consistency", "consistency");
  const auto refined = run(" --set refinement_selection=refined", "refined");
  BOOST_TEST(smc::number_of_inconsistent_vertices(consistency.first, consistency.second) <=
             smc::number_of_inconsistent_vertices(b12, b21));
  BOOST_TEST(((consistency.first == b12 && consistency.second == b21) ||
              (consistency.first == refined.first && consistency.second == refined.second)));
  BOOST_TEST(read_text(in_scratch("refined.json")).find("\"refinement_selection\": \"refined\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("regions.json")).find("\"refinement_selection\": \"regions\"") != std::string::npos);
  const double automatic_error = mean_error(p.pair.m2, b12, p.pair.gt_12);
  const double regions_error = mean_error(p.pair.m2, regions.first, p.pair.gt_12);
  BOOST_TEST_MESSAGE("automatic map 1->2 " << automatic_error << ", refined and selected (default) " << regions_error);
  BOOST_TEST(regions_error < automatic_error);
  // The confidence: these accurate maps are trusted (a line on stdout, no warning, "low": false
  // in the stats); a threshold of 1 flags any map, and comap warns on stderr, even with --quiet.
  {
    const Run trusted = comap("match " + p.a + " " + p.b + " --quiet --out-12 " + in_scratch("t12.map") +
                              " --out-21 " + in_scratch("t21.map") + " --stats " + in_scratch("t.json") + fast_options());
    BOOST_TEST_REQUIRE(trusted.code == 0, trusted.err);
    BOOST_TEST(trusted.out.find("confidence: ") != std::string::npos);
    BOOST_TEST(trusted.err.find("warning") == std::string::npos, trusted.err);
    const std::string stats = read_text(in_scratch("t.json"));
    BOOST_TEST(stats.find("\"confidence\": {") != std::string::npos);
    BOOST_TEST(stats.find("\"low\": false") != std::string::npos);
    const Run flagged = comap("match " + p.a + " " + p.b + " --quiet --set confidence_threshold=1 --out-12 " +
                              in_scratch("f12.map") + " --out-21 " + in_scratch("f21.map") + fast_options());
    BOOST_TEST_REQUIRE(flagged.code == 0, flagged.err);
    BOOST_TEST(flagged.err.find("comap: warning: low confidence") != std::string::npos, flagged.err);
    BOOST_TEST(flagged.out.find("confidence: ") != std::string::npos);
    BOOST_TEST((read_map(in_scratch("f12.map"), 1) == read_map(in_scratch("t12.map"), 1)));  // a report only
  }
  // Without the early stop, the whole schedule runs (ring_schedule [3, 2]: 2 outer iterations).
  run(" --set stop_when_consistency_worsens=false", "all");
  BOOST_TEST(read_text(in_scratch("all.json")).find("\"outer_iterations\": 2,") != std::string::npos);
}

// A target with a fin and 1% of its faces of zero area (test/damaged_meshes.h) is matched; the
// decisions, --verbose and the statistics say what the input check found, with 1-based indices.
BOOST_AUTO_TEST_CASE(match_handles_and_reports_damaged_meshes)
{
  const Cli_pair& p = cli_pair();
  const smc::Triangle_soup clean = smc::read_triangle_soup(p.b);
  const smc_damage::Soup soup = smc_damage::soup_of(clean);
  const smc_damage::Damaged flat = smc_damage::collapse_faces(soup, 0.01);
  const smc_damage::Damaged d = smc_damage::add_fin(flat.soup, soup.triangles.size() / 2);
  const std::size_t n2 = d.soup.points.size(), degenerate = std::size_t(std::lround(0.01 * double(soup.triangles.size())));
  smc_damage::write_off(in_scratch("damaged.off"), d.soup);
  const Run r = comap("match " + p.a + " " + in_scratch("damaged.off") + " --verbose --out-12 " +
                      in_scratch("x12.map") + " --out-21 " + in_scratch("x21.map") + " --stats " +
                      in_scratch("damaged.json") + fast_options());
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  check_map_file(in_scratch("x12.map"), num_vertices(p.pair.m1), n2, 1);
  check_map_file(in_scratch("x21.map"), n2, num_vertices(p.pair.m1), 1);
  BOOST_TEST(contains(r.out, "input: mesh 2 has 1 non-manifold edge, " + std::to_string(degenerate) +
                                 " degenerate faces (tufted Laplacian with mollification)"),
             r.out);
  const int i = d.soup.triangles.back()[0] + 1, j = d.soup.triangles.back()[1] + 1;
  const std::string edge = "(" + std::to_string(std::min(i, j)) + ", " + std::to_string(std::max(i, j)) + ")";
  BOOST_TEST(contains(r.err, "damaged.off: 1 non-manifold edge (in more than two faces): " + edge), r.err);
  BOOST_TEST(contains(r.err, "damaged.off: " + std::to_string(degenerate) + " faces of zero area:"), r.err);
  BOOST_TEST(contains(r.err, "A.off: manifold, no face of zero area"), r.err);
  const std::string stats = read_text(in_scratch("damaged.json"));
  BOOST_TEST(contains(stats, "\"non_manifold_edges\": 1,"), stats);
  BOOST_TEST(contains(stats, "\"degenerate_faces\": " + std::to_string(degenerate) + ","), stats);
  BOOST_TEST(contains(stats, "\"non_manifold_edge_vertices\": [[" + std::to_string(std::min(i, j)) + ", " +
                                 std::to_string(std::max(i, j)) + "]]"), stats);
}

BOOST_AUTO_TEST_CASE(match_repairs_torn_maps)
{
  // Given maps that turn one end of the capsule (z > 3 of [-1, 5]) by 180 degrees about its axis: torn
  // along a ring; the rest (two thirds) is the core. Repaired without the comparison and not refined,
  // comap writes exactly the maps of the library's repair_torn_maps().
  const Cli_pair& p = cli_pair();
  const Mesh& m1 = p.pair.m1;
  auto turned = [&](std::size_t v) {
    const Point q = m1.point(Vertex(static_cast<Mesh::size_type>(v)));
    if(q.z() <= 3.0) return v;
    std::size_t best = v;
    double best_d = std::numeric_limits<double>::infinity();
    for(Vertex w : m1.vertices())
    {
      const Point r = m1.point(w);
      const double d = CGAL::squared_distance(r, Point(-q.x(), -q.y(), q.z()));
      if(d < best_d) best_d = d, best = w.idx();
    }
    return best;
  };
  std::vector<std::size_t> t12(p.pair.gt_12.size()), t21(p.pair.gt_21.size());
  for(std::size_t v = 0; v < t12.size(); ++v) t12[v] = p.pair.gt_12[turned(v)];
  for(std::size_t w = 0; w < t21.size(); ++w) t21[w] = turned(p.pair.gt_21[w]);
  write_map(in_scratch("turned12.map"), t12, 0);
  write_map(in_scratch("turned21.map"), t21, 0);
  const Run r = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("turned12.map") + " --init-21 " +
                      in_scratch("turned21.map") + " --index-base 0 --set compare_with_automatic_maps=false" +
                      " --set use_refinement=false --set zoomout_final_size=40 --quiet" +
                      " --out-12 " + in_scratch("rep12.map") + " --out-21 " + in_scratch("rep21.map") + " --stats " +
                      in_scratch("repair.json"));
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  std::vector<std::size_t> l12 = t12, l21 = t21;
  const smc::Automatic_initialization_result lib =
      smc::repair_torn_maps<Tag>(p.pair.m1, p.pair.m2, l12, l21,
                                 smc::parameters::zoomout_final_size(40, smc::parameters::compare_with_automatic_maps(false)));
  BOOST_TEST(read_map(in_scratch("rep12.map"), 0) == l12);
  BOOST_TEST(read_map(in_scratch("rep21.map"), 0) == l21);
  const double before = mean_error(p.pair.m2, t12, p.pair.gt_12), after = mean_error(p.pair.m2, l12, p.pair.gt_12);
  BOOST_TEST_MESSAGE("turned end: error 1->2 " << before << " -> " << after << ", torn fraction "
                                               << lib.torn_fraction_before << " -> " << lib.torn_fraction << " in "
                                               << lib.repair_passes << " pass(es)");
  BOOST_TEST(lib.torn_fraction_before > 0.1);
  BOOST_TEST(lib.repair_passes >= 1);
  BOOST_TEST(lib.torn_fraction < lib.torn_fraction_before);
  BOOST_TEST(after < 0.5 * before);  // measured: 0.12 -> 0.027
  const std::string stats = read_text(in_scratch("repair.json"));
  BOOST_TEST(stats.find("\"repaired\": true") != std::string::npos);
  BOOST_TEST(stats.find("\"torn_fraction_before\"") != std::string::npos);
  // The kept repair pass's maps are maps of the automatic initialisation: they are refined with the
  // preset for automatic maps (consistency weight 0.5; 1 for given maps).
  BOOST_TEST(stats.find("\"consistency_weight\": 0.5,") != std::string::npos);
  // The comparison (on by default): the given maps compete with the automatic maps, as they are
  // (repair_given_maps=false) or repaired (the default), exactly as in the library.
  double unrepaired_distortion = 0;
  for(const bool with_repair : {false, true})
  {
    const std::string tag = with_repair ? "rc" : "c";
    const Run c = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("turned12.map") + " --init-21 " +
                        in_scratch("turned21.map") + " --index-base 0" +
                        (with_repair ? "" : " --set repair_given_maps=false") +
                        " --set use_refinement=false --set zoomout_final_size=40 --quiet --out-12 " +
                        in_scratch(tag + "12.map") + " --out-21 " + in_scratch(tag + "21.map") + " --stats " +
                        in_scratch(tag + ".json"));
    BOOST_TEST_REQUIRE(c.code == 0, c.err);
    std::vector<std::size_t> k12 = t12, k21 = t21;
    const smc::Automatic_initialization_result compared =
        with_repair ? smc::repair_torn_maps<Tag>(p.pair.m1, p.pair.m2, k12, k21,
                                                 smc::parameters::compare_with_automatic_maps(
                                                     true, smc::parameters::zoomout_final_size(40)))
                    : smc::compare_with_automatic_maps<Tag>(p.pair.m1, p.pair.m2, k12, k21,
                                                            smc::parameters::zoomout_final_size(40));
    BOOST_TEST_MESSAGE("turned end against the automatic maps" << (with_repair ? " after the repair" : "")
                                                               << ": sample distortion " << compared.given_maps_distortion
                                                               << " against " << compared.automatic_maps_distortion);
    BOOST_TEST(compared.compared_with_automatic_maps);
    BOOST_TEST(read_map(in_scratch(tag + "12.map"), 0) == k12);
    BOOST_TEST(read_map(in_scratch(tag + "21.map"), 0) == k21);
    const std::string compare_stats = read_text(in_scratch(tag + ".json"));
    BOOST_TEST(compare_stats.find("\"compared\": true") != std::string::npos);
    BOOST_TEST(compare_stats.find(std::string("\"automatic_maps_kept\": ") +
                                  (compared.automatic_maps_kept ? "true" : "false")) != std::string::npos);
    // Unrepaired, the turned end is far more distorted than the automatic maps, which replace it
    // and are refined as automatic maps (consistency weight 0.5).
    if(!with_repair) BOOST_TEST(compared.automatic_maps_kept);
    if(compared.automatic_maps_kept)
      BOOST_TEST(compare_stats.find("\"consistency_weight\": 0.5,") != std::string::npos);
    if(!with_repair) unrepaired_distortion = compared.given_maps_distortion;
  }
  // automatic_maps_comparison_threshold: given maps distorted less than the threshold are kept as
  // they are, without the automatic maps.
  const Run k = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("turned12.map") + " --init-21 " +
                      in_scratch("turned21.map") + " --index-base 0 --set repair_given_maps=false" +
                      " --set automatic_maps_comparison_threshold=" + std::to_string(1.01 * unrepaired_distortion) +
                      " --set use_refinement=false --set zoomout_final_size=40 --quiet" +
                      " --out-12 " + in_scratch("k12.map") + " --out-21 " + in_scratch("k21.map") + " --stats " +
                      in_scratch("k.json"));
  BOOST_TEST_REQUIRE(k.code == 0, k.err);
  BOOST_TEST(read_map(in_scratch("k12.map"), 0) == t12);
  BOOST_TEST(read_map(in_scratch("k21.map"), 0) == t21);
  const std::string kept_stats = read_text(in_scratch("k.json"));
  BOOST_TEST(kept_stats.find("\"automatic_maps_computed\": false") != std::string::npos);
  BOOST_TEST(kept_stats.find("\"automatic_maps_kept\": false") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(eval_matches_the_library)
{
  const Cli_pair& p = cli_pair();
  write_map(in_scratch("gt12.map"), p.pair.gt_12, 1);
  write_map(in_scratch("gt21.map"), p.pair.gt_21, 1);
  write_map(in_scratch("ids.vts"), identity(num_vertices(p.pair.m1)), 1);
  write_map(in_scratch("noisy12_1.map"), p.noisy_12, 1);
  write_map(in_scratch("noisy21_1.map"), p.noisy_21, 1);
  const std::string gt = " --gt-source " + in_scratch("ids.vts") + " --gt-target " + in_scratch("gt12.map");
  // The ground-truth map has no error.
  const Run exact = comap("eval --source " + p.a + " --target " + p.b + " --map " + in_scratch("gt12.map") + gt);
  BOOST_TEST_REQUIRE(exact.code == 0, exact.err);
  BOOST_TEST(printed_mean(exact.out) == 0.0);
  BOOST_TEST(exact.out.find("within 0.025: 100.0%") != std::string::npos);
  // A noisy map: the printed figures are the library's.
  const Run noisy = comap("eval --source " + p.a + " --target " + p.b + " --map " + in_scratch("noisy12_1.map") +
                          " --map-21 " + in_scratch("noisy21_1.map") + gt + " --gt-target-sym " + in_scratch("gt12.map"));
  BOOST_TEST_REQUIRE(noisy.code == 0, noisy.err);
  const double expected = mean_error(p.pair.m2, p.noisy_12, p.pair.gt_12);
  BOOST_TEST(std::abs(printed_mean(noisy.out) - expected) <= 0.00005 + 1e-12);
  BOOST_TEST(expected > 0.005);
  const smc::Cycle_consistency c = smc::Map_evaluator<>(p.pair.m1).cycle_consistency(p.noisy_12, p.noisy_21);
  BOOST_TEST(noisy.out.find("fixed points " + [&] {
    char b[32];
    std::snprintf(b, sizeof(b), "%.1f%%", 100 * c.fixed_point_fraction);
    return std::string(b);
  }()) != std::string::npos);
  BOOST_TEST(noisy.out.find("symmetry-tolerant") != std::string::npos);
  BOOST_TEST(noisy.out.find("coverage") != std::string::npos);
  // JSON output.
  const Run json = comap("eval --json --source " + p.a + " --target " + p.b + " --map " + in_scratch("noisy12_1.map") + gt);
  BOOST_TEST_REQUIRE(json.code == 0, json.err);
  BOOST_TEST(json.out.find("\"cumulative\"") != std::string::npos);
  BOOST_TEST(json.out.front() == '{');
}

BOOST_AUTO_TEST_CASE(transfer_pulls_the_target_colours)
{
  const Cli_pair& p = cli_pair();
  write_map(in_scratch("noisy12_1.map"), p.noisy_12, 1);
  const Run r = comap("transfer --source " + p.a + " --target " + p.b + " --map-12 " + in_scratch("noisy12_1.map") +
                      " --out " + in_scratch("colored.ply"));
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const auto source = read_ply_colors(in_scratch("colored.ply"));
  const auto target = read_ply_colors(in_scratch("colored_target.ply"));
  BOOST_TEST_REQUIRE(source.size() == num_vertices(p.pair.m1));
  BOOST_TEST_REQUIRE(target.size() == num_vertices(p.pair.m2));
  bool all_pulled = true, varied = false;
  for(std::size_t i = 0; i < source.size(); ++i) all_pulled = all_pulled && source[i] == target[p.noisy_12[i]];
  for(std::size_t i = 1; i < target.size(); ++i) varied = varied || target[i] != target[0];
  BOOST_TEST(all_pulled);
  BOOST_TEST(varied);
  BOOST_TEST(read_text(in_scratch("colored.ply")).rfind("ply\nformat ascii 1.0\n", 0) == 0);

  // A texture whose left half is red and right half blue: every colour is a blend of the two.
  std::vector<unsigned char> rgb;
  for(int y = 0; y < 2; ++y)
    for(int x = 0; x < 4; ++x)
      for(int c = 0; c < 3; ++c) rgb.push_back((x < 2) ? (c == 0 ? 255 : 0) : (c == 2 ? 255 : 0));
  write_png(in_scratch("texture.png"), 4, 2, rgb);
  const Run t = comap("transfer --source " + p.a + " --target " + p.b + " --map-12 " + in_scratch("noisy12_1.map") +
                      " --out " + in_scratch("textured.ply") + " --texture " + in_scratch("texture.png"));
  BOOST_TEST_REQUIRE(t.code == 0, t.err);
  const auto textured = read_ply_colors(in_scratch("textured_target.ply"));
  bool blends = !textured.empty(), both = false, red = false, blue = false;
  for(const auto& c : textured)
  {
    blends = blends && c[1] == 0 && std::abs(c[0] + c[2] - 255) <= 1;
    red = red || c[0] == 255;
    blue = blue || c[2] == 255;
  }
  both = red && blue;
  BOOST_TEST(blends);
  BOOST_TEST(both);
}

BOOST_AUTO_TEST_SUITE_END()
