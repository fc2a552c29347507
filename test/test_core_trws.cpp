// SPDX-License-Identifier: GPL-3.0-or-later
// TRW-S on the flat Discrete_energy: exact optima on chains, stars and trees (dynamic programming),
// bounds on small loopy graphs (brute force), monotone lower bound, visitor, float vs double,
// functor vs tables, reuse, initial labeling, the parallel passes (the sequential result, bit for
// bit), and every rejected input.

#include "test_core_trws_helpers.h"

#include <CGAL/Surface_mesh_correspondence/trws.h>

#include <boost/test/unit_test.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using trws_test::Problem;
using trws_test::close;

namespace {

// Solves p with tables in double precision and checks the result against the exact optimum.
void check_exact(const Problem& p, double optimum, const std::string& what)
{
  const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
  std::vector<int> labels;
  const smc::Trws_result r = smc::trws_minimize(
      energy, labels, params::relative_tolerance(1e-12).number_of_iterations(2000));
  BOOST_TEST_CONTEXT(what << ": n = " << p.n() << ", energy " << r.energy << ", optimum " << optimum
                          << ", bound " << r.lower_bound << ", " << r.number_of_iterations
                          << " iterations, " << smc::to_string(r.termination))
  {
    BOOST_TEST(close(r.energy, optimum));
    BOOST_TEST(close(p.energy(labels), r.energy));
    BOOST_TEST(r.lower_bound <= optimum + 1e-9 * std::max(1.0, std::abs(optimum)));
    BOOST_TEST(close(r.lower_bound, optimum, 1e-6)); // the LP relaxation is tight on trees
  }
}

struct Bound_recorder
{
  std::vector<double> bounds, energies;
  bool iteration(std::size_t, double energy, double bound)
  {
    energies.push_back(energy);
    bounds.push_back(bound);
    return true;
  }
};

} // namespace

BOOST_AUTO_TEST_SUITE(trws)

BOOST_AUTO_TEST_CASE(exact_on_chains)
{
  std::mt19937 rng(1);
  for(int trial = 0; trial < 40; ++trial)
  {
    Problem p;
    const int n = 2 + trial % 25;
    p.labels = trws_test::random_label_counts(n, 7, rng);
    // Half the chains in index order (one chain, gamma = 1), half with shuffled numbering.
    std::vector<int> perm(n);
    for(int i = 0; i < n; ++i) perm[i] = i;
    if(trial % 2) std::shuffle(perm.begin(), perm.end(), rng);
    for(int i = 0; i + 1 < n; ++i)
      p.edges.emplace_back(rng() % 2 ? std::make_pair(perm[i], perm[i + 1])
                                     : std::make_pair(perm[i + 1], perm[i]));
    trws_test::random_costs(p, rng, 2.0);
    check_exact(p, trws_test::tree_minimum(p), "chain");
  }
}

BOOST_AUTO_TEST_CASE(exact_on_stars)
{
  std::mt19937 rng(2);
  for(int trial = 0; trial < 30; ++trial)
  {
    Problem p;
    const int n = 2 + trial % 15;
    p.labels = trws_test::random_label_counts(n, 6, rng);
    const int center = int(rng() % n);
    for(int i = 0; i < n; ++i)
      if(i != center)
        p.edges.emplace_back(rng() % 2 ? std::make_pair(center, i) : std::make_pair(i, center));
    trws_test::random_costs(p, rng, 2.0);
    check_exact(p, trws_test::tree_minimum(p), "star");
  }
}

BOOST_AUTO_TEST_CASE(exact_on_random_trees_and_forests)
{
  std::mt19937 rng(3);
  for(int trial = 0; trial < 60; ++trial)
  {
    Problem p;
    const int n = 2 + int(rng() % 40);
    p.labels = trws_test::random_label_counts(n, 8, rng);
    p.edges = trws_test::random_tree(n, rng);
    if(trial % 5 == 0) p.edges.resize(p.edges.size() / 2); // a forest
    trws_test::random_costs(p, rng, 2.0);
    check_exact(p, trws_test::tree_minimum(p), "tree");
  }
}

BOOST_AUTO_TEST_CASE(tree_reference_agrees_with_brute_force)
{
  // The dynamic programming reference itself, against enumeration.
  std::mt19937 rng(4);
  for(int trial = 0; trial < 20; ++trial)
  {
    Problem p;
    const int n = 2 + int(rng() % 7);
    p.labels = trws_test::random_label_counts(n, 4, rng);
    p.edges = trws_test::random_tree(n, rng);
    trws_test::random_costs(p, rng);
    BOOST_TEST(close(trws_test::tree_minimum(p), trws_test::brute_force_minimum(p)));
  }
}

BOOST_AUTO_TEST_CASE(loopy_graphs_bound_optimum_energy)
{
  std::mt19937 rng(5);
  int trials = 0, optimal = 0, certified = 0;
  for(int trial = 0; trial < 150; ++trial)
  {
    Problem p;
    const int n = 3 + int(rng() % 8); // at most 10 nodes
    p.labels = trws_test::random_label_counts(n, 4, rng);
    p.edges = trws_test::random_loopy_graph(n, 1 + int(rng() % (2 * n)), rng);
    trws_test::random_costs(p, rng, 1.0 + trial % 3);
    const double optimum = trws_test::brute_force_minimum(p);
    const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
    std::vector<int> labels;
    const smc::Trws_result r = smc::trws_minimize(
        energy, labels, params::relative_tolerance(1e-10).number_of_iterations(500));
    const double eps = 1e-9 * std::max(1.0, std::abs(optimum));
    BOOST_TEST_CONTEXT("trial " << trial << ": bound " << r.lower_bound << ", optimum " << optimum
                                << ", energy " << r.energy)
    {
      BOOST_TEST(r.lower_bound <= optimum + eps);
      BOOST_TEST(optimum <= r.energy + eps);
      BOOST_TEST(close(p.energy(labels), r.energy));
    }
    ++trials;
    if(r.energy <= optimum + eps) ++optimal;
    if(r.termination == smc::Trws_termination::optimal) ++certified;
  }
  BOOST_TEST_MESSAGE("TRW-S on " << trials
                                 << " random loopy graphs of at most 10 nodes: optimal on "
                                 << optimal << " (" << 100.0 * optimal / trials
                                 << "%), certified by the bound on " << certified);
  BOOST_TEST(optimal >= trials * 8 / 10);
}

BOOST_AUTO_TEST_CASE(lower_bound_never_decreases)
{
  std::mt19937 rng(6);
  for(int trial = 0; trial < 6; ++trial)
  {
    // A 12 x 12 grid, 6 labels, random costs: loopy, far from trivial.
    Problem p;
    const int w = 12;
    p.labels.assign(w * w, 6);
    for(int y = 0; y < w; ++y)
      for(int x = 0; x < w; ++x)
      {
        if(x + 1 < w) p.edges.emplace_back(y * w + x, y * w + x + 1);
        if(y + 1 < w) p.edges.emplace_back(y * w + x, (y + 1) * w + x);
      }
    trws_test::random_costs(p, rng, 1.5);
    Bound_recorder recorder;
    std::vector<int> labels;
    if(trial % 2 == 0)
    {
      const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
      smc::trws_minimize(
          energy, labels,
          params::relative_tolerance(0.0).number_of_iterations(60).visitor(std::ref(recorder)));
    }
    else
    {
      const smc::Discrete_energy<float> energy = trws_test::make_energy<float>(p);
      smc::trws_minimize(
          energy, labels,
          params::relative_tolerance(0.0).number_of_iterations(60).visitor(std::ref(recorder)));
    }
    BOOST_TEST_REQUIRE(recorder.bounds.size() >= 2u);
    const double tol = (trial % 2 == 0 ? 1e-9 : 1e-4) * std::abs(recorder.bounds.back());
    for(std::size_t k = 1; k < recorder.bounds.size(); ++k)
    {
      BOOST_TEST(recorder.bounds[k] >= recorder.bounds[k - 1] - tol, "iteration " << k + 1);
      BOOST_TEST(recorder.energies[k] <= recorder.energies[k - 1], "iteration " << k + 1);
      BOOST_TEST(recorder.bounds[k] <= recorder.energies[k] + tol);
    }
    // The bound must actually move on such a problem.
    BOOST_TEST(recorder.bounds.back() > recorder.bounds.front());
  }
}

BOOST_AUTO_TEST_CASE(visitor_stops_the_run)
{
  std::mt19937 rng(7);
  Problem p;
  p.labels.assign(100, 5);
  p.edges = trws_test::random_loopy_graph(100, 200, rng);
  trws_test::random_costs(p, rng, 2.0);
  const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
  std::vector<int> labels;
  std::size_t calls = 0;
  auto stop_at_3 = [&](std::size_t k, double, double) {
    ++calls;
    return k < 3;
  };
  const smc::Trws_result r = smc::trws_minimize(
      energy, labels, params::relative_tolerance(0.0).number_of_iterations(100).visitor(stop_at_3));
  BOOST_TEST(calls == 3u);
  BOOST_TEST(r.number_of_iterations == 3u);
  BOOST_TEST(r.termination == smc::Trws_termination::visitor_stop);
  BOOST_TEST(std::string(smc::to_string(r.termination)) == "visitor_stop");
  BOOST_TEST(close(p.energy(labels), r.energy));

  const smc::Trws_result limited =
      smc::trws_minimize(energy, labels, params::relative_tolerance(0.0).number_of_iterations(4));
  BOOST_TEST(limited.number_of_iterations == 4u);
  BOOST_TEST(limited.termination == smc::Trws_termination::iteration_limit);
}

BOOST_AUTO_TEST_CASE(convergence_criteria)
{
  std::mt19937 rng(8);
  Problem p;
  p.labels.assign(64, 4);
  p.edges = trws_test::random_loopy_graph(64, 100, rng);
  trws_test::random_costs(p, rng, 2.0);
  const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
  std::vector<int> labels;
  Bound_recorder recorder;
  const smc::Trws_result r = smc::trws_minimize(
      energy, labels,
      params::relative_tolerance(1e-3).number_of_iterations(1000).visitor(std::ref(recorder)));
  BOOST_TEST(r.termination != smc::Trws_termination::iteration_limit);
  const std::size_t k = recorder.bounds.size();
  BOOST_TEST(k == r.number_of_iterations);
  if(r.termination == smc::Trws_termination::converged)
    BOOST_TEST(std::abs(recorder.bounds[k - 1] - recorder.bounds[k - 2]) <=
               1e-3 * std::abs(recorder.bounds[k - 1]));
  else
    BOOST_TEST(r.energy - r.lower_bound <= 1e-3 * std::abs(r.energy));
  // A graph without edges is solved exactly in one iteration.
  Problem q;
  q.labels = {3, 1, 4};
  trws_test::random_costs(q, rng);
  std::vector<int> x;
  const smc::Trws_result rq = smc::trws_minimize(trws_test::make_energy<double>(q), x);
  BOOST_TEST(rq.number_of_iterations == 1u);
  BOOST_TEST(rq.termination == smc::Trws_termination::optimal);
  BOOST_TEST(close(rq.energy, trws_test::brute_force_minimum(q)));
  // An empty energy.
  std::vector<int> none;
  const smc::Trws_result re = smc::trws_minimize(smc::Discrete_energy<double>(), none);
  BOOST_TEST(re.energy == 0.0);
  BOOST_TEST(none.empty());
}

BOOST_AUTO_TEST_CASE(deterministic_float_double_functor_tables)
{
  std::mt19937 rng(9);
  Problem p;
  const int w = 20;
  std::uniform_int_distribution<int> k(5, 12);
  for(int i = 0; i < w * w; ++i) p.labels.push_back(k(rng));
  for(int y = 0; y < w; ++y)
    for(int x = 0; x < w; ++x)
    {
      if(x + 1 < w) p.edges.emplace_back(y * w + x, y * w + x + 1);
      if(y + 1 < w) p.edges.emplace_back((y + 1) * w + x, y * w + x); // reversed orientation
    }
  trws_test::random_costs(p, rng, 1.0);
  auto np = params::relative_tolerance(1e-7).number_of_iterations(200);

  std::vector<int> a, b, c, d;
  const smc::Trws_result ra = smc::trws_minimize(trws_test::make_energy<double>(p), a, np);
  const smc::Trws_result rb = smc::trws_minimize(trws_test::make_energy<double>(p), b, np);
  BOOST_TEST(a == b); // deterministic
  BOOST_TEST(ra.energy == rb.energy);
  BOOST_TEST(ra.lower_bound == rb.lower_bound);
  BOOST_TEST(ra.number_of_iterations == rb.number_of_iterations);

  // The functor path computes the same tables on the fly: the same run, bit for bit.
  const smc::Trws_result rc = smc::trws_minimize(trws_test::make_functor_energy<double>(p), c, np);
  BOOST_TEST(a == c);
  BOOST_TEST(ra.energy == rc.energy);
  BOOST_TEST(ra.lower_bound == rc.lower_bound);
  BOOST_TEST(ra.number_of_iterations == rc.number_of_iterations);
  std::vector<int> cf, tf;
  const smc::Trws_result rcf = smc::trws_minimize(trws_test::make_functor_energy<float>(p), cf, np);
  const smc::Trws_result rtf = smc::trws_minimize(trws_test::make_energy<float>(p), tf, np);
  BOOST_TEST(cf == tf);
  BOOST_TEST(rcf.energy == rtf.energy);

  // float messages: close to double.
  const smc::Trws_result rd = smc::trws_minimize(trws_test::make_energy<float>(p), d, np);
  BOOST_TEST_MESSAGE("float vs double on a 20x20 grid: energy "
                     << rd.energy << " vs " << ra.energy << ", bound " << rd.lower_bound << " vs "
                     << ra.lower_bound);
  BOOST_TEST(std::abs(rd.energy - ra.energy) <= 5e-3 * std::abs(ra.energy));
  BOOST_TEST(std::abs(rd.lower_bound - ra.lower_bound) <= 1e-3 * std::abs(ra.lower_bound));
  BOOST_TEST(close(p.energy(d), rd.energy, 1e-6));
}

#ifdef CGAL_LINKED_WITH_TBB
namespace {

// A w x w grid with random label counts (at most `max_labels`) and costs: edges to the right and
// down, and with `diagonals` to the lower right.
Problem grid_problem(int w, int max_labels, bool diagonals, double pairwise_scale, std::mt19937& rng)
{
  Problem p;
  p.labels = trws_test::random_label_counts(std::size_t(w * w), max_labels, rng);
  for(int y = 0; y < w; ++y)
    for(int x = 0; x < w; ++x)
    {
      if(x + 1 < w) p.edges.emplace_back(y * w + x, y * w + x + 1);
      if(y + 1 < w) p.edges.emplace_back(y * w + x, (y + 1) * w + x);
      if(diagonals && x + 1 < w && y + 1 < w) p.edges.emplace_back(y * w + x, (y + 1) * w + x + 1);
    }
  trws_test::random_costs(p, rng, pairwise_scale);
  return p;
}

// A run of Trws_solver<FT, Tag> on `energy` in an arena of `threads` threads: its labeling,
// result and the bound of every iteration.
struct Recorded_run
{
  std::vector<int> labels;
  smc::Trws_result result;
  std::vector<double> bounds;
};

template <typename FT, typename Tag, typename Energy>
Recorded_run recorded_run(smc::Trws_solver<FT, Tag>& solver, const Energy& energy, int threads)
{
  Recorded_run run;
  auto record = [&run](std::size_t, double, double bound) {
    run.bounds.push_back(bound);
    return true;
  };
  tbb::task_arena arena(threads);
  arena.execute([&] {
    run.result = solver.solve(energy, run.labels,
                              params::relative_tolerance(0.0).number_of_iterations(30).visitor(record));
  });
  return run;
}

void check_same_run(const Recorded_run& a, const Recorded_run& b, const std::string& what)
{
  BOOST_TEST_CONTEXT(what)
  {
    BOOST_TEST(a.labels == b.labels);
    BOOST_TEST(a.result.energy == b.result.energy); // bit for bit
    BOOST_TEST(a.result.lower_bound == b.result.lower_bound);
    BOOST_TEST(a.result.number_of_iterations == b.result.number_of_iterations);
    BOOST_TEST(a.bounds == b.bounds, boost::test_tools::per_element());
  }
}

} // namespace

BOOST_AUTO_TEST_CASE(parallel_passes_give_the_sequential_result)
{
  // Triangulated grids above Trws_solver::minimum_parallel_nodes, numbered by rows (about
  // 2 w levels), randomly (few wide levels) and column by column in a snake (almost a chain:
  // each node waits for the previous one); random label counts and costs. The parallel passes must
  // reproduce the sequential run exactly: a node updated before one of its neighbours, or
  // two neighbours updated at once, changes the messages and hence the bounds.
  std::mt19937 rng(21);
  const int w = 36, n = w * w;
  static_assert(36 * 36 >= int(smc::Trws_solver<float, CGAL::Parallel_tag>::minimum_parallel_nodes),
                "the grid must be solved in parallel");
  for(int numbering = 0; numbering < 3; ++numbering)
  {
    std::vector<int> id(n);
    for(int i = 0; i < n; ++i) id[i] = i;
    if(numbering == 1) std::shuffle(id.begin(), id.end(), rng);
    if(numbering == 2)
      for(int y = 0; y < w; ++y)
        for(int x = 0; x < w; ++x) id[y * w + x] = x * w + (x % 2 ? w - 1 - y : y);
    Problem p;
    p.labels = trws_test::random_label_counts(std::size_t(n), 14, rng);
    for(int y = 0; y < w; ++y)
      for(int x = 0; x < w; ++x)
      {
        const int v = id[y * w + x];
        if(x + 1 < w) p.edges.emplace_back(v, id[y * w + x + 1]);
        if(y + 1 < w) p.edges.emplace_back(id[(y + 1) * w + x], v);
        if(x + 1 < w && y + 1 < w) p.edges.emplace_back(v, id[(y + 1) * w + x + 1]);
      }
    trws_test::random_costs(p, rng, 1.5);
    const std::string what = "numbering " + std::to_string(numbering);

    const smc::Discrete_energy<float> energy = trws_test::make_energy<float>(p);
    smc::Trws_solver<float> sequential;
    const Recorded_run reference = recorded_run(sequential, energy, 1);
    BOOST_TEST(reference.bounds.size() == 30u);
    smc::Trws_solver<float, CGAL::Parallel_tag> parallel;
    for(int threads : {2, 4})
      check_same_run(reference, recorded_run(parallel, energy, threads),
                     what + ", float, " + std::to_string(threads) + " threads");
    // One thread: the sequential passes of the parallel solver.
    check_same_run(reference, recorded_run(parallel, energy, 1), what + ", float, 1 thread");

    const smc::Discrete_energy<double> energy_d = trws_test::make_energy<double>(p);
    smc::Trws_solver<double> sequential_d;
    smc::Trws_solver<double, CGAL::Parallel_tag> parallel_d;
    check_same_run(recorded_run(sequential_d, energy_d, 1), recorded_run(parallel_d, energy_d, 2),
                   what + ", double, 2 threads");
  }

  // Reuse on an energy of another size, a small energy (sequential passes) and a functor energy
  // (sequential passes): still the sequential result.
  smc::Trws_solver<float, CGAL::Parallel_tag> parallel;
  for(int size : {40, 12})
  {
    const Problem p = grid_problem(size, 9, false, 1.0, rng);
    smc::Trws_solver<float> sequential;
    const Recorded_run reference = recorded_run(sequential, trws_test::make_energy<float>(p), 1);
    check_same_run(reference, recorded_run(parallel, trws_test::make_energy<float>(p), 2),
                   "reused solver, " + std::to_string(size) + " x " + std::to_string(size) + " grid");
    smc::Trws_solver<float, CGAL::Parallel_tag> functor_solver;
    check_same_run(reference, recorded_run(functor_solver, trws_test::make_functor_energy<float>(p), 2),
                   "functor costs, " + std::to_string(size) + " x " + std::to_string(size) + " grid");
  }
}

BOOST_AUTO_TEST_CASE(trws_minimize_takes_the_concurrency_tag)
{
  // trws_minimize<Parallel_tag> runs its passes on the threads of the arena (reported by
  // number_of_threads) and returns the sequential result; functor costs and small energies are
  // solved sequentially.
  std::mt19937 rng(33);
  const auto np = params::relative_tolerance(0.0).number_of_iterations(20);
  tbb::task_arena arena(2);
  const Problem large = grid_problem(36, 12, true, 1.5, rng), small = grid_problem(10, 12, true, 1.5, rng);
  const smc::Discrete_energy<float> energy = trws_test::make_energy<float>(large);
  std::vector<int> sequential_labels, parallel_labels, labels;
  smc::Trws_result sequential, parallel, functor, little;
  arena.execute([&] {
    sequential = smc::trws_minimize(energy, sequential_labels, np);
    parallel = smc::trws_minimize<CGAL::Parallel_tag>(energy, parallel_labels, np);
    functor = smc::trws_minimize<CGAL::Parallel_tag>(trws_test::make_functor_energy<float>(large), labels, np);
    little = smc::trws_minimize<CGAL::Parallel_tag>(trws_test::make_energy<float>(small), labels, np);
  });
  BOOST_TEST(sequential.number_of_threads == 1u);
  BOOST_TEST(parallel.number_of_threads == 2u);
  BOOST_TEST((parallel_labels == sequential_labels));
  BOOST_TEST(parallel.energy == sequential.energy);
  BOOST_TEST(parallel.lower_bound == sequential.lower_bound);
  BOOST_TEST(parallel.number_of_iterations == sequential.number_of_iterations);
  BOOST_TEST(functor.number_of_threads == 1u);
  BOOST_TEST(functor.energy == sequential.energy);
  BOOST_TEST(little.number_of_threads == 1u);
}
#endif

BOOST_AUTO_TEST_CASE(solver_reuse_and_modification)
{
  std::mt19937 rng(10);
  Problem p;
  p.labels = trws_test::random_label_counts(80, 9, rng);
  p.edges = trws_test::random_loopy_graph(80, 120, rng);
  trws_test::random_costs(p, rng, 1.0);
  smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
  smc::Trws_solver<double> solver;
  std::vector<int> first, again, fresh;
  const smc::Trws_result r1 = solver.solve(energy, first);
  // Modify the costs in place, solve again with the same solver, compare with a new solver.
  trws_test::random_costs(p, rng, 3.0);
  for(std::size_t i = 0; i < p.n(); ++i)
    std::copy(p.unary[i].begin(), p.unary[i].end(), energy.unary_costs(i));
  for(std::size_t e = 0; e < p.edges.size(); ++e)
    for(int k = 0; k < p.labels[p.edges[e].first]; ++k)
      for(int l = 0; l < p.labels[p.edges[e].second]; ++l)
        energy.pairwise_cost(e, k, l) = p.cost(e, k, l);
  const smc::Trws_result r2 = solver.solve(energy, again);
  const smc::Trws_result r3 = smc::Trws_solver<double>().solve(energy, fresh);
  BOOST_TEST(again == fresh);
  BOOST_TEST(r2.energy == r3.energy);
  BOOST_TEST(close(p.energy(again), r2.energy));
  BOOST_TEST(r1.energy != r2.energy);
  // reset() to another graph, reusing the memory.
  Problem q;
  q.labels = trws_test::random_label_counts(30, 5, rng);
  q.edges = trws_test::random_tree(30, rng);
  trws_test::random_costs(q, rng);
  energy.reset(q.labels, q.edges);
  BOOST_TEST(energy.number_of_nodes() == 30u);
  BOOST_TEST(energy.unary_cost(3, 0) == 0.0);
  for(std::size_t i = 0; i < q.n(); ++i)
    std::copy(q.unary[i].begin(), q.unary[i].end(), energy.unary_costs(i));
  for(std::size_t e = 0; e < q.edges.size(); ++e)
    std::copy(q.pairwise[e].begin(), q.pairwise[e].end(), energy.pairwise_costs(e));
  std::vector<int> x;
  const smc::Trws_result rq =
      solver.solve(energy, x, params::relative_tolerance(1e-12).number_of_iterations(1000));
  BOOST_TEST(close(rq.energy, trws_test::tree_minimum(q)));
  BOOST_TEST(energy.memory_bytes() > 0u);
  BOOST_TEST(solver.memory_bytes() > 0u);
}

BOOST_AUTO_TEST_CASE(initial_labeling_is_kept_unless_improved)
{
  std::mt19937 rng(11);
  Problem p;
  p.labels = trws_test::random_label_counts(10, 4, rng);
  p.edges = trws_test::random_loopy_graph(10, 15, rng);
  trws_test::random_costs(p, rng, 3.0);
  std::vector<int> optimum_labels;
  const double optimum = trws_test::brute_force_minimum(p, &optimum_labels);
  const smc::Discrete_energy<double> energy = trws_test::make_energy<double>(p);
  // One iteration from the optimum: the first forward pass is greedy, the optimum must be kept.
  std::vector<int> labels;
  const smc::Trws_result r = smc::trws_minimize(
      energy, labels, params::initial_labeling(optimum_labels).number_of_iterations(1));
  BOOST_TEST(close(r.energy, optimum));
  BOOST_TEST(close(p.energy(labels), optimum));
  // Initial labels of another integer type, and out of range.
  std::vector<std::size_t> zeros(10, 0);
  BOOST_CHECK_NO_THROW(smc::trws_minimize(energy, labels, params::initial_labeling(zeros)));
  std::vector<int> bad(10, 0);
  bad[4] = p.labels[4];
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels, params::initial_labeling(bad)),
                    smc::Invalid_parameter_error);
  bad[4] = -1;
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels, params::initial_labeling(bad)),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(
      smc::trws_minimize(energy, labels, params::initial_labeling(std::vector<int>(9, 0))),
      smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(rejected_inputs)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto message_of = [](auto&& f) -> std::string {
    try
    {
      f();
    }
    catch(const smc::Invalid_energy_error& e)
    {
      return e.what();
    }
    return "no exception";
  };
  typedef std::vector<std::pair<int, int> > Edges;
  // A node with zero labels.
  BOOST_TEST(message_of([] {
               smc::Discrete_energy<double>(std::vector<int>{2, 0, 3}, Edges{});
             }).find("node 1 has no label") != std::string::npos);
  BOOST_CHECK_THROW(smc::Discrete_energy<double>(std::vector<int>{2, -1}, Edges{}),
                    smc::Invalid_energy_error);
  // Self-loop, end out of range, parallel edges (in either direction).
  BOOST_TEST(message_of([] {
               smc::Discrete_energy<float>(std::vector<int>{2, 2}, Edges{{0, 1}, {1, 1}});
             }).find("edge 1 is a self-loop at node 1") != std::string::npos);
  BOOST_TEST(message_of([] {
               smc::Discrete_energy<float>(std::vector<int>{2, 2}, Edges{{0, 2}});
             }).find("edge 0 (0, 2) has an end out of range") != std::string::npos);
  BOOST_CHECK_THROW(smc::Discrete_energy<float>(std::vector<int>{2, 2}, Edges{{0, -1}}),
                    smc::Invalid_energy_error);
  BOOST_TEST(
      message_of([] {
        smc::Discrete_energy<double>(std::vector<int>{2, 2, 2}, Edges{{0, 1}, {1, 2}, {1, 0}});
      }).find("edges 0 and 2 both join nodes 0 and 1") != std::string::npos);

  // NaN and infinite costs, unary and pairwise, tables and functor.
  std::vector<int> labels;
  smc::Discrete_energy<double> energy(std::vector<int>{2, 3, 2}, Edges{{0, 1}, {2, 1}});
  BOOST_CHECK_NO_THROW(smc::trws_minimize(energy, labels));
  energy.unary_cost(1, 2) = nan;
  BOOST_TEST(message_of([&] {
               smc::trws_minimize(energy, labels);
             }).find("unary cost of node 1, label 2") != std::string::npos);
  energy.unary_cost(1, 2) = -inf;
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels), smc::Invalid_energy_error);
  energy.unary_cost(1, 2) = 0;
  energy.pairwise_cost(1, 1, 2) = inf;
  BOOST_TEST(message_of([&] {
               smc::trws_minimize(energy, labels);
             }).find("pairwise cost of edge 1 (2, 1), labels (1, 2)") != std::string::npos);
  energy.pairwise_cost(1, 1, 2) = nan;
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels), smc::Invalid_energy_error);
  energy.pairwise_cost(1, 1, 2) = 1;
  BOOST_CHECK_NO_THROW(smc::trws_minimize(energy, labels));

  auto bad_functor = [nan](std::size_t e, std::size_t k, std::size_t l) {
    return (e == 1 && k == 0 && l == 1) ? nan : double(k + l);
  };
  smc::Discrete_energy<float, decltype(bad_functor)> fenergy(std::vector<int>{2, 3, 2},
                                                             Edges{{0, 1}, {2, 1}}, bad_functor);
  std::vector<int> flabels;
  BOOST_TEST(message_of([&] {
               smc::trws_minimize(fenergy, flabels);
             }).find("pairwise cost of edge 1 (2, 1), labels (0, 1)") != std::string::npos);

#ifdef NDEBUG
  // Costs too large for float: the messages overflow (Debug builds trap the overflow instead).
  smc::Discrete_energy<float> huge(std::vector<int>{2, 2, 2}, Edges{{0, 1}, {1, 2}});
  for(std::size_t i = 0; i < 3; ++i)
    for(int k = 0; k < 2; ++k) huge.unary_cost(i, k) = 3e38f;
  for(std::size_t e = 0; e < 2; ++e)
    for(int k = 0; k < 4; ++k) huge.pairwise_costs(e)[k] = 3e38f;
  BOOST_CHECK_THROW(smc::trws_minimize(huge, labels), smc::Numerical_error);
#endif

  // Parameters.
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels, params::number_of_iterations(0)),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::trws_minimize(energy, labels, params::relative_tolerance(-1.0)),
                    smc::Invalid_parameter_error);
  // Energy evaluation with a bad labeling.
  BOOST_CHECK_THROW(energy.energy(std::vector<int>{0, 3, 0}), smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(energy.energy(std::vector<int>{0, 0}), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(large_finite_costs_act_as_forbidden_combinations)
{
  // "Forbidden" label pairs are expressed with a large finite cost (infinite costs are rejected).
  // On trees TRW-S is exact, so it must avoid them whenever a feasible labeling exists.
  std::mt19937 rng(12);
  int feasible = 0;
  for(int trial = 0; trial < 20; ++trial)
  {
    Problem p;
    p.labels = trws_test::random_label_counts(25, 5, rng);
    p.edges = trws_test::random_tree(25, rng);
    trws_test::random_costs(p, rng);
    for(auto& table : p.pairwise)
      for(double& c : table)
        if(rng() % 10 < 4) c = 1e7;
    const double optimum = trws_test::tree_minimum(p);
    std::vector<int> labels;
    const smc::Trws_result r =
        smc::trws_minimize(trws_test::make_energy<double>(p), labels,
                           params::relative_tolerance(1e-12).number_of_iterations(2000));
    BOOST_TEST(close(r.energy, optimum));
    BOOST_TEST(r.lower_bound <= optimum + 1e-6);
    if(optimum < 1e7)
    {
      ++feasible;
      BOOST_TEST(r.energy < 1e7);
    }
  }
  BOOST_TEST(feasible > 0);
}

BOOST_AUTO_TEST_SUITE_END()
