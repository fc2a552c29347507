// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap round trips on a small generated pair (a bumpy capsule and a bent, remeshed copy):
// match with and without initial maps, 0- and 1-based files, eval against values computed with
// the library, transfer with coordinate colours and with a PNG texture.

#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

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

BOOST_AUTO_TEST_CASE(help_shows_the_library_defaults)
{
  const Run r = comap("match --help");
  BOOST_TEST(r.code == 0);
  const smc::Refinement_settings defaults;
  BOOST_TEST(r.out.find("--candidates M") != std::string::npos);
  BOOST_TEST(r.out.find("(default " + std::to_string(defaults.number_of_candidates) + ")") != std::string::npos);
  std::string rings;
  for(std::size_t i = 0; i < defaults.ring_schedule.size(); ++i)
    rings += (i ? "," : "") + std::to_string(defaults.ring_schedule[i]);
  BOOST_TEST(r.out.find("(default " + rings + ")") != std::string::npos);
  BOOST_TEST(r.out.find("--init-basis") != std::string::npos);
  const Run top = comap("--help");
  BOOST_TEST(top.code == 0);
  BOOST_TEST(top.out.find("bench") != std::string::npos);
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
  for(const char* key : {"\"settings\"", "\"refinement\"", "\"steps\"", "\"timings\"", "\"data_preparation_seconds\""})
    BOOST_TEST(stats.find(key) != std::string::npos, key);
  BOOST_TEST(r0.out.find("0-based") != std::string::npos);
  // Given maps: the default stop rule runs the whole schedule (--rings 3,2: 2 outer iterations).
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
  // --no-refine: exactly the maps of the library's automatic_initial_maps() with the same settings.
  const Run init = comap("match " + p.a + " " + p.b + " --no-refine --init-basis 40 --quiet --out-12 " +
                         in_scratch("a12.map") + " --out-21 " + in_scratch("a21.map"));
  BOOST_TEST_REQUIRE(init.code == 0, init.err);
  BOOST_TEST(init.out.find("automatic") != std::string::npos);
  check_map_file(in_scratch("a12.map"), n1, n2, 1);
  check_map_file(in_scratch("a21.map"), n2, n1, 1);
  std::vector<std::size_t> l12, l21;
  smc::automatic_initial_maps<Tag>(p.pair.m1, p.pair.m2, l12, l21, smc::parameters::zoomout_final_size(40));
  BOOST_TEST(read_map(in_scratch("a12.map"), 1) == l12);
  BOOST_TEST(read_map(in_scratch("a21.map"), 1) == l21);
  BOOST_TEST_MESSAGE("automatic initial map 1->2: mean error " << mean_error(p.pair.m2, l12, p.pair.gt_12));
  // --init-pass-basis: passes end at 40, the kept maps grow to 60, as in the library.
  const Run grown = comap("match " + p.a + " " + p.b + " --no-refine --init-basis 60 --init-pass-basis 40 --quiet" +
                          " --out-12 " + in_scratch("g12.map") + " --out-21 " + in_scratch("g21.map"));
  BOOST_TEST_REQUIRE(grown.code == 0, grown.err);
  std::vector<std::size_t> g12, g21;
  smc::automatic_initial_maps<Tag>(p.pair.m1, p.pair.m2, g12, g21,
                                   smc::parameters::zoomout_final_size(60, smc::parameters::zoomout_pass_size(40)));
  BOOST_TEST(read_map(in_scratch("g12.map"), 1) == g12);
  BOOST_TEST(read_map(in_scratch("g21.map"), 1) == g21);
  BOOST_TEST(g12 != l12);

  // Without --rings, --candidates and --trws-iterations, automatic maps are refined with the short
  // schedule 4,3,2,1, 40 candidates and 15 TRW-S iterations; given maps with the library's
  // defaults (6,4,3,2,1, 20 and 100). The cycle term's weight is recorded.
  std::string no_refinement_options = fast_options();
  for(const std::string option : {" --rings 3,2", " --candidates 10", " --trws-iterations 30"})
    no_refinement_options.erase(no_refinement_options.find(option), option.size());
  std::string with_progress = no_refinement_options;
  with_progress.erase(with_progress.find(" --quiet"), std::string(" --quiet").size());
  const Run short_schedule = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch("s12.map") + " --out-21 " +
                                   in_scratch("s21.map") + " --stats " + in_scratch("short.json") +
                                   " --consistency-weight 0.75" + with_progress);
  BOOST_TEST_REQUIRE(short_schedule.code == 0, short_schedule.err);
  // The progress announces the settings actually used.
  BOOST_TEST(short_schedule.err.find("rings 4,3,2,1, 40 candidates") != std::string::npos, short_schedule.err);
  const std::string short_stats = read_text(in_scratch("short.json"));
  BOOST_TEST(short_stats.find("\"ring_schedule\": [4, 3, 2, 1]") != std::string::npos);
  BOOST_TEST(short_stats.find("\"number_of_candidates\": 40,") != std::string::npos);
  BOOST_TEST(short_stats.find("\"trws_number_of_iterations\": 15,") != std::string::npos);
  BOOST_TEST(short_stats.find("\"consistency_weight\": 0.75") != std::string::npos);
  const smc::Refinement_settings library;
  const Run given_defaults = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("s12.map") + " --init-21 " +
                                   in_scratch("s21.map") + " --out-12 " + in_scratch("d12.map") + " --out-21 " +
                                   in_scratch("d21.map") + " --stats " + in_scratch("given_defaults.json") +
                                   " --outer-iterations 1" + no_refinement_options);
  BOOST_TEST_REQUIRE(given_defaults.code == 0, given_defaults.err);
  const std::string given_stats = read_text(in_scratch("given_defaults.json"));
  BOOST_TEST(given_stats.find("\"ring_schedule\": [6, 4, 3, 2, 1]") != std::string::npos);
  BOOST_TEST(given_stats.find("\"number_of_candidates\": " + std::to_string(library.number_of_candidates) + ",") !=
             std::string::npos);
  BOOST_TEST(given_stats.find("\"trws_number_of_iterations\": " + std::to_string(library.trws_number_of_iterations) +
                              ",") != std::string::npos);

  // Automatic maps with the fast settings, then the whole pipeline with them.
  const Run fast_init = comap("match " + p.a + " " + p.b + " --no-refine --out-12 " + in_scratch("b12.map") +
                              " --out-21 " + in_scratch("b21.map") + fast_options());
  BOOST_TEST_REQUIRE(fast_init.code == 0, fast_init.err);
  const Run full = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch("f12.map") + " --out-21 " +
                         in_scratch("f21.map") + " --stats " + in_scratch("full.json") + " --keep-input on" +
                         fast_options());
  BOOST_TEST_REQUIRE(full.code == 0, full.err);
  const std::vector<std::size_t> f12 = read_map(in_scratch("f12.map"), 1), f21 = read_map(in_scratch("f21.map"), 1);
  BOOST_TEST(f12.size() == n1);
  // With --keep-input on, the refinement never returns maps less consistent than its input (the
  // automatic maps; the default for automatic maps returns the most consistent refined iterate).
  BOOST_TEST(smc::number_of_inconsistent_vertices(f12, f21) <=
             smc::number_of_inconsistent_vertices(read_map(in_scratch("b12.map"), 1), read_map(in_scratch("b21.map"), 1)));
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"initialization\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"keep_input\": \"on\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"keep_consistent_input_maps\": true") != std::string::npos);
  // Without --consistency-weight, automatic maps get the lighter cycle term.
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"consistency_weight\": 0.5,") != std::string::npos);

  // --stop-rule auto (the default) is the Eq. (4) early stop for automatic maps: the same maps as
  // --stop-rule consistency; the whole schedule (--stop-rule none, 2 outer iterations with
  // --rings 3,2) returns maps at least as consistent.
  auto run = [&](const std::string& rule, const std::string& tag) {
    const Run r = comap("match " + p.a + " " + p.b + " --out-12 " + in_scratch(tag + "12.map") + " --out-21 " +
                        in_scratch(tag + "21.map") + " --stats " + in_scratch(tag + ".json") + rule + fast_options());
    BOOST_TEST_REQUIRE(r.code == 0, r.err);
    return std::make_pair(read_map(in_scratch(tag + "12.map"), 1), read_map(in_scratch(tag + "21.map"), 1));
  };
  const auto light = run("", "light");  // every default
  const auto early = run(" --stop-rule consistency", "early"), all = run(" --stop-rule none", "all");
  BOOST_TEST((early.first == light.first && early.second == light.second));
  // The settings record the choice and what it means for these maps.
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"stop_rule\": \"auto\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("full.json")).find("\"stop_when_consistency_worsens\": true") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("all.json")).find("\"stop_rule\": \"none\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("all.json")).find("\"outer_iterations\": 2,") != std::string::npos);
  // With the cycle term of given maps (--consistency-weight 1) every refined iterate of these
  // automatic maps is more consistent than the one before, so the Eq. (4) early stop runs the whole
  // schedule and returns refined maps, more consistent than the automatic ones; the same maps given
  // as initial maps run the whole schedule without the early stop.
  const auto strong = run(" --keep-input on --consistency-weight 1", "strong");
  BOOST_TEST(read_text(in_scratch("strong.json")).find("\"outer_iterations\": 2,") != std::string::npos);
  BOOST_TEST(smc::number_of_inconsistent_vertices(strong.first, strong.second) <
             smc::number_of_inconsistent_vertices(read_map(in_scratch("b12.map"), 1), read_map(in_scratch("b21.map"), 1)));
  // The default for automatic maps (cycle weight 0.5, the most consistent refined iterate
  // returned) moves them further: more accurate than the automatic maps.
  const double automatic_error = mean_error(p.pair.m2, read_map(in_scratch("b12.map"), 1), p.pair.gt_12);
  const double light_error = mean_error(p.pair.m2, light.first, p.pair.gt_12);
  BOOST_TEST_MESSAGE("automatic map 1->2 " << automatic_error << ", refined (default) " << light_error);
  BOOST_TEST(read_text(in_scratch("light.json")).find("\"keep_input\": \"auto\"") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("light.json")).find("\"keep_consistent_input_maps\": false") != std::string::npos);
  BOOST_TEST(light_error < automatic_error);
  run(" --init-12 " + in_scratch("b12.map") + " --init-21 " + in_scratch("b21.map"), "given");
  BOOST_TEST(read_text(in_scratch("given.json")).find("\"outer_iterations\": 2,") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("given.json")).find("\"stop_when_consistency_worsens\": false") != std::string::npos);
  BOOST_TEST(read_text(in_scratch("given.json")).find("\"consistency_weight\": 1,") != std::string::npos);
  BOOST_TEST(smc::number_of_inconsistent_vertices(all.first, all.second) <=
             smc::number_of_inconsistent_vertices(f12, f21));
}

BOOST_AUTO_TEST_CASE(match_repairs_torn_maps)
{
  // Given maps that turn one end of the capsule (z > 3 of [-1, 5]) by 180 degrees about its axis: torn
  // along a ring; the rest (two thirds) is the core. --repair --no-refine writes exactly the maps of
  // the library's repair_torn_maps().
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
                      in_scratch("turned21.map") + " --index-base 0 --repair --no-refine --init-basis 40 --quiet" +
                      " --out-12 " + in_scratch("rep12.map") + " --out-21 " + in_scratch("rep21.map") + " --stats " +
                      in_scratch("repair.json"));
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  std::vector<std::size_t> l12 = t12, l21 = t21;
  const smc::Automatic_initialization_result lib =
      smc::repair_torn_maps<Tag>(p.pair.m1, p.pair.m2, l12, l21, smc::parameters::zoomout_final_size(40));
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
  BOOST_TEST(stats.find("\"repair\"") != std::string::npos);
  BOOST_TEST(stats.find("\"torn_fraction_before\"") != std::string::npos);
  // The kept repair pass's maps are maps of the automatic initialisation: they are refined with the
  // preset for automatic maps (consistency weight 0.5; 1 for given maps).
  BOOST_TEST(stats.find("\"consistency_weight\": 0.5,") != std::string::npos);
  // --compare-automatic: the given maps compete with the automatic maps, as they are or (with
  // --repair) repaired, exactly as in the library.
  double unrepaired_distortion = 0;
  for(const bool with_repair : {false, true})
  {
    const std::string tag = with_repair ? "rc" : "c";
    const Run c = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("turned12.map") + " --init-21 " +
                        in_scratch("turned21.map") + " --index-base 0 --compare-automatic" +
                        (with_repair ? " --repair" : "") + " --no-refine --init-basis 40 --quiet --out-12 " +
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
    BOOST_TEST(compare_stats.find("\"compared_with_automatic_maps\": true") != std::string::npos);
    BOOST_TEST(compare_stats.find(std::string("\"automatic_maps_kept\": ") +
                                  (compared.automatic_maps_kept ? "true" : "false")) != std::string::npos);
    // Unrepaired, the turned end is far more distorted than the automatic maps, which replace it
    // and are refined as automatic maps (consistency weight 0.5).
    if(!with_repair) BOOST_TEST(compared.automatic_maps_kept);
    if(compared.automatic_maps_kept)
      BOOST_TEST(compare_stats.find("\"consistency_weight\": 0.5,") != std::string::npos);
    if(!with_repair) unrepaired_distortion = compared.given_maps_distortion;
  }
  // --compare-automatic-above: given maps distorted less than the threshold are kept as they are,
  // without the automatic maps.
  const Run k = comap("match " + p.a + " " + p.b + " --init-12 " + in_scratch("turned12.map") + " --init-21 " +
                      in_scratch("turned21.map") + " --index-base 0 --compare-automatic --compare-automatic-above " +
                      std::to_string(1.01 * unrepaired_distortion) + " --no-refine --init-basis 40 --quiet" +
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
