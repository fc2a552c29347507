// SPDX-License-Identifier: GPL-3.0-or-later
// TRW-S on a tiny image denoising problem, twice: on a boost::adjacency_list with property maps
// (trws_labeling), and on the flat Discrete_energy whose tables are written in place.

#include <CGAL/Surface_mesh_correspondence/trws.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/property_map/function_property_map.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <utility>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;

int main()
{
  // A 12 x 8 image with 4 grey levels (a bright square on a dark background) plus noise.
  const int w = 12, h = 8, levels = 4;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.8);
  std::vector<std::pair<int, int> > edges; // 4-neighbourhood
  std::vector<std::vector<double> > unary(w * h, std::vector<double>(levels));
  for(int y = 0; y < h; ++y)
    for(int x = 0; x < w; ++x)
    {
      const int i = y * w + x;
      if(x + 1 < w) edges.emplace_back(i, i + 1);
      if(y + 1 < h) edges.emplace_back(i, i + w);
      const double observed = ((x >= 3 && x < 9 && y >= 2 && y < 6) ? 3.0 : 0.0) + noise(rng);
      for(int k = 0; k < levels; ++k) unary[i][k] = (observed - k) * (observed - k);
    }
  auto smoothness = [](std::size_t k, std::size_t l) { // truncated linear
    return std::min(2.0, 1.5 * std::abs(double(k) - double(l)));
  };
  std::vector<int> label_counts(w * h, levels);

  // --- 1. Generic entry point: any BGL graph and property maps.
  typedef boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> Graph;
  typedef boost::graph_traits<Graph>::edge_descriptor Edge;
  const Graph g(edges.begin(), edges.end(), w * h);
  auto vertex_map = [&](auto& values) {
    return boost::make_iterator_property_map(values.begin(), get(boost::vertex_index, g));
  };
  // Pairwise costs as a functor (k, l) -> cost for every edge: no table is stored.
  auto pairwise = boost::make_function_property_map<Edge>([&](const Edge&) { return smoothness; });
  std::vector<int> labels(w * h);
  const smc::Trws_result r =
      smc::trws_labeling(g, vertex_map(label_counts), vertex_map(unary), pairwise,
                         vertex_map(labels), smc::parameters::number_of_iterations(50));
  std::cout << "trws_labeling: energy " << r.energy << ", lower bound " << r.lower_bound << ", "
            << r.number_of_iterations << " iterations (" << r.termination << ")\n";
  for(int y = 0; y < h; ++y)
  {
    for(int x = 0; x < w; ++x) std::cout << " .:#"[labels[y * w + x]];
    std::cout << "\n";
  }

  // --- 2. Flat layer: build the graph once, write the costs in place, solve (and solve again).
  smc::Discrete_energy<float> energy(label_counts, edges);
  for(int i = 0; i < w * h; ++i)
    for(int k = 0; k < levels; ++k) energy.unary_costs(i)[k] = float(unary[i][k]);
  for(std::size_t e = 0; e < energy.number_of_edges(); ++e)
  {
    float* table = energy.pairwise_costs(e); // levels x levels, row = label of source(e)
    for(int k = 0; k < levels; ++k)
      for(int l = 0; l < levels; ++l) table[k * levels + l] = float(smoothness(k, l));
  }
  smc::Trws_solver<float> solver; // keeps its workspace between solves
  std::vector<int> flat_labels;
  const smc::Trws_result f = solver.solve(energy, flat_labels);
  std::cout << "Trws_solver<float>: energy " << f.energy << ", lower bound " << f.lower_bound
            << ", same labels: " << (flat_labels == labels ? "yes" : "no") << "\n";
  return 0;
}
