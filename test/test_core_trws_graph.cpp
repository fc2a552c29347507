// SPDX-License-Identifier: GPL-3.0-or-later
// trws_labeling() on BGL graphs: Surface_mesh vs an adjacency_list copy, tables vs functors,
// Potts energies against CGAL's alpha_expansion_graphcut, parallel edges merged, bad inputs.

// Boost's max-flow code used by CGAL's alpha expansion triggers -Wmaybe-uninitialized in Boost's
// headers; silence it for the headers only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "test_core_trws_helpers.h"
#include "test_meshes.h"

#include <CGAL/Surface_mesh_correspondence/trws.h>

#include <CGAL/boost/graph/alpha_expansion_graphcut.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/property_map/function_property_map.hpp>
#include <boost/test/unit_test.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using trws_test::close;

namespace {

struct Edge_data
{
  std::vector<double> table;
  double weight = 1;
};
typedef boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                              Edge_data>
    Graph;
typedef boost::graph_traits<Graph>::edge_descriptor Graph_edge;

template <typename Vector>
auto index_map(Vector& v, const Graph& g)
{
  return boost::make_iterator_property_map(v.begin(), get(boost::vertex_index, g));
}

// A Potts interaction with its own weight: w [k != l].
struct Potts
{
  double weight;
  double operator()(std::size_t k, std::size_t l) const { return k == l ? 0.0 : weight; }
};

} // namespace

BOOST_AUTO_TEST_SUITE(trws_graph)

BOOST_AUTO_TEST_CASE(surface_mesh_and_adjacency_list_agree)
{
  typedef smc_test::Mesh Mesh;
  typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef boost::graph_traits<Mesh>::edge_descriptor edge_descriptor;
  Mesh mesh = smc_test::icosphere(2);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> kdist(2, 7);

  auto counts = mesh.add_property_map<vertex_descriptor, int>("v:trws_labels", 0).first;
  auto unary = mesh.add_property_map<vertex_descriptor, std::vector<double> >("v:trws_unary").first;
  auto tables = mesh.add_property_map<edge_descriptor, std::vector<double> >("e:trws_table").first;
  auto result = mesh.add_property_map<vertex_descriptor, std::size_t>("v:trws_result", 0).first;
  for(vertex_descriptor v : vertices(mesh))
  {
    counts[v] = kdist(rng);
    unary[v].resize(counts[v]);
    for(double& c : unary[v]) c = u(rng);
  }
  for(edge_descriptor e : edges(mesh))
  {
    tables[e].resize(std::size_t(counts[source(e, mesh)]) * counts[target(e, mesh)]);
    for(double& c : tables[e]) c = 1.5 * u(rng);
  }

  // The same energy on a boost::adjacency_list built from the mesh's vertex and edge lists.
  const std::size_t n = num_vertices(mesh);
  Graph g(n);
  std::vector<int> g_counts(n);
  std::vector<std::vector<double> > g_unary(n);
  for(vertex_descriptor v : vertices(mesh))
  {
    g_counts[std::size_t(v)] = counts[v];
    g_unary[std::size_t(v)] = unary[v];
  }
  for(edge_descriptor e : edges(mesh))
  {
    Edge_data d;
    d.table = tables[e];
    add_edge(std::size_t(source(e, mesh)), std::size_t(target(e, mesh)), d, g);
  }
  std::vector<int> g_result(n, -1);

  const auto np = params::relative_tolerance(1e-8).number_of_iterations(300);
  const smc::Trws_result rm = smc::trws_labeling(mesh, counts, unary, tables, result, np);
  const smc::Trws_result rg =
      smc::trws_labeling(g, index_map(g_counts, g), index_map(g_unary, g),
                         get(&Edge_data::table, g), index_map(g_result, g), np);
  BOOST_TEST(close(rm.energy, rg.energy));
  BOOST_TEST(close(rm.lower_bound, rg.lower_bound));
  BOOST_TEST(rm.number_of_iterations == rg.number_of_iterations);
  std::size_t same = 0;
  for(vertex_descriptor v : vertices(mesh)) same += (int(result[v]) == g_result[std::size_t(v)]);
  BOOST_TEST(same == n);

  // The energy reported is the energy of the labeling written to the map.
  double e = 0;
  for(vertex_descriptor v : vertices(mesh)) e += unary[v][result[v]];
  for(edge_descriptor ed : edges(mesh))
    e += tables[ed][result[source(ed, mesh)] * counts[target(ed, mesh)] + result[target(ed, mesh)]];
  BOOST_TEST(close(e, rm.energy));

  // Float messages, and a functor map giving the same costs: close / identical.
  auto result_float = mesh.add_property_map<vertex_descriptor, int>("v:trws_result_float", 0).first;
  const smc::Trws_result rf =
      smc::trws_labeling<float>(mesh, counts, unary, tables, result_float, np);
  BOOST_TEST(std::abs(rf.energy - rm.energy) <= 1e-3 * rm.energy);
  auto functors =
      boost::make_function_property_map<edge_descriptor>([&](const edge_descriptor& ed) {
        const std::vector<double>* t = &tables[ed];
        const std::size_t cols = std::size_t(counts[target(ed, mesh)]);
        return [t, cols](std::size_t k, std::size_t l) {
          return (*t)[k * cols + l];
        };
      });
  auto result_functor =
      mesh.add_property_map<vertex_descriptor, int>("v:trws_result_functor", 0).first;
  const smc::Trws_result rfun =
      smc::trws_labeling(mesh, counts, unary, functors, result_functor, np);
  BOOST_TEST(rfun.energy == rm.energy);
  BOOST_TEST(rfun.number_of_iterations == rm.number_of_iterations);
  std::size_t same_functor = 0;
  for(vertex_descriptor v : vertices(mesh))
    same_functor += (std::size_t(result_functor[v]) == result[v]);
  BOOST_TEST(same_functor == n);

  // Deterministic.
  const smc::Trws_result again = smc::trws_labeling(mesh, counts, unary, tables, result, np);
  BOOST_TEST(again.energy == rm.energy);
  BOOST_TEST(again.lower_bound == rm.lower_bound);
}

BOOST_AUTO_TEST_CASE(potts_grid_no_worse_than_alpha_expansion)
{
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int w = 40, labels = 5;
  for(int trial = 0; trial < 3; ++trial)
  {
    Graph g(w * w);
    std::vector<std::pair<std::size_t, std::size_t> > edge_list;
    std::vector<double> edge_weights;
    for(int y = 0; y < w; ++y)
      for(int x = 0; x < w; ++x)
        for(int d = 0; d < 2; ++d)
        {
          if((d == 0 && x + 1 == w) || (d == 1 && y + 1 == w)) continue;
          const std::size_t s = y * w + x, t = d == 0 ? s + 1 : s + w;
          Edge_data data;
          data.weight = 0.3 + (0.5 + 0.5 * trial) * u(rng);
          add_edge(s, t, data, g);
          edge_list.emplace_back(s, t);
          edge_weights.push_back(data.weight);
        }
    // Noisy piecewise-constant data: a few blobs of each label.
    std::vector<std::vector<double> > unary(w * w, std::vector<double>(labels));
    std::vector<std::vector<double> > cost_matrix(labels, std::vector<double>(w * w));
    std::vector<std::size_t> alpha_labels(w * w);
    for(int i = 0; i < w * w; ++i)
    {
      const int truth = ((i % w) / 10 + (i / w) / 10) % labels;
      for(int k = 0; k < labels; ++k)
        cost_matrix[k][i] = unary[i][k] = (k == truth ? 0.0 : 1.0) + 1.2 * u(rng);
      alpha_labels[i] = std::min_element(unary[i].begin(), unary[i].end()) - unary[i].begin();
    }
    CGAL::alpha_expansion_graphcut(edge_list, edge_weights, cost_matrix, alpha_labels);
    double alpha_energy = 0;
    for(int i = 0; i < w * w; ++i) alpha_energy += unary[i][alpha_labels[i]];
    for(std::size_t e = 0; e < edge_list.size(); ++e)
      alpha_energy += alpha_labels[edge_list[e].first] != alpha_labels[edge_list[e].second]
                          ? edge_weights[e]
                          : 0.0;

    std::vector<int> counts(w * w, labels), trws_labels(w * w);
    auto potts = boost::make_function_property_map<Graph_edge>(
        [&](const Graph_edge& e) { return Potts{g[e].weight}; });
    const smc::Trws_result r =
        smc::trws_labeling(g, index_map(counts, g), index_map(unary, g), potts,
                           index_map(trws_labels, g), params::number_of_iterations(200));
    BOOST_TEST_MESSAGE("Potts " << w << "x" << w << ", " << labels << " labels: TRW-S energy "
                                << r.energy << " (bound " << r.lower_bound << ", "
                                << r.number_of_iterations << " iterations), alpha expansion "
                                << alpha_energy);
    BOOST_TEST(r.energy <= 1.01 * alpha_energy);
    BOOST_TEST(r.lower_bound <= alpha_energy + 1e-9);
  }
}

#ifdef CGAL_LINKED_WITH_TBB
BOOST_AUTO_TEST_CASE(trws_labeling_takes_the_concurrency_tag)
{
  // A 36 x 36 grid graph (above Trws_solver's minimum_parallel_nodes) with table costs:
  // trws_labeling<double, Parallel_tag> runs on both threads of the arena and writes the
  // sequential labeling; with Potts functors it runs sequentially.
  const int w = 36;
  const std::size_t n = std::size_t(w * w);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> kdist(2, 9);
  std::vector<int> counts(n);
  std::vector<std::vector<double> > unary(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    counts[i] = kdist(rng);
    for(int k = 0; k < counts[i]; ++k) unary[i].push_back(u(rng));
  }
  Graph g(n);
  for(int y = 0; y < w; ++y)
    for(int x = 0; x < w; ++x)
      for(int d = 0; d < 2; ++d)
      {
        if((d == 0 && x + 1 == w) || (d == 1 && y + 1 == w)) continue;
        const std::size_t a = std::size_t(y * w + x), b = d == 0 ? a + 1 : a + std::size_t(w);
        Edge_data data;
        data.weight = 0.2 + u(rng);
        data.table.resize(std::size_t(counts[a] * counts[b]));
        for(double& c : data.table) c = 1.5 * u(rng);
        add_edge(a, b, data, g);
      }
  std::vector<int> sequential(n, -1), parallel(n, -1), potts_labels(n, -1);
  auto potts = boost::make_function_property_map<Graph_edge>(
      [&](const Graph_edge& e) { return Potts{g[e].weight}; });
  const auto np = params::relative_tolerance(0.0).number_of_iterations(20);
  smc::Trws_result rs, rp, rf;
  tbb::task_arena arena(2);
  arena.execute([&] {
    rs = smc::trws_labeling(g, index_map(counts, g), index_map(unary, g), get(&Edge_data::table, g),
                            index_map(sequential, g), np);
    rp = smc::trws_labeling<double, CGAL::Parallel_tag>(g, index_map(counts, g), index_map(unary, g),
                                                        get(&Edge_data::table, g), index_map(parallel, g), np);
    rf = smc::trws_labeling<double, CGAL::Parallel_tag>(g, index_map(counts, g), index_map(unary, g), potts,
                                                        index_map(potts_labels, g), np);
  });
  BOOST_TEST(rs.number_of_threads == 1u);
  BOOST_TEST(rp.number_of_threads == 2u);
  BOOST_TEST((parallel == sequential));
  BOOST_TEST(rp.energy == rs.energy);
  BOOST_TEST(rp.lower_bound == rs.lower_bound);
  BOOST_TEST(rf.number_of_threads == 1u);
  BOOST_TEST(std::count(potts_labels.begin(), potts_labels.end(), -1) == 0);
}
#endif

BOOST_AUTO_TEST_CASE(parallel_edges_are_merged)
{
  // Edges 0-1 twice (once reversed) and 1-2 twice: same as one edge each with the summed tables.
  std::mt19937 rng(23);
  for(int trial = 0; trial < 10; ++trial)
  {
    trws_test::Problem p;
    p.labels = trws_test::random_label_counts(6, 4, rng);
    p.edges = {{0, 1}, {1, 0}, {1, 2}, {2, 3}, {1, 2}, {3, 4}, {4, 5}, {5, 0}, {3, 0}};
    trws_test::random_costs(p, rng, 2.0);
    Graph g(6);
    for(std::size_t e = 0; e < p.edges.size(); ++e)
    {
      Edge_data d;
      d.table = p.pairwise[e];
      add_edge(p.edges[e].first, p.edges[e].second, d, g);
    }
    std::vector<int> result(6);
    const smc::Trws_result r = smc::trws_labeling(
        g, index_map(p.labels, g), index_map(p.unary, g), get(&Edge_data::table, g),
        index_map(result, g), params::relative_tolerance(1e-10).number_of_iterations(500));
    // The reference: the energy with the tables summed by hand, and its exact minimum.
    trws_test::Problem merged = p;
    merged.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 0}, {3, 0}};
    merged.pairwise = {p.pairwise[0], p.pairwise[2], p.pairwise[3], p.pairwise[5],
                       p.pairwise[6], p.pairwise[7], p.pairwise[8]};
    for(int k = 0; k < p.labels[0]; ++k)
      for(int l = 0; l < p.labels[1]; ++l)
        merged.pairwise[0][k * p.labels[1] + l] += p.cost(1, l, k);
    for(std::size_t i = 0; i < merged.pairwise[1].size(); ++i)
      merged.pairwise[1][i] += p.pairwise[4][i];
    BOOST_TEST(close(p.energy(result), r.energy));
    BOOST_TEST(close(merged.energy(result), r.energy));
    std::vector<int> flat;
    const smc::Trws_result rf =
        smc::trws_minimize(trws_test::make_energy<double>(merged), flat,
                           params::relative_tolerance(1e-10).number_of_iterations(500));
    BOOST_TEST(flat == result);
    BOOST_TEST(close(rf.lower_bound, r.lower_bound));
    BOOST_TEST(r.lower_bound <= trws_test::brute_force_minimum(merged) + 1e-9);
    // The functor path merges the same way.
    auto functors = boost::make_function_property_map<Graph_edge>([&](const Graph_edge& e) {
      const std::vector<double>* t = &g[e].table;
      const std::size_t cols = std::size_t(p.labels[target(e, g)]);
      return [t, cols](std::size_t k, std::size_t l) {
        return (*t)[k * cols + l];
      };
    });
    std::vector<int> result_functor(6);
    const smc::Trws_result rfun = smc::trws_labeling(
        g, index_map(p.labels, g), index_map(p.unary, g), functors, index_map(result_functor, g),
        params::relative_tolerance(1e-10).number_of_iterations(500));
    BOOST_TEST(result_functor == result);
    BOOST_TEST(close(rfun.energy, r.energy));
  }
}

BOOST_AUTO_TEST_CASE(initial_labeling_and_vertex_index_map)
{
  std::mt19937 rng(24);
  trws_test::Problem p;
  p.labels = trws_test::random_label_counts(9, 4, rng);
  p.edges = trws_test::random_loopy_graph(9, 12, rng);
  trws_test::random_costs(p, rng, 3.0);
  Graph g(9);
  for(std::size_t e = 0; e < p.edges.size(); ++e)
  {
    Edge_data d;
    d.table = p.pairwise[e];
    add_edge(p.edges[e].first, p.edges[e].second, d, g);
  }
  std::vector<int> best;
  const double optimum = trws_test::brute_force_minimum(p, &best);
  std::vector<int> result(9);
  const smc::Trws_result r = smc::trws_labeling(
      g, index_map(p.labels, g), index_map(p.unary, g), get(&Edge_data::table, g),
      index_map(result, g), params::initial_labeling(index_map(best, g)).number_of_iterations(1));
  BOOST_TEST(close(r.energy, optimum));
  BOOST_TEST(close(p.energy(result), optimum));

  // A vertex index map reversing the order: another node order, a valid result.
  std::vector<std::size_t> reversed(9);
  for(std::size_t i = 0; i < 9; ++i) reversed[i] = 8 - i;
  const smc::Trws_result rr = smc::trws_labeling(g, index_map(p.labels, g), index_map(p.unary, g),
                                                 get(&Edge_data::table, g), index_map(result, g),
                                                 params::vertex_index_map(index_map(reversed, g)));
  BOOST_TEST(close(p.energy(result), rr.energy));
  BOOST_TEST(rr.lower_bound <= optimum + 1e-9);
  // A vertex index map that is not a bijection.
  std::vector<std::size_t> duplicate(9, 0);
  for(std::size_t i = 0; i < 9; ++i) duplicate[i] = i;
  duplicate[5] = 4;
  BOOST_CHECK_THROW(smc::trws_labeling(g, index_map(p.labels, g), index_map(p.unary, g),
                                       get(&Edge_data::table, g), index_map(result, g),
                                       params::vertex_index_map(index_map(duplicate, g))),
                    smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(rejected_graph_inputs)
{
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
  auto build = [](std::vector<std::pair<int, int> > edge_list, std::vector<int> counts) {
    Graph g(counts.size());
    for(auto [s, t] : edge_list)
    {
      Edge_data d;
      d.table.assign(std::size_t(counts[s]) * counts[t], 1.0);
      add_edge(s, t, d, g);
    }
    return g;
  };
  std::vector<int> counts = {2, 3, 2};
  std::vector<std::vector<double> > unary = {{0, 1}, {0, 1, 2}, {1, 0}};
  std::vector<int> result(3);
  Graph g = build({{0, 1}, {2, 1}}, counts);
  auto run = [&](Graph& graph) {
    smc::trws_labeling(graph, index_map(counts, graph), index_map(unary, graph),
                       get(&Edge_data::table, graph), index_map(result, graph));
  };
  BOOST_CHECK_NO_THROW(run(g));

  counts[1] = 0;
  BOOST_TEST(message_of([&] { run(g); }).find("vertex 1 has no label") != std::string::npos);
  counts[1] = 3;
  unary[2].push_back(5.0);
  BOOST_TEST(message_of([&] { run(g); }).find("vertex 2 has 2 labels but 3 unary costs") !=
             std::string::npos);
  unary[2].pop_back();
  unary[0][1] = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(message_of([&] { run(g); }).find("unary cost of vertex 0, label 1") !=
             std::string::npos);
  unary[0][1] = std::numeric_limits<double>::infinity();
  BOOST_CHECK_THROW(run(g), smc::Invalid_energy_error);
  unary[0][1] = 1.0;

  Graph wrong_size = build({{0, 1}, {2, 1}}, counts);
  wrong_size[*edges(wrong_size).first].table.resize(5);
  BOOST_TEST(message_of([&] {
               run(wrong_size);
             }).find("table of edge (0, 1) has 5 costs instead of 2 x 3 = 6") != std::string::npos);
  Graph nan_table = build({{0, 1}, {2, 1}}, counts);
  g[*edges(g).first].table[4] = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(message_of([&] { run(g); }).find("pairwise cost of edge (0, 1), labels (1, 1)") !=
             std::string::npos);
  Graph loop = build({{0, 1}, {2, 2}}, counts);
  BOOST_TEST(message_of([&] { run(loop); }).find("self-loop at vertex 2") != std::string::npos);
  (void)nan_table;
}

BOOST_AUTO_TEST_SUITE_END()
