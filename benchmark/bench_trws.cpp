// SPDX-License-Identifier: GPL-3.0-or-later
// TRW-S benchmark.
//
// 1. A CoMap-shaped MRF: nodes = vertices of a ~5k-vertex closed mesh, edges = its edges, m labels
//    per node (m = 10, 20, 30, 40), each label of node i with a random value a_i(k), pairwise
//    costs |a_s(k) - a_t(l)| (the shape of |d_a(i, j) - d_b(k, l)|), random unary costs. Edges
//    are numbered as internal::Indexed_mesh numbers them (i < j, sorted), so that the forward
//    pass reads the tables in storage order; two rows show the mesh's own edge order and a
//    breadth-first renumbering of the nodes. For
//    tables and functor, float and double: milliseconds per iteration (median over the timed
//    iterations, thread CPU time), iterations until the
//    bound's relative change is below 1e-4 and the time of that run (setup and cost check
//    included), peak memory, achieved min-plus operations per second
//    (one iteration = 2 |E| m^2 min-plus operations).
// 2. The min-plus kernels alone on the same tables: multi-versioned SIMD vs portable loops.
// 3. A 256 x 256 grid, 16 labels, truncated linear costs (image restoration).
// 4. Trws_solver<float, CGAL::Parallel_tag> against Trws_solver<float> on the CoMap-shaped MRF
//    with breadth-first numbered nodes (the numbering of the refinement), float tables, 15 iterations as in the
//    refinement of automatic maps: wall-clock time (best of 5) and whether the runs are identical.
//
// Usage: bench_trws [number_of_vertices (5000)] [iterations timed (30)] [labels (10,20,30,40)]

#include "bench_util.h"

#include <CGAL/Surface_mesh_correspondence/trws.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <malloc.h>
#include <time.h>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using smc_bench::Report;

namespace {

struct Mrf_shape
{
  std::size_t n = 0;
  std::vector<std::pair<std::size_t, std::size_t> > edges;
  std::vector<std::size_t> vertex; // mesh vertex of each node (the costs follow the vertices)
};

// |a_s(k) - a_t(l)| computed on the fly from the per-label values.
template <typename FT>
struct Abs_difference_cost
{
  const std::vector<FT>* values = nullptr; // n x m
  const std::vector<std::pair<std::size_t, std::size_t> >* edges = nullptr;
  std::size_t m = 0;
  FT operator()(std::size_t e, std::size_t k, std::size_t l) const
  {
    const FT a = (*values)[(*edges)[e].first * m + k], b = (*values)[(*edges)[e].second * m + l];
    return std::abs(a - b);
  }
};

// The same graph with the nodes renumbered in breadth-first order (neighbours get close indices),
// edges as (i, j), i < j, sorted.
Mrf_shape breadth_first_renumbered(const Mrf_shape& shape)
{
  std::vector<std::vector<std::size_t> > adjacent(shape.n);
  for(const auto& e : shape.edges)
  {
    adjacent[e.first].push_back(e.second);
    adjacent[e.second].push_back(e.first);
  }
  const std::size_t unset = std::size_t(-1);
  std::vector<std::size_t> new_index(shape.n, unset), queue;
  for(std::size_t root = 0; root < shape.n; ++root)
  {
    if(new_index[root] != unset) continue;
    new_index[root] = queue.size();
    queue.push_back(root);
    for(std::size_t head = queue.size() - 1; head < queue.size(); ++head)
      for(std::size_t t : adjacent[queue[head]])
        if(new_index[t] == unset)
        {
          new_index[t] = queue.size();
          queue.push_back(t);
        }
  }
  Mrf_shape result;
  result.n = shape.n;
  result.vertex.resize(shape.n);
  for(std::size_t i = 0; i < shape.n; ++i) result.vertex[new_index[i]] = shape.vertex[i];
  for(const auto& e : shape.edges)
    result.edges.emplace_back(std::min(new_index[e.first], new_index[e.second]),
                              std::max(new_index[e.first], new_index[e.second]));
  std::sort(result.edges.begin(), result.edges.end());
  return result;
}

// CPU time of the calling thread, in seconds: unlike wall-clock time, it does not count the time
// the thread waits while other processes use the (shared) cores.
double thread_cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Times each iteration (between consecutive visitor calls: a backward then a forward pass).
struct Iteration_timer
{
  std::vector<double> stamps;
  bool iteration(std::size_t, double, double)
  {
    stamps.push_back(thread_cpu_seconds());
    return true;
  }
  double median_ms_per_iteration() const
  {
    std::vector<double> d;
    for(std::size_t i = 1; i < stamps.size(); ++i) d.push_back(stamps[i] - stamps[i - 1]);
    if(d.empty()) return 0.0;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return 1e3 * d[d.size() / 2];
  }
};

struct Run
{
  double ms_per_iteration = 0, solve_ms = 0, energy = 0, bound = 0, peak_mib = 0, model_mib = 0;
  std::size_t iterations = 0;
  std::string termination;
};

template <typename FT, typename Energy>
Run time_energy(const Energy& energy, std::size_t timed_iterations)
{
  Run run;
  smc::Trws_solver<FT> solver;
  std::vector<int> labels;
  Iteration_timer timer;
  solver.solve(energy, labels,
               params::relative_tolerance(0.0)
                   .number_of_iterations(timed_iterations)
                   .visitor(std::ref(timer)));
  run.ms_per_iteration = timer.median_ms_per_iteration();
  const double start = thread_cpu_seconds();
  const smc::Trws_result r =
      solver.solve(energy, labels, params::relative_tolerance(1e-4).number_of_iterations(2000));
  run.solve_ms = 1e3 * (thread_cpu_seconds() - start);
  run.iterations = r.number_of_iterations;
  run.termination = smc::to_string(r.termination);
  run.energy = r.energy;
  run.bound = r.lower_bound;
  run.model_mib = double(energy.memory_bytes() + solver.memory_bytes()) / (1024.0 * 1024.0);
  return run;
}

// Returns freed heap memory to the system, so that the next measurement's allocations show in the
// resident set size, then starts a new peak.
double start_memory_measurement()
{
  malloc_trim(0);
  const double rss = smc_bench::current_memory_mib();
  smc_bench::reset_peak_memory();
  return rss;
}

// Calls f(energy) with the CoMap-shaped energy of `shape` with m labels (stored tables or the
// functor). Random label values and unary costs are drawn per mesh vertex, so that renumbered nodes
// get the same energy.
template <typename FT, typename F>
void with_comap_energy(const Mrf_shape& shape, std::size_t m, bool tables, const F& f)
{
  std::mt19937 rng{static_cast<unsigned>(m)};
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<FT> vertex_values(shape.n * m), vertex_unary(shape.n * m), values(shape.n * m);
  for(FT& v : vertex_values) v = FT(u(rng));
  for(FT& v : vertex_unary) v = FT(0.5 * u(rng));
  for(std::size_t i = 0; i < shape.n; ++i)
    std::copy_n(vertex_values.begin() + shape.vertex[i] * m, m, values.begin() + i * m);
  const std::vector<std::size_t> counts(shape.n, m);
  auto fill_unary = [&](auto& energy) {
    for(std::size_t i = 0; i < shape.n; ++i)
      std::copy_n(vertex_unary.begin() + shape.vertex[i] * m, m, energy.unary_costs(i));
  };
  Abs_difference_cost<FT> cost{&values, &shape.edges, m};
  if(tables)
  {
    smc::Discrete_energy<FT> energy(counts, shape.edges);
    fill_unary(energy);
    for(std::size_t e = 0; e < shape.edges.size(); ++e)
    {
      FT* table = energy.pairwise_costs(e);
      for(std::size_t k = 0; k < m; ++k)
        for(std::size_t l = 0; l < m; ++l) table[k * m + l] = cost(e, k, l);
    }
    f(energy);
  }
  else
  {
    smc::Discrete_energy<FT, Abs_difference_cost<FT> > energy(counts, shape.edges, cost);
    fill_unary(energy);
    f(energy);
  }
}

template <typename FT>
Run comap_run(const Mrf_shape& shape, std::size_t m, bool tables, std::size_t timed_iterations)
{
  const double rss_before = start_memory_measurement();
  Run run;
  with_comap_energy<FT>(shape, m, tables, [&](const auto& energy) { run = time_energy<FT>(energy, timed_iterations); });
  run.peak_mib = smc_bench::peak_memory_mib() - rss_before;
  return run;
}

// The kernels alone: per edge one message to the target and one to the source, i.e. one
// iteration's min-plus work, with the multi-versioned kernels and with the portable loops.
template <typename FT>
void kernel_rows(Report& report, std::size_t edges, std::size_t m)
{
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<FT> tables(edges * m * m), a(m), out(m);
  for(FT& t : tables) t = FT(u(rng));
  for(FT& x : a) x = FT(u(rng));
  auto measure = [&](auto&& to_target, auto&& to_source) {
    double best = 1e30;
    FT sink = 0;
    for(int rep = 0; rep < 5; ++rep)
    {
      const double start = thread_cpu_seconds();
      for(std::size_t e = 0; e < edges; ++e)
      {
        to_target(a.data(), tables.data() + e * m * m, m, m, out.data());
        sink += out[0];
        to_source(a.data(), tables.data() + e * m * m, m, m, out.data());
        sink += out[1];
      }
      best = std::min(best, thread_cpu_seconds() - start);
    }
    if(sink == FT(-1)) std::cout << "";
    return best * 1e3;
  };
  const double simd =
      measure([](const FT* x, const FT* t, std::size_t ks, std::size_t kt,
                 FT* o) { smc::internal::trws_min_plus_to_target(x, t, ks, kt, o); },
              [](const FT* x, const FT* t, std::size_t ks, std::size_t kt, FT* o) {
                smc::internal::trws_min_plus_to_source(x, t, ks, kt, o);
              });
  const double scalar =
      measure([](const FT* x, const FT* t, std::size_t ks, std::size_t kt,
                 FT* o) { smc::internal::trws_kernels::to_target_scalar(x, t, ks, kt, o); },
              [](const FT* x, const FT* t, std::size_t ks, std::size_t kt, FT* o) {
                smc::internal::trws_kernels::to_source_scalar(x, t, ks, kt, o);
              });
  const double ops = 2.0 * double(edges) * double(m * m);
  report.add({sizeof(FT) == 4 ? "float" : "double", std::to_string(m), std::to_string(edges),
              Report::num(simd, 3), Report::num(ops / (simd * 1e-3) * 1e-9, 2),
              Report::num(scalar, 3), Report::num(ops / (scalar * 1e-3) * 1e-9, 2),
              Report::num(scalar / simd, 2)});
}

template <typename FT>
void grid_run(Report& report, int size, std::size_t labels, bool tables,
              std::size_t timed_iterations)
{
  const double rss_before = start_memory_measurement();
  // A piecewise smooth image with Gaussian noise; unary (I - k)^2 / 8, pairwise
  // lambda min(|k - l|, T) with lambda = 2, T = 3.
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  const std::size_t n = std::size_t(size) * size;
  std::vector<std::pair<std::size_t, std::size_t> > edges;
  for(int y = 0; y < size; ++y)
    for(int x = 0; x < size; ++x)
    {
      if(x + 1 < size) edges.emplace_back(std::size_t(y) * size + x, std::size_t(y) * size + x + 1);
      if(y + 1 < size) edges.emplace_back(std::size_t(y) * size + x, std::size_t(y + 1) * size + x);
    }
  const std::vector<std::size_t> counts(n, labels);
  auto truncated_linear = [](std::size_t, std::size_t k, std::size_t l) {
    return FT(2.0 * std::min(3.0, std::abs(double(k) - double(l))));
  };
  auto fill_unary = [&](auto& energy) {
    for(int y = 0; y < size; ++y)
      for(int x = 0; x < size; ++x)
      {
        const double clean = (labels - 1) * (0.5 + 0.5 * std::sin(x * 0.05) * std::cos(y * 0.03));
        const double observed = ((x / 64 + y / 64) % 2 ? clean : labels - 1 - clean) + noise(rng);
        for(std::size_t k = 0; k < labels; ++k)
          energy.unary_costs(std::size_t(y) * size + x)[k] =
              FT((observed - k) * (observed - k) / 8.0);
      }
  };
  Run run;
  if(tables)
  {
    smc::Discrete_energy<FT> energy(counts, edges);
    fill_unary(energy);
    for(std::size_t e = 0; e < edges.size(); ++e)
      for(std::size_t k = 0; k < labels; ++k)
        for(std::size_t l = 0; l < labels; ++l)
          energy.pairwise_cost(e, k, l) = truncated_linear(e, k, l);
    run = time_energy<FT>(energy, timed_iterations);
  }
  else
  {
    smc::Discrete_energy<FT, decltype(truncated_linear)> energy(counts, edges, truncated_linear);
    fill_unary(energy);
    run = time_energy<FT>(energy, timed_iterations);
  }
  run.peak_mib = smc_bench::peak_memory_mib() - rss_before;
  const double ops = 2.0 * double(edges.size()) * double(labels * labels);
  report.add({"grid " + std::to_string(size) + "x" + std::to_string(size),
              sizeof(FT) == 4 ? "float" : "double", tables ? "tables" : "functor",
              std::to_string(labels), std::to_string(n), std::to_string(edges.size()),
              Report::num(run.ms_per_iteration, 2),
              Report::num(ops / (run.ms_per_iteration * 1e-3) * 1e-9, 2),
              std::to_string(run.iterations), Report::num(run.solve_ms, 1), run.termination,
              Report::num(run.energy, 1), Report::num(run.bound, 1),
              Report::num(100.0 * (run.energy - run.bound) / std::abs(run.energy), 3),
              Report::num(run.peak_mib, 1), Report::num(run.model_mib, 1)});
}

#ifdef CGAL_LINKED_WITH_TBB
// Wall-clock time of 15 TRW-S iterations with Trws_solver<float, Tag> (best of 5), and the run.
template <typename Tag, typename Energy>
double parallel_row_ms(const Energy& energy, std::vector<int>& labels, smc::Trws_result& result)
{
  double best = 1e300;
  for(int rep = 0; rep < 5; ++rep)
  {
    smc::Trws_solver<float, Tag> solver;
    const auto start = std::chrono::steady_clock::now();
    result = solver.solve(energy, labels, params::relative_tolerance(0.0).number_of_iterations(15));
    best = std::min(best, 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

void parallel_rows(const Mrf_shape& shape)
{
  Report report({"labels", "nodes", "threads", "sequential_ms", "parallel_ms", "speedup", "identical"});
  for(std::size_t m : {20, 40})
  {
    std::vector<int> a, b;
    smc::Trws_result ra, rb;
    double sequential = 0, parallel = 0;
    with_comap_energy<float>(shape, m, true, [&](const auto& energy) {
      sequential = parallel_row_ms<CGAL::Sequential_tag>(energy, a, ra);
      parallel = parallel_row_ms<CGAL::Parallel_tag>(energy, b, rb);
    });
    const bool identical = a == b && ra.energy == rb.energy && ra.lower_bound == rb.lower_bound;
    report.add({std::to_string(m), std::to_string(shape.n),
                std::to_string(tbb::this_task_arena::max_concurrency()), Report::num(sequential, 1),
                Report::num(parallel, 1), Report::num(sequential / parallel, 2), identical ? "yes" : "NO"});
  }
  std::cout << "\n== parallel passes: 15 iterations, float tables, breadth-first nodes, wall clock, best of 5\n";
  report.print();
}
#endif

} // namespace

int main(int argc, char** argv)
{
  const int vertices_wanted = argc > 1 ? std::atoi(argv[1]) : 5000;
  const std::size_t timed_iterations = argc > 2 ? std::size_t(std::atoi(argv[2])) : 30;
  std::vector<std::size_t> label_counts = {10, 20, 30, 40};
  if(argc > 3)
  {
    label_counts.clear();
    std::stringstream list(argv[3]);
    for(std::string item; std::getline(list, item, ',');) label_counts.push_back(std::stoul(item));
  }

  std::string description;
  const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(vertices_wanted, &description);
  Mrf_shape mesh_order, shape;
  mesh_order.n = shape.n = num_vertices(mesh);
  shape.vertex.resize(shape.n);
  for(std::size_t i = 0; i < shape.n; ++i) shape.vertex[i] = i;
  mesh_order.vertex = shape.vertex;
  for(auto e : edges(mesh))
  {
    const std::size_t s = std::size_t(source(e, mesh)), t = std::size_t(target(e, mesh));
    mesh_order.edges.emplace_back(s, t);
    shape.edges.emplace_back(std::min(s, t), std::max(s, t));
  }
  std::sort(shape.edges.begin(), shape.edges.end());
  std::cout << "mesh: " << description << ", " << shape.n << " vertices, " << shape.edges.size()
            << " edges\n";

  const std::vector<std::string> columns = {
      "case",          "FT",          "storage",     "labels",
      "nodes",         "edges",       "ms_per_iter", "G_minplus_per_s",
      "iters_to_1e-4", "solve_ms",    "termination", "energy",
      "bound",         "gap_percent", "peak_MiB",    "model_MiB"};
  Report comap(columns);
  for(std::size_t m : label_counts)
    for(int variant = 0; variant < 4; ++variant)
    {
      const bool tables = variant < 2, use_float = variant % 2 == 0;
      const Run r = use_float ? comap_run<float>(shape, m, tables, timed_iterations)
                              : comap_run<double>(shape, m, tables, timed_iterations);
      const double ops = 2.0 * double(shape.edges.size()) * double(m * m);
      comap.add({"comap mesh sorted edges", use_float ? "float" : "double",
                 tables ? "tables" : "functor", std::to_string(m), std::to_string(shape.n),
                 std::to_string(shape.edges.size()), Report::num(r.ms_per_iteration, 2),
                 Report::num(ops / (r.ms_per_iteration * 1e-3) * 1e-9, 2),
                 std::to_string(r.iterations), Report::num(r.solve_ms, 1), r.termination,
                 Report::num(r.energy, 2), Report::num(r.bound, 2),
                 Report::num(100.0 * (r.energy - r.bound) / std::abs(r.energy), 3),
                 Report::num(r.peak_mib, 1), Report::num(r.model_mib, 1)});
    }
  // Two other numberings of the same MRF, m = 20, float tables.
  const Mrf_shape breadth_first = breadth_first_renumbered(shape);
  for(const Mrf_shape* other : std::vector<const Mrf_shape*>{&mesh_order, &breadth_first})
  {
    const Run r = comap_run<float>(*other, 20, true, timed_iterations);
    const double ops = 2.0 * double(shape.edges.size()) * 400.0;
    comap.add({other == &mesh_order ? "comap mesh edge order" : "comap breadth-first nodes",
               "float", "tables", "20", std::to_string(shape.n), std::to_string(shape.edges.size()),
               Report::num(r.ms_per_iteration, 2),
               Report::num(ops / (r.ms_per_iteration * 1e-3) * 1e-9, 2),
               std::to_string(r.iterations), Report::num(r.solve_ms, 1), r.termination,
               Report::num(r.energy, 2), Report::num(r.bound, 2),
               Report::num(100.0 * (r.energy - r.bound) / std::abs(r.energy), 3),
               Report::num(r.peak_mib, 1), Report::num(r.model_mib, 1)});
  }
  grid_run<float>(comap, 256, 16, true, timed_iterations);
  grid_run<float>(comap, 256, 16, false, timed_iterations);
  grid_run<double>(comap, 256, 16, true, timed_iterations);
  std::cout << "\n== TRW-S (ms_per_iter = one forward + one backward pass, median, thread CPU time;"
            << " G_minplus_per_s = 2 |E| m^2 / time)\n";
  comap.print();

  Report kernels({"FT", "labels", "edges", "simd_ms", "simd_G_minplus_per_s", "portable_ms",
                  "portable_G_minplus_per_s", "speedup"});
  for(std::size_t m : {10, 20, 30, 40}) kernel_rows<float>(kernels, shape.edges.size(), m);
  for(std::size_t m : {10, 20, 30, 40}) kernel_rows<double>(kernels, shape.edges.size(), m);
  std::cout
      << "\n== min-plus kernels alone, one iteration's work (2 |E| m^2) on tables read in order,"
      << " best of 5, thread CPU time\n";
  kernels.print();
#ifdef CGAL_LINKED_WITH_TBB
  parallel_rows(breadth_first);
#endif
  return EXIT_SUCCESS;
}
