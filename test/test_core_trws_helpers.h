// SPDX-License-Identifier: GPL-3.0-or-later
// Shared helpers of the TRW-S tests: random energies, independent references (brute force,
// dynamic programming on trees), conversion to Discrete_energy.
#ifndef SMC_TEST_CORE_TRWS_HELPERS_H
#define SMC_TEST_CORE_TRWS_HELPERS_H

#include <CGAL/Surface_mesh_correspondence/trws.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace trws_test {

namespace smc = CGAL::Surface_mesh_correspondence;

/// A pairwise energy in plain containers, independent of the solver's storage.
struct Problem
{
  std::vector<int> labels;                    // K_i
  std::vector<std::pair<int, int> > edges;    // (s, t)
  std::vector<std::vector<double> > unary;    // unary[i][k]
  std::vector<std::vector<double> > pairwise; // pairwise[e][k * K_t + l]

  std::size_t n() const { return labels.size(); }
  double cost(std::size_t e, int k, int l) const
  {
    return pairwise[e][std::size_t(k) * labels[edges[e].second] + l];
  }
  template <typename LabelVector>
  double energy(const LabelVector& x) const
  {
    double sum = 0;
    for(std::size_t i = 0; i < n(); ++i) sum += unary[i][std::size_t(x[i])];
    for(std::size_t e = 0; e < edges.size(); ++e)
      sum += cost(e, int(x[edges[e].first]), int(x[edges[e].second]));
    return sum;
  }
};

/// Whether a and b agree to the relative tolerance `rel` (absolute below 1).
inline bool close(double a, double b, double rel = 1e-9)
{
  return std::abs(a - b) <= rel * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

inline void random_costs(Problem& p, std::mt19937& rng, double pairwise_scale = 1.0)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  p.unary.assign(p.n(), {});
  for(std::size_t i = 0; i < p.n(); ++i)
  {
    p.unary[i].resize(p.labels[i]);
    for(double& c : p.unary[i]) c = u(rng);
  }
  p.pairwise.assign(p.edges.size(), {});
  for(std::size_t e = 0; e < p.edges.size(); ++e)
  {
    p.pairwise[e].resize(std::size_t(p.labels[p.edges[e].first]) * p.labels[p.edges[e].second]);
    for(double& c : p.pairwise[e]) c = pairwise_scale * u(rng);
  }
}

inline std::vector<int> random_label_counts(std::size_t n, int max_labels, std::mt19937& rng)
{
  std::uniform_int_distribution<int> k(1, max_labels);
  std::vector<int> labels(n);
  for(int& x : labels) x = k(rng);
  return labels;
}

/// A random spanning tree on n nodes, with random node numbering and edge orientation.
inline std::vector<std::pair<int, int> > random_tree(int n, std::mt19937& rng)
{
  std::vector<int> perm(n);
  for(int i = 0; i < n; ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<std::pair<int, int> > edges;
  for(int i = 1; i < n; ++i)
  {
    const int parent = std::uniform_int_distribution<int>(0, i - 1)(rng);
    if(rng() % 2)
      edges.emplace_back(perm[i], perm[parent]);
    else
      edges.emplace_back(perm[parent], perm[i]);
  }
  return edges;
}

/// Exact minimum of a tree- or forest-structured energy by dynamic programming (min-sum).
inline double tree_minimum(const Problem& p)
{
  const std::size_t n = p.n();
  std::vector<std::vector<std::pair<int, int> > > adj(n); // (neighbour, edge)
  for(std::size_t e = 0; e < p.edges.size(); ++e)
  {
    adj[p.edges[e].first].emplace_back(p.edges[e].second, int(e));
    adj[p.edges[e].second].emplace_back(p.edges[e].first, int(e));
  }
  std::vector<int> parent(n, -2), parent_edge(n, -1), order;
  double total = 0;
  std::vector<std::vector<double> > belief(p.unary);
  for(std::size_t root = 0; root < n; ++root)
  {
    if(parent[root] != -2) continue;
    order.clear();
    parent[root] = -1;
    order.push_back(int(root));
    for(std::size_t q = 0; q < order.size(); ++q)
      for(auto [t, e] : adj[order[q]])
        if(parent[t] == -2)
        {
          parent[t] = order[q];
          parent_edge[t] = e;
          order.push_back(t);
        }
    for(std::size_t q = order.size(); q-- > 1;)
    {
      const int c = order[q], par = parent[c], e = parent_edge[c];
      for(int kp = 0; kp < p.labels[par]; ++kp)
      {
        double best = std::numeric_limits<double>::infinity();
        for(int kc = 0; kc < p.labels[c]; ++kc)
        {
          const double pc = (p.edges[e].first == c) ? p.cost(e, kc, kp) : p.cost(e, kp, kc);
          best = std::min(best, belief[c][kc] + pc);
        }
        belief[par][kp] += best;
      }
    }
    total += *std::min_element(belief[root].begin(), belief[root].end());
  }
  return total;
}

/// Exact minimum by enumeration (product of label counts must be small).
inline double brute_force_minimum(const Problem& p, std::vector<int>* argmin = nullptr)
{
  std::vector<int> x(p.n(), 0);
  double best = std::numeric_limits<double>::infinity();
  for(;;)
  {
    const double e = p.energy(x);
    if(e < best)
    {
      best = e;
      if(argmin) *argmin = x;
    }
    std::size_t i = 0;
    for(; i < p.n(); ++i)
    {
      if(++x[i] < p.labels[i]) break;
      x[i] = 0;
    }
    if(i == p.n()) break;
  }
  return best;
}

template <typename FT>
smc::Discrete_energy<FT> make_energy(const Problem& p)
{
  smc::Discrete_energy<FT> energy(p.labels, p.edges);
  for(std::size_t i = 0; i < p.n(); ++i)
    for(int k = 0; k < p.labels[i]; ++k) energy.unary_costs(i)[k] = FT(p.unary[i][k]);
  for(std::size_t e = 0; e < p.edges.size(); ++e)
    std::transform(p.pairwise[e].begin(), p.pairwise[e].end(), energy.pairwise_costs(e),
                   [](double c) { return FT(c); });
  return energy;
}

/// Pairwise costs read from a Problem on the fly (the functor path).
template <typename FT>
struct Problem_cost
{
  const Problem* p = nullptr;
  FT operator()(std::size_t e, std::size_t k, std::size_t l) const
  {
    return FT(p->cost(e, int(k), int(l)));
  }
};

template <typename FT>
smc::Discrete_energy<FT, Problem_cost<FT> > make_functor_energy(const Problem& p)
{
  smc::Discrete_energy<FT, Problem_cost<FT> > energy(p.labels, p.edges, Problem_cost<FT>{&p});
  for(std::size_t i = 0; i < p.n(); ++i)
    for(int k = 0; k < p.labels[i]; ++k) energy.unary_costs(i)[k] = FT(p.unary[i][k]);
  return energy;
}

/// A random connected graph on n nodes with about `extra` edges beyond a spanning tree.
inline std::vector<std::pair<int, int> > random_loopy_graph(int n, int extra, std::mt19937& rng)
{
  std::vector<std::pair<int, int> > edges = random_tree(n, rng);
  std::vector<std::vector<char> > used(n, std::vector<char>(n, 0));
  for(auto [s, t] : edges) used[s][t] = used[t][s] = 1;
  for(int tries = 0; tries < 10 * extra && extra > 0; ++tries)
  {
    const int s = int(rng() % n), t = int(rng() % n);
    if(s == t || used[s][t]) continue;
    used[s][t] = used[t][s] = 1;
    edges.emplace_back(s, t);
    --extra;
  }
  return edges;
}

} // namespace trws_test

#endif
