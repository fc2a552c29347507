// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap bench on a two-pair dataset made by the test, laid out like FAUST_r / TOSCA_r (off/,
// corres/*.vts and *.sym.vts, a tab-separated pairs file ending with an empty line, 1-based
// initial maps): outputs present and consistent, refined maps re-evaluated with the library give
// the figures of the CSV.

#include <CGAL/Surface_mesh/IO/OFF.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>

#include "test_cli_helpers.h"

#include <boost/test/unit_test.hpp>

#include <fstream>
#include <map>

namespace smc = CGAL::Surface_mesh_correspondence;
using namespace smc_cli_test;

namespace {

/// Composes a (from -> template) with b (template -> to): the map from -> to.
std::vector<std::size_t> compose(const std::vector<std::size_t>& a, const std::vector<std::size_t>& b)
{
  std::vector<std::size_t> out(a.size());
  for(std::size_t i = 0; i < a.size(); ++i) out[i] = b[a[i]];
  return out;
}

struct Dataset
{
  std::string dir;
  Mesh s0, s1, s2;
  std::vector<std::size_t> vts0, vts1, vts2;
  Dataset()
  {
    dir = in_scratch("dataset");
    std::filesystem::create_directories(dir + "/off");
    std::filesystem::create_directories(dir + "/corres");
    std::filesystem::create_directories(dir + "/maps/noisy");
    const Cli_pair& p = cli_pair();
    const Shape_pair second = bent_pair(p.pair.m1, 4.0, 0.5, true);
    s0 = p.pair.m1;
    s1 = p.pair.m2;
    s2 = second.m2;
    // The template is s0: sample k is vertex k of s0.
    vts0 = identity(num_vertices(s0));
    vts1 = p.pair.gt_12;
    vts2 = second.gt_12;
    write_off(dir + "/off/s0.off", s0);
    write_off(dir + "/off/s1.off", s1);
    write_off(dir + "/off/s2.off", s2);
    write_map(dir + "/corres/s0.vts", vts0, 1);
    write_map(dir + "/corres/s1.vts", vts1, 1);
    write_map(dir + "/corres/s2.vts", vts2, 1);
    write_map(dir + "/corres/s0.sym.vts", vts0, 1);  // s2 has no mirrored ground truth
    write_map(dir + "/corres/s1.sym.vts", vts1, 1);
    write_text(dir + "/test_pairs.txt", "s0\ts1\ns1\ts2\n\n");
    write_map(dir + "/maps/noisy/s0_s1.map", p.noisy_12, 1);
    write_map(dir + "/maps/noisy/s1_s0.map", p.noisy_21, 1);
    write_map(dir + "/maps/noisy/s1_s2.map", perturbed(compose(p.pair.gt_21, second.gt_12), s2, 0.4, 2, 3), 1);
    write_map(dir + "/maps/noisy/s2_s1.map", perturbed(compose(second.gt_21, p.pair.gt_12), s1, 0.4, 2, 4), 1);
  }
};

const Dataset& dataset()
{
  static const Dataset d;
  return d;
}

std::vector<std::map<std::string, std::string> > read_csv(const std::string& file)
{
  std::vector<std::map<std::string, std::string> > rows;
  const std::vector<std::string> lines = lines_of(read_text(file));
  if(lines.empty()) return rows;
  auto fields = [](const std::string& line) {
    std::vector<std::string> f;
    std::string x;
    std::istringstream in(line);
    while(std::getline(in, x, ',')) f.push_back(x);
    if(!line.empty() && line.back() == ',') f.emplace_back();
    return f;
  };
  const std::vector<std::string> header = fields(lines[0]);
  for(std::size_t i = 1; i < lines.size(); ++i)
  {
    const std::vector<std::string> f = fields(lines[i]);
    std::map<std::string, std::string> row;
    for(std::size_t c = 0; c < header.size() && c < f.size(); ++c) row[header[c]] = f[c];
    rows.push_back(row);
  }
  return rows;
}

} // namespace

BOOST_AUTO_TEST_SUITE(cli_bench)

BOOST_AUTO_TEST_CASE(bench_on_a_two_pair_dataset)
{
  const Dataset& d = dataset();
  const std::string out = in_scratch("bench_out");
  // The given maps as they are: neither repaired nor compared with the automatic maps.
  const Run r = comap("bench --data " + d.dir + " --init " + d.dir + "/maps/noisy --out " + out + " --jobs 2" +
                      fast_options() + " --set repair_given_maps=false --set compare_with_automatic_maps=false");
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("2 pairs (4 maps)") != std::string::npos);
  const auto rows = read_csv(out + "/pairs.csv");
  BOOST_TEST_REQUIRE(rows.size() == 4u);
  BOOST_TEST(rows[0].at("pair") == "s0_s1");
  BOOST_TEST(rows[0].at("direction") == "12");
  BOOST_TEST(rows[3].at("pair") == "s1_s2");
  BOOST_TEST(rows[3].at("source") == "s2");
  for(const char* column : {"initial_error", "refined_sym_error", "initial_cycle_error", "refined_fixed_points",
                            "preprocessing_seconds", "data_preparation_seconds", "trws_seconds"})
    BOOST_TEST(rows[0].count(column) == 1u, column);
  BOOST_TEST(rows[0].at("automatic_maps_kept") == "");  // no comparison
  BOOST_TEST(rows[0].at("given_maps_distortion") == "");
  BOOST_TEST(rows[0].at("automatic_maps_distortion") == "");
  BOOST_TEST(rows[0].at("refined_as_automatic") == "0");  // given maps, not repaired
  // Every refined map is written, 1-based, and re-evaluating it gives the CSV's figure.
  const std::vector<std::pair<std::string, const Mesh*> > maps = {
      {"s0_s1", &d.s1}, {"s1_s0", &d.s0}, {"s1_s2", &d.s2}, {"s2_s1", &d.s1}};
  const std::map<std::string, const std::vector<std::size_t>*> vts = {{"s0", &d.vts0}, {"s1", &d.vts1}, {"s2", &d.vts2}};
  const std::map<std::string, const Mesh*> meshes = {{"s0", &d.s0}, {"s1", &d.s1}, {"s2", &d.s2}};
  for(std::size_t i = 0; i < maps.size(); ++i)
  {
    const std::string a = maps[i].first.substr(0, 2), b = maps[i].first.substr(3, 2);
    const std::vector<std::size_t> m = read_map(out + "/maps/" + maps[i].first + ".map", 1);
    BOOST_TEST_REQUIRE(m.size() == num_vertices(*meshes.at(a)));
    const double error = smc::Map_evaluator<>(*maps[i].second).geodesic_errors(m, *vts.at(a), *vts.at(b)).mean;
    const auto& row = rows[i];  // pair by pair, direction 12 then 21
    BOOST_TEST(row.at("source") == a);
    BOOST_TEST(std::abs(std::stod(row.at("refined_error")) - error) <= 1e-9 * (1 + error), maps[i].first);
  }
  // Symmetry-tolerant errors where the target has a .sym.vts (here equal to the direct one).
  BOOST_TEST(rows[0].at("refined_sym_error") != "");
  BOOST_TEST(std::stod(rows[0].at("refined_sym_error")) <= std::stod(rows[0].at("refined_error")) + 1e-12);
  BOOST_TEST(rows[2].at("refined_sym_error") == "");  // s1 -> s2: no s2.sym.vts
  // The refinement improves these noisy maps and does not make them less consistent.
  for(const auto& row : rows)
  {
    BOOST_TEST(std::stod(row.at("refined_error")) < std::stod(row.at("initial_error")));
    BOOST_TEST(std::stoul(row.at("inconsistent_after")) <= std::stoul(row.at("inconsistent_before")));
  }
  const std::string summary = read_text(out + "/summary.json");
  BOOST_TEST(summary.find("\"pairs\": 2") != std::string::npos);
  BOOST_TEST(summary.find("\"median_seconds_per_pair\"") != std::string::npos);
  for(const char* svg : {"cumulative_error.svg", "cycle_consistency.svg", "per_pair_error.svg"})
  {
    const std::string text = read_text(out + "/" + svg);
    BOOST_TEST(text.rfind("<?xml", 0) == 0u, svg);
    BOOST_TEST(text.find("<polyline") != std::string::npos, svg);
  }
}

BOOST_AUTO_TEST_CASE(bench_from_ground_truth_landmarks)
{
  const Dataset& d = dataset();
  const std::string out = in_scratch("bench_landmarks");
  const Run r = comap("bench --data " + d.dir + " --out " + out + " --limit 1 --ground-truth-landmarks 3" +
                      fast_options());
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(read_text(out + "/summary.json").find("\"ground_truth_landmarks\": 3") != std::string::npos);
  // The landmarks, by brute force: the first sample of s0, then each time the sample farthest from
  // those chosen, with the ground truth of s1 (on the points of the file, as bench reads them).
  Mesh s0;
  {
    std::ifstream in(d.dir + "/off/s0.off");
    BOOST_TEST_REQUIRE(CGAL::IO::read_OFF(in, s0));
  }
  BOOST_TEST_REQUIRE(num_vertices(s0) == num_vertices(d.s0));
  auto sample = [&](std::size_t k) { return s0.point(Vertex(static_cast<Mesh::size_type>(d.vts0[k]))); };
  std::vector<std::size_t> chosen = {0};
  while(chosen.size() < 3)
  {
    std::size_t best = 0;
    double best_distance = -1;
    for(std::size_t k = 0; k < d.vts0.size(); ++k)
    {
      double nearest = 1e300;
      for(std::size_t c : chosen) nearest = std::min(nearest, std::sqrt(CGAL::squared_distance(sample(k), sample(c))));
      if(nearest > best_distance)
      {
        best_distance = nearest;
        best = k;
      }
    }
    chosen.push_back(best);
  }
  std::string landmarks;
  for(std::size_t k : chosen) landmarks += std::to_string(d.vts0[k] + 1) + " " + std::to_string(d.vts1[k] + 1) + "\n";
  const std::string landmark_file = in_scratch("bench_landmarks.txt");
  write_text(landmark_file, landmarks);
  // comap match from those landmarks gives the maps of the bench.
  const std::string m12 = in_scratch("bench_landmarks_12.map"), m21 = in_scratch("bench_landmarks_21.map");
  const Run m = comap("match " + d.dir + "/off/s0.off " + d.dir + "/off/s1.off --landmarks " + landmark_file +
                      " --out-12 " + m12 + " --out-21 " + m21 + fast_options());
  BOOST_TEST_REQUIRE(m.code == 0, m.err);
  BOOST_TEST(read_map(m12, 1) == read_map(out + "/maps/s0_s1.map", 1));
  BOOST_TEST(read_map(m21, 1) == read_map(out + "/maps/s1_s0.map", 1));
  // The landmarks guide the automatic initial maps: not with given maps.
  const Run both = comap("bench --data " + d.dir + " --init " + d.dir + "/maps/noisy --out " +
                         in_scratch("bench_landmarks_init") + " --ground-truth-landmarks 3");
  BOOST_TEST(both.code == 2);
  BOOST_TEST(both.err.find("--ground-truth-landmarks") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(bench_automatic_pipeline_and_comparison_plot)
{
  const Dataset& d = dataset();
  const std::string out = in_scratch("bench_auto");
  const Run r = comap("bench --data " + d.dir + " --out " + out + " --limit 1" + fast_options());
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(read_map(out + "/unrefined_maps/s0_s1.map", 1).size() == num_vertices(d.s0));
  BOOST_TEST(read_map(out + "/maps/s1_s0.map", 1).size() == num_vertices(d.s1));
  BOOST_TEST(lines_of(read_text(out + "/pairs.csv")).size() == 3u);
  BOOST_TEST(read_csv(out + "/pairs.csv")[0].at("refined_as_automatic") == "1");
  // bench runs the library's entry point as comap match does (there on prepared shapes, here on
  // the meshes): the same maps.
  const std::string m12 = in_scratch("bench_auto_match_12.map"), m21 = in_scratch("bench_auto_match_21.map");
  const Run m = comap("match " + d.dir + "/off/s0.off " + d.dir + "/off/s1.off --out-12 " + m12 + " --out-21 " + m21 +
                      fast_options());
  BOOST_TEST_REQUIRE(m.code == 0, m.err);
  BOOST_TEST(read_map(m12, 1) == read_map(out + "/maps/s0_s1.map", 1));
  BOOST_TEST(read_map(m21, 1) == read_map(out + "/maps/s1_s0.map", 1));
  // Given maps compared with the automatic ones (on every pair: threshold 0), not refined: the
  // column says which were kept, and maps kept from the automatic initialisation count as
  // automatic maps.
  const std::string compared = in_scratch("bench_compare");
  const Run c = comap("bench --data " + d.dir + " --init " + d.dir + "/maps/noisy --out " + compared +
                      " --limit 1" + fast_options() +
                      " --set repair_given_maps=false --set automatic_maps_comparison_threshold=0"
                      " --set use_refinement=false");
  BOOST_TEST_REQUIRE(c.code == 0, c.err);
  const auto rows = read_csv(compared + "/pairs.csv");
  BOOST_TEST_REQUIRE(rows.size() == 2u);
  BOOST_TEST((rows[0].at("automatic_maps_kept") == "0" || rows[0].at("automatic_maps_kept") == "1"));
  BOOST_TEST(rows[0].at("refined_as_automatic") == rows[0].at("automatic_maps_kept"));
  // Both distortions compared, and the kept maps are the less distorted ones.
  const double given_distortion = std::stod(rows[0].at("given_maps_distortion"));
  const double automatic_distortion = std::stod(rows[0].at("automatic_maps_distortion"));
  BOOST_TEST(given_distortion > 0);
  BOOST_TEST(automatic_distortion > 0);
  BOOST_TEST((rows[0].at("automatic_maps_kept") == "1") == (automatic_distortion < given_distortion));
  BOOST_TEST(read_map(compared + "/unrefined_maps/s0_s1.map", 1) == read_map(compared + "/maps/s0_s1.map", 1));
  BOOST_TEST(read_text(compared + "/summary.json").find("\"compare_with_automatic_maps\": true") != std::string::npos);
  // A non-coupled run compared with the coupled one: both curves in its plot.
  const std::string ablation = in_scratch("bench_ablation");
  const Run a = comap("bench --data " + d.dir + " --out " + ablation + " --limit 1 --compare " + out + fast_options() +
                      " --set use_coupling=false");
  BOOST_TEST_REQUIRE(a.code == 0, a.err);
  const std::string svg = read_text(ablation + "/cumulative_error.svg");
  BOOST_TEST(svg.find("refined (non-coupled)") != std::string::npos);
  BOOST_TEST(svg.find("refined (coupled)") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
