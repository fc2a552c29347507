// SPDX-License-Identifier: GPL-3.0-or-later
// Benchmark of the geodesic machinery: speed and memory of every distance method and oracle,
// farthest point sampling and k-rings at the sizes the refinement meets, the accuracy of every
// method against exact geodesics (short and long range), and how often the refinement's pair
// queries fall inside the local oracle's radius.
//
//   bench_geodesics [--sizes 5000,25000,100000] [--skip-accuracy] [--skip-timing] [--sources N]
//
// Prints CSV and tables (see doc/geodesics.md for the figures measured on the reference machine).

#include <CGAL/Surface_mesh_correspondence/distance_oracle.h>
#include <CGAL/Surface_mesh_correspondence/geodesic_distances.h>
#include <CGAL/Surface_mesh_correspondence/neighborhoods.h>

#include "bench_util.h"
#include "../test/test_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace smci = CGAL::Surface_mesh_correspondence::internal;
using smc_bench::Report;
using smc_bench::Timer;

// Process CPU time (all threads), in seconds: with other jobs on the machine, wall time alone
// does not tell how much work a call did.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

namespace {

std::string num(double x, int p = 3) { return Report::num(x, p); }

// ---------------------------------------------------------------- accuracy

struct Error_accumulator
{
  double abs_sum = 0, rel_sum = 0, abs_max = 0;
  long count = 0;
  void add(double value, double exact, double scale)
  {
    const double e = std::abs(value - exact);
    abs_sum += e / scale;
    rel_sum += e / exact;
    abs_max = std::max(abs_max, e / scale);
    ++count;
  }
};

// Errors of every method against exact geodesics from `sources` random sources, split at 5 rings.
void accuracy(const std::string& name, const smci::Indexed_mesh& m, int sources, Report& report)
{
  const int n = m.number_of_vertices();
  const double scale = std::sqrt(m.total_area);
  Timer timer;
  smci::Exact_geodesic_solver exact(m);
  smci::Heat_method_solver heat(m);
  smci::Fast_marching_geometry circular(m, smci::Fast_marching_update::circular);
  smci::Fast_marching_geometry planar(m, smci::Fast_marching_update::planar);
  smci::Fast_marching_workspace ws_c(circular), ws_p(planar);
  const smc::Dense_distance_oracle dense =
      n <= 15000 ? smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m) : smc::Dense_distance_oracle();
  const double radius = smc::Matching_settings().oracle_radius * circular.graph.mean_edge_length;
  const smc::Local_distance_oracle local =
      smc::Local_distance_oracle::build<CGAL::Parallel_tag>(m, radius, smc::Matching_settings().oracle_landmarks);
  std::cerr << name << ": oracles built in " << timer.seconds() << " s\n";

  enum { EXACT_SELF, FMM, FMM_PLANAR, HEAT, DENSE, LOCAL, LOCAL_FAR, LOCAL_FAR_NEAR, METHODS };
  const char* method_names[METHODS] = {"exact", "fast_marching", "fast_marching_planar(KS98)", "heat_method",
                                       "dense_oracle", "local_oracle", "local_oracle_far_pairs",
                                       "local_oracle_far_pairs_d<2R"};
  Error_accumulator acc[METHODS][2];
  long local_pairs[2] = {0, 0}, all_pairs[2] = {0, 0};
  smci::K_ring_workspace rings(m);
  std::vector<int> ring;
  std::mt19937 rng(12345);
  std::vector<double> de, dh, dc, dp;
  for(int t = 0; t < sources; ++t)
  {
    const int s = std::uniform_int_distribution<int>(0, n - 1)(rng);
    exact.distances(s, de);
    heat.distances(s, dh);
    ws_c.run(s);
    ws_c.copy_distances(dc);
    ws_p.run(s);
    ws_p.copy_distances(dp);
    rings.k_ring(&s, 1, 5, ring);
    for(int v = 0; v < n; ++v)
    {
      if(v == s || !std::isfinite(de[v])) continue;
      const int range = rings.level(v) >= 0 ? 0 : 1;  // 0: within 5 rings
      acc[FMM][range].add(dc[v], de[v], scale);
      acc[FMM_PLANAR][range].add(dp[v], de[v], scale);
      acc[HEAT][range].add(dh[v], de[v], scale);
      if(dense.number_of_vertices() == n) acc[DENSE][range].add(dense.distance(s, v), de[v], scale);
      acc[LOCAL][range].add(local.distance(s, v), de[v], scale);
      ++all_pairs[range];
      if(local.is_local(s, v)) ++local_pairs[range];
      else
      {
        acc[LOCAL_FAR][range].add(local.distance(s, v), de[v], scale);
        if(de[v] < 2 * radius) acc[LOCAL_FAR_NEAR][range].add(local.distance(s, v), de[v], scale);
      }
    }
  }
  for(int k = FMM; k < METHODS; ++k)
    for(int range = 0; range < 2; ++range)
    {
      const Error_accumulator& a = acc[k][range];
      if(a.count == 0) continue;
      report.add({name, std::to_string(n), method_names[k], range == 0 ? "<=5 rings" : ">5 rings",
                  std::to_string(a.count), num(100 * a.abs_sum / a.count, 4), num(100 * a.abs_max, 3),
                  num(100 * a.rel_sum / a.count, 3)});
    }
  std::cerr << name << ": local oracle radius " << radius << " (" << smc::Matching_settings().oracle_radius
            << " mean edges), fraction of pairs inside: <=5 rings "
            << double(local_pairs[0]) / std::max(1L, all_pairs[0]) << ", >5 rings "
            << double(local_pairs[1]) / std::max(1L, all_pairs[1]) << ", covering radius / sqrt(area) "
            << local.covering_radius() / scale << "\n";
}

// Simulates the refinement's pairwise queries: for source edges (i, j), candidates of i are an
// FPS of the union of the r-rings of x(i) and x~(i) (x = identity, x~ = a vertex `spread` rings
// away), likewise for j; counts the candidate pairs (k, l) that the local oracle answers from its
// rows. The mesh plays both roles (only the target's distances matter).
void coverage(const smci::Indexed_mesh& m, const smc::Local_distance_oracle& local, Report& report)
{
  const int n = m.number_of_vertices();
  smci::Edge_length_graph graph(m);
  smci::K_ring_workspace rings(m), walk(m);
  smci::Farthest_point_sampler fps(graph);
  std::mt19937 rng(7);
  std::vector<int> set, phi_i, phi_j, tmp;
  auto drift = [&](int v, int spread) {
    if(spread == 0) return v;
    walk.k_ring(&v, 1, spread, tmp);
    std::vector<int> boundary;
    for(int u : tmp)
      if(walk.level(u) == spread) boundary.push_back(u);
    return boundary.empty() ? v : boundary[std::uniform_int_distribution<std::size_t>(0, boundary.size() - 1)(rng)];
  };
  for(int r : {6, 4, 3})
    for(int spread : {0, 2, 5})
    {
      long inside = 0, total = 0;
      for(int t = 0; t < 400; ++t)
      {
        const int i = std::uniform_int_distribution<int>(0, n - 1)(rng);
        const int j = m.neighbors[m.neighbor_offsets[i]];
        auto candidates = [&](int v, std::vector<int>& phi) {
          const int seeds[2] = {v, drift(v, spread)};
          rings.k_ring(seeds, 2, r, set);
          fps.sample(set.data(), set.size(), seeds, 2, 30, phi);
        };
        candidates(i, phi_i);
        candidates(j, phi_j);
        for(int k : phi_i)
          for(int l : phi_j)
          {
            ++total;
            if(k == l || local.is_local(k, l)) ++inside;
          }
      }
      report.add({std::to_string(r), std::to_string(spread), num(100.0 * inside / total, 2)});
    }
}

// ---------------------------------------------------------------- timing

void timing(int target_size, int sources, Report& report)
{
  std::string description;
  Timer timer;
  const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(target_size, &description);
  const smci::Indexed_mesh m = smci::make_indexed_mesh(mesh);
  const int n = m.number_of_vertices();
  std::cerr << "mesh " << n << " vertices (" << description << "), prepared in " << timer.seconds() << " s\n";
  const std::string size = std::to_string(n);
  // Times are per call (per build for builds); `cpu` is the process CPU time of the same calls.
  double cpu_start = cpu_seconds();
  auto add_cpu = [&](const std::string& what, double seconds, double cpu, double memory_mib, const std::string& note) {
    report.add({size, what, num(seconds * 1e6, 2), num(cpu * 1e6, 2), memory_mib > 0 ? num(memory_mib, 1) : "", note});
    std::cerr << "  " << what << ": " << seconds * 1e6 << " us (cpu " << cpu * 1e6 << " us)"
              << (memory_mib > 0 ? ", " + num(memory_mib, 1) + " MiB" : "") << " " << note << "\n";
  };
  // Per-call figures for `calls` calls since the last timer.reset() / cpu_start.
  auto add = [&](const std::string& what, double seconds, double memory_mib, const std::string& note,
                 double calls = 1) {
    add_cpu(what, seconds, (cpu_seconds() - cpu_start) / calls, memory_mib, note);
  };
  auto restart = [&]() {
    timer.reset();
    cpu_start = cpu_seconds();
  };
  std::mt19937 rng(1);
  std::vector<int> picks(sources);
  for(int& s : picks) s = std::uniform_int_distribution<int>(0, n - 1)(rng);

  // Heat method.
  smc_bench::reset_peak_memory();
  double base = smc_bench::current_memory_mib();
  restart();
  {
    smci::Heat_method_solver heat(m);
    add("heat_method_precomputation", timer.seconds(), smc_bench::peak_memory_mib() - base, "");
    std::vector<double> d;
    restart();
    for(int s : picks) heat.distances(s, d);
    add("heat_method_per_source", timer.seconds() / sources, 0, "", sources);
  }
  // Exact (5k only: about 0.2 s per source).
  if(n <= 6000)
  {
    smci::Exact_geodesic_solver exact(m);
    std::vector<double> d;
    restart();
    for(int k = 0; k < std::min(sources, 5); ++k) exact.distances(picks[k], d);
    add("exact_per_source", timer.seconds() / std::min(sources, 5), 0, "CGAL Surface_mesh_shortest_path",
        std::min(sources, 5));
  }
  // Fast marching.
  smci::Fast_marching_geometry geometry(m);
  smci::Fast_marching_workspace ws(geometry);
  const double radius = smc::Matching_settings().oracle_radius * geometry.graph.mean_edge_length;
  restart();
  for(int k = 0; k < 5 * sources; ++k) ws.run(picks[k % sources]);
  add("fast_marching_per_source_full", timer.seconds() / (5 * sources), 0, "", 5 * sources);
  restart();
  std::size_t accepted = 0;
  for(int k = 0; k < 20 * sources; ++k)
  {
    ws.run(picks[k % sources], radius);
    accepted += ws.accepted().size();
  }
  add("fast_marching_per_source_truncated", timer.seconds() / (20 * sources), 0,
      "R = " + std::to_string(smc::Matching_settings().oracle_radius) + " mean edges, " +
          std::to_string(accepted / (20 * sources)) + " vertices",
      20 * sources);
  // Dijkstra along edges (what farthest point sampling uses), full run, for comparison.
  {
    std::vector<double> d;
    restart();
    for(int k = 0; k < 5 * sources; ++k) smci::dijkstra_distances(geometry.graph, {picks[k % sources]}, d);
    add("dijkstra_per_source_full", timer.seconds() / (5 * sources), 0, "edge graph", 5 * sources);
  }
  // Early termination: distance between two random vertices.
  restart();
  for(int k = 0; k < 5 * sources; ++k)
  {
    const int a = picks[k % sources], b = picks[(k * 7 + 3) % sources];
    ws.run(&b, 1, std::numeric_limits<double>::infinity(), &a, 1);
  }
  add("fast_marching_pair_early_termination", timer.seconds() / (5 * sources), 0, "random pairs", 5 * sources);

  // Dense oracle (5k only).
  if(n <= 6000)
  {
    for(int parallel = 0; parallel < 2; ++parallel)
    {
      smc_bench::reset_peak_memory();
      base = smc_bench::current_memory_mib();
      restart();
      const smc::Dense_distance_oracle dense = parallel ? smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m)
                                                        : smc::Dense_distance_oracle::build<CGAL::Sequential_tag>(m);
      add(parallel ? "dense_oracle_build_parallel" : "dense_oracle_build_sequential", timer.seconds(),
          smc_bench::peak_memory_mib() - base, "fast marching rows");
      if(parallel)
      {
        std::vector<int> ks(1 << 20), ls(1 << 20);
        for(std::size_t q = 0; q < ks.size(); ++q)
        {
          ks[q] = std::uniform_int_distribution<int>(0, n - 1)(rng);
          ls[q] = std::uniform_int_distribution<int>(0, n - 1)(rng);
        }
        restart();
        double sum = 0;
        for(std::size_t q = 0; q < ks.size(); ++q) sum += dense.distance(ks[q], ls[q]);
        add("dense_oracle_query_random_pair", timer.seconds() / ks.size(), 0, sum > 0 ? "" : "?",
            static_cast<double>(ks.size()));
      }
    }
    smc_bench::reset_peak_memory();
    restart();
    const smc::Dense_distance_oracle heat_dense = smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(
        m, smc::Geodesic_method::heat_method);
    add("dense_oracle_build_parallel_heat_method", timer.seconds(), 0, "");
  }

  // Local oracle.
  smc_bench::reset_peak_memory();
  base = smc_bench::current_memory_mib();
  restart();
  const smc::Local_distance_oracle local =
      smc::Local_distance_oracle::build<CGAL::Parallel_tag>(m, radius, smc::Matching_settings().oracle_landmarks);
  const double build = timer.seconds();
  add("local_oracle_build_parallel", build, smc_bench::peak_memory_mib() - base,
      "oracle " + num(local.memory_bytes() / 1048576.0, 1) + " MiB, " +
          num(double(local.number_of_local_entries()) / n, 1) + " entries/row, " +
          std::to_string(local.number_of_landmarks()) + " landmarks");

  // Candidate selection: k-rings and FPS on the union of the 6-rings of two vertices 3 rings apart.
  smci::K_ring_workspace rings(m), walk(m);
  smci::Farthest_point_sampler fps(geometry.graph);
  std::vector<int> set, samples, tmp;
  const int calls = 20000;
  std::vector<std::array<int, 2> > pairs(calls);
  for(auto& p : pairs)
  {
    p[0] = std::uniform_int_distribution<int>(0, n - 1)(rng);
    walk.k_ring(&p[0], 1, 3, tmp);
    p[1] = tmp.back();
  }
  for(int r : {6, 4, 3})
  {
    restart();
    std::size_t total = 0;
    for(const auto& p : pairs)
    {
      rings.k_ring(p.data(), 2, r, set);
      total += set.size();
    }
    add("k_ring_union_of_two_r" + std::to_string(r), timer.seconds() / calls, 0,
        "mean |set| " + num(double(total) / calls, 1), calls);
    for(int count : {20, 30})
    {
      restart();
      for(const auto& p : pairs)
      {
        rings.k_ring(p.data(), 2, r, set);
        fps.sample(set.data(), set.size(), p.data(), 2, count, samples);
      }
      add("k_ring_and_fps_r" + std::to_string(r) + "_m" + std::to_string(count), timer.seconds() / calls, 0,
          "per source vertex", calls);
    }
  }

  // Pair queries as the refinement issues them: rows of m = 30 candidates against 30 candidates.
  {
    std::vector<std::vector<int> > phi(2000);
    for(std::size_t t = 0; t < phi.size(); ++t)
    {
      const auto& p = pairs[t];
      rings.k_ring(p.data(), 2, 6, set);
      fps.sample(set.data(), set.size(), p.data(), 2, 30, phi[t]);
    }
    std::vector<float> out(30);
    restart();
    double sum = 0;
    long queries = 0;
    for(int rep = 0; rep < 5; ++rep)
      for(std::size_t t = 0; t < phi.size(); ++t)
      {
        // Candidates of t against those of a nearby set (the next pair shares nothing, so use t
        // itself: the typical case of neighbouring sources with similar candidates).
        for(int k : phi[t])
        {
          local.distances(k, phi[t].data(), phi[t].size(), out.data());
          sum += out[0];
          queries += static_cast<long>(phi[t].size());
        }
      }
    add("local_oracle_query_candidate_rows", timer.seconds() / queries, 0, "30 x 30 batches, local pairs",
        static_cast<double>(queries));
    std::vector<int> ks(1 << 18), ls(1 << 18);
    for(std::size_t q = 0; q < ks.size(); ++q)
    {
      ks[q] = std::uniform_int_distribution<int>(0, n - 1)(rng);
      ls[q] = std::uniform_int_distribution<int>(0, n - 1)(rng);
    }
    restart();
    for(std::size_t q = 0; q < ks.size(); ++q) sum += local.distance(ks[q], ls[q]);
    add("local_oracle_query_random_pair", timer.seconds() / ks.size(), 0, sum > 0 ? "mostly far (landmarks)" : "?",
        static_cast<double>(ks.size()));
  }
}

std::vector<int> parse_sizes(const std::string& s)
{
  std::vector<int> out;
  std::stringstream in(s);
  std::string item;
  while(std::getline(in, item, ',')) out.push_back(std::stoi(item));
  return out;
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<int> sizes = {5000, 25000, 100000};
  bool do_accuracy = true, do_timing = true;
  int sources = 20;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--sizes" && i + 1 < argc) sizes = parse_sizes(argv[++i]);
    else if(a == "--skip-accuracy") do_accuracy = false;
    else if(a == "--skip-timing") do_timing = false;
    else if(a == "--sources" && i + 1 < argc) sources = std::atoi(argv[++i]);
    else
    {
      std::cerr << "usage: bench_geodesics [--sizes 5000,25000,100000] [--skip-accuracy] [--skip-timing] "
                   "[--sources N]\n";
      return 1;
    }
  }

  if(do_accuracy)
  {
    Report report({"shape", "n", "method", "range", "pairs", "mean_abs_err_pct_sqrtA", "max_abs_err_pct_sqrtA",
                   "mean_rel_err_pct"});
    std::vector<std::pair<std::string, smc_bench::Mesh> > shapes;
    smc_bench::Mesh shape;
    if(smc_bench::read_mesh(smc_bench::data_directory() + "/TOSCA_r/off/david0.off", shape))
      shapes.emplace_back("TOSCA_r/david0", shape);
    if(smc_bench::read_mesh(smc_bench::data_directory() + "/FAUST_r/off/tr_reg_000.off", shape))
      shapes.emplace_back("FAUST_r/tr_reg_000", shape);
    if(shapes.empty()) std::cerr << "shared data not found (" << smc_bench::data_directory() << "): sphere only\n";
    shapes.emplace_back("icosphere(5)", smc_test::icosphere(5));
    Report cover({"rings_r", "x_vs_xtilde_rings", "pct_candidate_pairs_local"});
    for(const auto& s : shapes)
    {
      const smci::Indexed_mesh m = smci::make_indexed_mesh(s.second);
      accuracy(s.first, m, sources, report);
      if(s.first == shapes.front().first)
      {
        const double radius = smc::Matching_settings().oracle_radius * smci::Edge_length_graph(m).mean_edge_length;
        const smc::Local_distance_oracle local = smc::Local_distance_oracle::build<CGAL::Parallel_tag>(m, radius, 64);
        coverage(m, local, cover);
      }
    }
    std::cout << "=== accuracy against exact geodesics (CGAL Surface_mesh_shortest_path), " << sources
              << " random sources per shape; errors in % of sqrt(area) and relative %\n";
    report.print();
    std::cout << "=== refinement pair queries inside the local radius (" << smc::Matching_settings().oracle_radius
              << " mean edge lengths), " << shapes.front().first << ", 400 source edges x 30 x 30 candidates\n";
    cover.print();
  }
  if(do_timing)
  {
    Report report({"n", "what", "wall_us", "cpu_us", "peak_MiB", "note"});
    for(int size : sizes) timing(size, sources, report);
    std::cout << "=== timing (microseconds per call or build; cpu = process CPU time, all threads) and peak memory\n";
    report.print();
  }
  return 0;
}
