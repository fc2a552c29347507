// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Coupled map refinement: Algorithm 1 of Azencot, Dubrovina and Guibas, "Consistent shape
// matching via coupled optimization", Computer Graphics Forum 38(5), 2019.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_REFINE_COUPLED_MAPS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_REFINE_COUPLED_MAPS_H

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/map_selection.h>
#include <CGAL/Surface_mesh_correspondence/internal/neighborhood_search.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/trws.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Settings of the coupled refinement (see refine_coupled_maps() for their meaning). The defaults
/// are the registry's for automatic maps (Matching_settings); from() gives those of either kind of
/// maps.
struct Refinement_settings
{
  int number_of_candidates = internal::matching_defaults().number_of_candidates;  ///< m: labels per source vertex
  /// r_j: candidate neighbourhood radius (rings) at outer iteration j
  std::vector<int> ring_schedule = internal::matching_defaults().ring_schedule;
  /// mu: weight of the descriptor term against the geodesic term
  double unary_weight = internal::matching_defaults().unary_weight;
  /// lambda: weight of the cycle term lambda d_S(i, x_ba(k)) added to the unary cost of label k
  /// of source vertex i (0: the paper's energy; not used without coupling)
  double consistency_weight = internal::matching_defaults().consistency_weight;
  /// candidates from the inverse map and the cycle term (false: the paper's non-coupled ablation)
  bool use_coupling = internal::matching_defaults().use_coupling;
  /// 0: the length of the ring schedule
  int number_of_outer_iterations = internal::matching_defaults().number_of_outer_iterations;
  /// TRW-S iterations per solve
  int trws_number_of_iterations = internal::matching_defaults().trws_number_of_iterations;
  /// TRW-S stops when the bound's relative change is below this
  double trws_relative_tolerance = internal::matching_defaults().trws_relative_tolerance;
  /// pairwise terms between source vertices at most this many rings apart (1: mesh edges, the paper)
  int pairwise_rings = internal::matching_defaults().pairwise_rings;
  /// also seed the candidates with the matches of the source neighbours (propagation)
  bool use_neighbor_matches = internal::matching_defaults().use_neighbor_matches;
  /// The paper's rule, Eq. (4): stop at the first outer iteration that makes the maps less
  /// consistent. Either way the most consistent refined iterate is returned.
  bool stop_when_consistency_worsens = internal::matching_defaults().stop_when_consistency_worsens;

  /// The refinement settings of `m` (resolved for the origin of the maps, see
  /// Matching_settings::resolved()).
  static Refinement_settings from(const Matching_settings& m)
  {
    Refinement_settings s;
    s.number_of_candidates = m.number_of_candidates;
    s.ring_schedule = m.ring_schedule;
    s.unary_weight = m.unary_weight;
    s.consistency_weight = m.consistency_weight;
    s.use_coupling = m.use_coupling;
    s.number_of_outer_iterations = m.number_of_outer_iterations;
    s.trws_number_of_iterations = m.trws_number_of_iterations;
    s.trws_relative_tolerance = m.trws_relative_tolerance;
    s.pairwise_rings = m.pairwise_rings;
    s.use_neighbor_matches = m.use_neighbor_matches;
    s.stop_when_consistency_worsens = m.stop_when_consistency_worsens;
    s.check();
    return s;
  }

  /// The settings of the named parameters `np` for maps of origin `origin`: the registry's
  /// defaults for that origin, then every parameter given.
  template <typename NamedParameters>
  static Refinement_settings from(const NamedParameters& np, Map_origin origin)
  {
    return from(Matching_settings::from(np).resolved(origin));
  }

  /// Throws Invalid_parameter_error naming the first invalid setting.
  void check() const
  {
    if(number_of_candidates < 1)
      throw Invalid_parameter_error("number_of_candidates = " + std::to_string(number_of_candidates) +
                                    " must be at least 1");
    if(ring_schedule.empty()) throw Invalid_parameter_error("ring_schedule is empty");
    for(int r : ring_schedule)
      if(r < 0) throw Invalid_parameter_error("ring_schedule holds a negative radius " + std::to_string(r));
    if(!(unary_weight >= 0) || !std::isfinite(unary_weight))
      throw Invalid_parameter_error("unary_weight = " + std::to_string(unary_weight) +
                                    " must be finite and non-negative");
    if(!(consistency_weight >= 0) || !std::isfinite(consistency_weight))
      throw Invalid_parameter_error("consistency_weight = " + std::to_string(consistency_weight) +
                                    " must be finite and non-negative");
    if(number_of_outer_iterations < 0)
      throw Invalid_parameter_error("number_of_outer_iterations must be non-negative");
    if(trws_number_of_iterations < 1) throw Invalid_parameter_error("trws_number_of_iterations must be positive");
    if(pairwise_rings < 1) throw Invalid_parameter_error("pairwise_rings must be at least 1");
    if(!(trws_relative_tolerance >= 0)) throw Invalid_parameter_error("trws_relative_tolerance must be non-negative");
  }

  int outer_iterations() const
  {
    return number_of_outer_iterations > 0 ? number_of_outer_iterations : static_cast<int>(ring_schedule.size());
  }
  int rings(int outer_iteration) const
  {
    return ring_schedule[std::min<std::size_t>(static_cast<std::size_t>(outer_iteration), ring_schedule.size() - 1)];
  }
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// What the visitor of refine_coupled_maps() sees after each MRF solve.
struct Refinement_step
{
  int outer_iteration = 0;      ///< 0-based outer iteration of Algorithm 1
  int direction = 0;            ///< 0: the map 1 -> 2 was just solved; 1: the map 2 -> 1
  int rings = 0;                ///< radius of the candidate neighbourhoods
  double energy = 0;            ///< MRF energy of the new map
  double lower_bound = 0;       ///< TRW-S lower bound
  std::size_t trws_iterations = 0;
  std::size_t changed_vertices = 0;       ///< source vertices whose match changed
  std::size_t inconsistent_vertices = 0;  ///< Eq. (4) after this step (both directions, see number_of_inconsistent_vertices())
  double data_preparation_seconds = 0;    ///< candidates, unary and pairwise terms
  double trws_seconds = 0;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Default visitor of refine_coupled_maps(): does nothing and never stops. Derive from it and
/// hide the functions you need.
struct Default_refinement_visitor
{
  /// Called after every TRW-S iteration of every solve; return false to stop that solve.
  bool trws_iteration(int /*direction*/, std::size_t /*iteration*/, double /*energy*/, double /*lower_bound*/)
  {
    return true;
  }
  /// Called after every solve; return false to stop the refinement (the best maps so far by the
  /// consistency rule are returned).
  bool step(const Refinement_step&) { return true; }
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Why the refinement stopped.
enum class Refinement_termination
{
  schedule_completed,          ///< every outer iteration ran and consistency never got worse
  consistency_stopped_improving, ///< Eq. (4): the summed cycle-consistency error increased
  visitor_stop                 ///< the visitor asked to stop
};

inline const char* to_string(Refinement_termination t)
{
  switch(t)
  {
  case Refinement_termination::schedule_completed: return "schedule completed";
  case Refinement_termination::consistency_stopped_improving: return "consistency stopped improving";
  case Refinement_termination::visitor_stop: return "stopped by the visitor";
  }
  return "unknown";
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Summary of a coupled refinement.
struct Coupled_refinement_result
{
  int outer_iterations = 0;                    ///< outer iterations run (fully or partly)
  int kept_outer_iterations = 0;               ///< outer iterations whose maps were kept (0: the input maps)
  std::vector<Refinement_step> steps;          ///< one per solve, in order
  std::size_t inconsistent_vertices_before = 0; ///< Eq. (4) for the input maps
  std::size_t inconsistent_vertices_after = 0;  ///< Eq. (4) for the returned maps
  Refinement_termination termination = Refinement_termination::schedule_completed;
  double preprocessing_seconds = 0;            ///< Table 1: spectra, descriptors, distances (0 when shapes were given)
  double data_preparation_seconds = 0;         ///< Table 1: candidates, unary and pairwise terms
  double trws_seconds = 0;                     ///< Table 1: TRW-S solves
  double total_seconds = 0;
  /// Where the refined maps replaced their input (the public refine_coupled_maps() functions;
  /// match_shapes() reports it in its own result).
  Selection_result selection;
};

namespace internal {

/// Candidate labels of every source vertex (CSR, nodes in MRF order) and per-thread workspaces.
struct Candidate_sets
{
  std::vector<int> offsets;  ///< node u: labels[offsets[u] .. offsets[u+1])
  std::vector<int> labels;   ///< target vertex indices
};

/// Paper, Section 6: inverse of the map `opposite` (target -> source) as a map source -> target:
/// for a source vertex i with preimages Psi(i) = {k : opposite(k) = i}, the target vertex nearest
/// (Euclidean) to the mean of Psi(i); without preimages, `current`(i).
inline std::vector<int> inverse_map(const Shape_data& source, const Shape_data& target,
                                    const std::vector<int>& opposite, const std::vector<int>& current)
{
  const int ns = source.number_of_vertices();
  std::vector<int> count(static_cast<std::size_t>(ns), 0), first(static_cast<std::size_t>(ns), -1);
  std::vector<Eigen::Vector3d> sum(static_cast<std::size_t>(ns), Eigen::Vector3d::Zero());
  for(std::size_t k = 0; k < opposite.size(); ++k)
  {
    const int i = opposite[k];
    if(count[i]++ == 0) first[i] = static_cast<int>(k);
    sum[i] += target.mesh.point(static_cast<int>(k));
  }
  std::vector<int> result(static_cast<std::size_t>(ns));
  for(int i = 0; i < ns; ++i)
  {
    if(count[i] == 0)
      result[i] = current[i];
    else if(count[i] == 1)
      result[i] = first[i];
    else
    {
      const Eigen::Vector3d mean = sum[i] / count[i];
      result[i] = target.nearest->nearest(mean.x(), mean.y(), mean.z());
    }
  }
  return result;
}

/// Solver state reused between solves (energy storage, TRW-S messages). With Parallel_tag the
/// TRW-S passes use every thread of the arena (same result as sequentially, see Trws_solver).
template <typename ConcurrencyTag>
struct Refinement_workspace
{
  Discrete_energy<float> energy;
  Trws_solver<float, ConcurrencyTag> solver;
  Candidate_sets candidates;
  std::vector<std::pair<int, int> > edges;  ///< MRF edges (node pairs u < v) of the current source, sorted
  std::vector<std::size_t> first_edge;      ///< node u -> its first edge (u, v); size n + 1
  std::vector<int> label_counts;
  std::vector<int> labeling;
};

template <typename Visitor>
struct Trws_visitor_adapter
{
  Visitor* visitor;
  int direction;
  bool iteration(std::size_t k, double energy, double bound)
  {
    return visitor->trws_iteration(direction, k, energy, bound);
  }
};

/// Candidate sets Phi(i) of every source vertex, nodes in MRF order (paper, Section 5): farthest
/// point sampling of m target vertices in the union of the r-ring neighbourhoods of x(i) and
/// x~(i), seeded with x(i) and x~(i) (and, with use_neighbor_matches, with the matches x(j) of the
/// source neighbours j of i, which are added to the set). The seeds come first: label 0 is x(i).
template <typename ConcurrencyTag>
void select_candidates(const Shape_data& S, const Shape_data& T, const std::vector<int>& x,
                       const std::vector<int>& x_inverse, int rings, const Refinement_settings& settings,
                       Candidate_sets& C)
{
  const int n = S.number_of_vertices();
  const std::size_t m = static_cast<std::size_t>(settings.number_of_candidates);
  std::vector<std::vector<int> > per_node(static_cast<std::size_t>(n));
  const Edge_length_graph target_graph(T.mesh);
  parallel_for_ranges<ConcurrencyTag>(
      static_cast<std::size_t>(n),
      [&](std::size_t b, std::size_t e) {
        K_ring_workspace rings_ws(T.mesh);
        Farthest_point_sampler sampler(target_graph);
        std::vector<int> ring, seeds;
        for(std::size_t u = b; u < e; ++u)
        {
          const int i = S.node_order[u];
          seeds.assign(1, x[i]);
          if(settings.use_coupling && x_inverse[i] != x[i]) seeds.push_back(x_inverse[i]);
          rings_ws.k_ring(seeds.data(), seeds.size(), rings, ring);
          // Propagation: the matches of the source neighbours are candidates too (always kept), so
          // that a well-matched region can grow into a badly matched one.
          if(settings.use_neighbor_matches)
            for(const int* j = S.mesh.neighbors_begin(i); j != S.mesh.neighbors_end(i); ++j)
              if(std::find(seeds.begin(), seeds.end(), x[*j]) == seeds.end())
              {
                seeds.push_back(x[*j]);
                if(std::find(ring.begin(), ring.end(), x[*j]) == ring.end()) ring.push_back(x[*j]);
              }
          sampler.sample(ring.data(), ring.size(), seeds.data(), seeds.size(), std::max(m, seeds.size()),
                         per_node[u]);
        }
      },
      64);
  C.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  for(int u = 0; u < n; ++u) C.offsets[u + 1] = C.offsets[u] + static_cast<int>(per_node[u].size());
  C.labels.resize(static_cast<std::size_t>(C.offsets[n]));
  for(int u = 0; u < n; ++u) std::copy(per_node[u].begin(), per_node[u].end(), C.labels.begin() + C.offsets[u]);
}

/// Builds the MRF of one direction in `w.energy`: nodes = source vertices (breadth-first order),
/// edges = source mesh edges, labels = the candidate sets; unary
/// U(i, k) = mu |F_S(i) - F_T(k)|^2 (Eq. 2) + lambda d_S(i, opposite(k)) (the cycle term, with
/// coupling only; `opposite` is the current map target -> source) and pairwise
/// |d_S(i, j) - d_T(k, l)| (Eq. 3), with distances in units of sqrt(area) of each shape.
template <typename ConcurrencyTag>
void build_energy(const Shape_data& S, const Shape_data& T, const std::vector<int>& opposite,
                  const Refinement_settings& settings, Refinement_workspace<ConcurrencyTag>& w)
{
  const int n = S.number_of_vertices();
  const Candidate_sets& C = w.candidates;
  w.label_counts.resize(static_cast<std::size_t>(n));
  for(int u = 0; u < n; ++u) w.label_counts[u] = C.offsets[u + 1] - C.offsets[u];
  if(w.edges.empty())
  {
    if(settings.pairwise_rings <= 1)
      for(const auto& e : S.mesh.edges)
      {
        const int a = S.node_of_vertex[e[0]], b = S.node_of_vertex[e[1]];
        w.edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    else
    {
      K_ring_workspace ring_ws(S.mesh);
      std::vector<int> ring;
      for(int i = 0; i < n; ++i)
      {
        ring_ws.k_ring(&i, 1, settings.pairwise_rings, ring);
        for(int j : ring)
          if(j > i)
          {
            const int a = S.node_of_vertex[i], b = S.node_of_vertex[j];
            w.edges.emplace_back(std::min(a, b), std::max(a, b));
          }
      }
    }
    std::sort(w.edges.begin(), w.edges.end());
    w.first_edge.assign(static_cast<std::size_t>(n) + 1, 0);
    for(const auto& e : w.edges) ++w.first_edge[static_cast<std::size_t>(e.first) + 1];
    for(int u = 0; u < n; ++u) w.first_edge[u + 1] += w.first_edge[u];
  }
  w.energy.reset(w.label_counts, w.edges);

  const float mu = static_cast<float>(settings.unary_weight);
  const float source_unit = static_cast<float>(1.0 / S.scale), target_unit = static_cast<float>(1.0 / T.scale);
  // The cycle term uses the opposite map: part of the coupling (off in the non-coupled ablation).
  const float lambda =
      settings.use_coupling ? static_cast<float>(settings.consistency_weight) * source_unit : 0.0f;
  std::visit(
      [&](const auto& source_oracle) {
        parallel_for_ranges<ConcurrencyTag>(
            static_cast<std::size_t>(n),
            [&](std::size_t b, std::size_t e) {
              for(std::size_t u = b; u < e; ++u)
              {
                const int i = S.node_order[u];
                float* costs = w.energy.unary_costs(u);
                for(int k = C.offsets[u]; k < C.offsets[u + 1]; ++k)
                {
                  float c = mu * (S.descriptors.row(i) - T.descriptors.row(C.labels[k])).squaredNorm();
                  // Cycle term: how far the opposite map sends candidate k from i.
                  if(lambda > 0) c += lambda * source_oracle.distance(i, opposite[C.labels[k]]);
                  costs[k - C.offsets[u]] = c;
                }
              }
            },
            256);
      },
      S.oracle);

  // Pairwise tables, node by node: node u's edges (u, v) need the target distances from each
  // candidate of u to the candidates of its neighbours v, so the union L of those candidate sets
  // is indexed once (slot[l] = 1 + position in L) and each candidate's oracle row is walked once
  // for all of u's edges, instead of one search per table entry.
  const int number_of_targets = T.number_of_vertices();
  Object_pool<std::vector<int> > slot_pool([number_of_targets]() {
    return std::unique_ptr<std::vector<int> >(new std::vector<int>(static_cast<std::size_t>(number_of_targets), 0));
  });
  std::visit(
      [&](const auto& source_oracle) {
        std::visit(
            [&](const auto& target_oracle) {
              parallel_for_ranges<ConcurrencyTag>(
                  static_cast<std::size_t>(n),
                  [&](std::size_t b, std::size_t e) {
                    std::unique_ptr<std::vector<int> > slot_holder = slot_pool.acquire();
                    std::vector<int>& slot = *slot_holder; // all 0 between nodes
                    std::vector<int> set;
                    std::vector<float> row, source_lengths;
                    for(std::size_t u = b; u < e; ++u)
                    {
                      const std::size_t edges_begin = w.first_edge[u], edges_end = w.first_edge[u + 1];
                      if(edges_begin == edges_end) continue;
                      set.clear();
                      for(std::size_t edge = edges_begin; edge < edges_end; ++edge)
                      {
                        const int v = w.edges[edge].second;
                        for(int k = C.offsets[v]; k < C.offsets[v + 1]; ++k)
                          if(slot[C.labels[k]] == 0)
                          {
                            set.push_back(C.labels[k]);
                            slot[C.labels[k]] = static_cast<int>(set.size());
                          }
                      }
                      row.resize(set.size() + 1);
                      source_lengths.clear();
                      for(std::size_t edge = edges_begin; edge < edges_end; ++edge)
                        source_lengths.push_back(
                            source_oracle.distance(S.node_order[u], S.node_order[w.edges[edge].second]) *
                            source_unit);
                      const int ku = w.label_counts[u];
                      const int* lu = C.labels.data() + C.offsets[u];
                      for(int a = 0; a < ku; ++a)
                      {
                        target_oracle.distances_to_set(lu[a], slot.data(), set.data(), set.size(), row.data());
                        for(std::size_t edge = edges_begin; edge < edges_end; ++edge)
                        {
                          const int v = w.edges[edge].second;
                          const float d1 = source_lengths[edge - edges_begin];
                          const int kv = w.label_counts[v];
                          const int* lv = C.labels.data() + C.offsets[v];
                          float* table = w.energy.pairwise_costs(edge) + a * kv;
                          for(int c = 0; c < kv; ++c) table[c] = std::abs(d1 - row[slot[lv[c]]] * target_unit);
                        }
                      }
                      for(int l : set) slot[l] = 0;
                    }
                    slot_pool.release(std::move(slot_holder));
                  },
                  64);
            },
            T.oracle);
      },
      S.oracle);
}

/// One MRF solve (paper, function MAP of Algorithm 1): refines `x` (source -> target) in place
/// given the opposite map `opposite` (target -> source, for the cycle term) and its inverse
/// `x_inverse` (source -> target, for the candidates).
template <typename ConcurrencyTag, typename Visitor>
Refinement_step solve_direction(const Shape_data& S, const Shape_data& T, std::vector<int>& x,
                                const std::vector<int>& x_inverse, const std::vector<int>& opposite, int rings,
                                const Refinement_settings& settings, int direction, Refinement_workspace<ConcurrencyTag>& w,
                                Visitor& visitor)
{
  Refinement_step step;
  step.direction = direction;
  step.rings = rings;
  const auto t0 = std::chrono::steady_clock::now();
  select_candidates<ConcurrencyTag>(S, T, x, x_inverse, rings, settings, w.candidates);
  build_energy<ConcurrencyTag>(S, T, opposite, settings, w);
  const auto t1 = std::chrono::steady_clock::now();
  step.data_preparation_seconds = std::chrono::duration<double>(t1 - t0).count();

  // TRW-S, started from the current map (label 0 of every node is x(i), the first seed).
  const int n = S.number_of_vertices();
  w.labeling.assign(static_cast<std::size_t>(n), 0);
  Trws_visitor_adapter<Visitor> adapter{&visitor, direction};
  const Trws_result r = w.solver.solve(
      w.energy, w.labeling,
      parameters::relative_tolerance(settings.trws_relative_tolerance, parameters::initial_labeling(w.labeling))
          .number_of_iterations(static_cast<std::size_t>(settings.trws_number_of_iterations))
          .visitor(adapter));
  step.energy = r.energy;
  step.lower_bound = r.lower_bound;
  step.trws_iterations = r.number_of_iterations;
  const Candidate_sets& C = w.candidates;
  for(int u = 0; u < n; ++u)
  {
    const int i = S.node_order[u];
    const int k = C.labels[static_cast<std::size_t>(C.offsets[u] + w.labeling[u])];
    step.changed_vertices += k != x[i];
    x[i] = k;
  }
  step.trws_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  return step;
}

inline std::vector<int> to_int_map(const Vertex_index_map_vector& m)
{
  return std::vector<int>(m.begin(), m.end());
}

inline std::size_t inconsistency(const std::vector<int>& x12, const std::vector<int>& x21)
{
  std::size_t c = 0;
  for(std::size_t i = 0; i < x12.size(); ++i) c += x21[x12[i]] != static_cast<int>(i);
  for(std::size_t k = 0; k < x21.size(); ++k) c += x12[x21[k]] != static_cast<int>(k);
  return c;
}

/// Algorithm 1 on prepared shapes; `x12`, `x21` are refined in place.
template <typename ConcurrencyTag, typename Visitor>
Coupled_refinement_result refine_coupled_maps(const Shape_data& M1, const Shape_data& M2, std::vector<int>& x12,
                                              std::vector<int>& x21, const Refinement_settings& settings,
                                              Visitor& visitor)
{
  settings.check();
  const auto start = std::chrono::steady_clock::now();
  if(M1.descriptors.cols() != M2.descriptors.cols())
    throw Invalid_parameter_error("the two shapes have descriptor stacks of different sizes (" +
                                  std::to_string(M1.descriptors.cols()) + " and " +
                                  std::to_string(M2.descriptors.cols()) + "): prepare them with the same settings");
  Coupled_refinement_result result;
  result.inconsistent_vertices_before = inconsistency(x12, x21);
  std::size_t best_c = result.inconsistent_vertices_before;
  bool have_best = false;  // the most consistent refined iterate is returned (the selection compares it with the input)
  std::vector<int> best12 = x12, best21 = x21;
  Refinement_workspace<ConcurrencyTag> w12, w21;
  bool stop = false;
  for(int t = 0; t < settings.outer_iterations() && !stop; ++t)
  {
    result.outer_iterations = t + 1;
    const int r = settings.rings(t);
    // One MRF solve for the map a -> b, using the inverse of the current map b -> a; returns
    // whether the visitor lets the refinement go on.
    auto solve = [&](const Shape_data& A, const Shape_data& B, std::vector<int>& x_ab, const std::vector<int>& x_ba,
                     int direction, Refinement_workspace<ConcurrencyTag>& w) {
      const std::vector<int> inverse = inverse_map(A, B, x_ba, x_ab);
      Refinement_step step = solve_direction<ConcurrencyTag>(A, B, x_ab, inverse, x_ba, r, settings, direction, w, visitor);
      step.outer_iteration = t;
      step.inconsistent_vertices = inconsistency(x12, x21);
      result.steps.push_back(step);
      if(visitor.step(step)) return true;
      result.termination = Refinement_termination::visitor_stop;
      return false;
    };
    // 1. the map 1 -> 2, then 2. the map 2 -> 1 using the inverse of the new map 1 -> 2
    stop = !solve(M1, M2, x12, x21, 0, w12) || !solve(M2, M1, x21, x12, 1, w21);
    // Eq. (4): continue while the summed cycle-consistency error does not increase.
    const std::size_t c = inconsistency(x12, x21);
    if(have_best && c > best_c)
    {
      if(settings.stop_when_consistency_worsens)
      {
        if(!stop) result.termination = Refinement_termination::consistency_stopped_improving;
        stop = true;
      }
    }
    else
    {
      have_best = true;
      best_c = c;
      best12 = x12;
      best21 = x21;
      result.kept_outer_iterations = t + 1;
    }
  }
  x12.swap(best12);
  x21.swap(best21);
  result.inconsistent_vertices_after = best_c;
  for(const Refinement_step& s : result.steps)
  {
    result.data_preparation_seconds += s.data_preparation_seconds;
    result.trws_seconds += s.trws_seconds;
  }
  result.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

/// The vertex indices of a vertex-to-vertex property map: entry i is the index (in
/// `target_index`) of the vertex of `target` that `map` assigns to vertex i of `source_shape`.
/// Throws Invalid_map_error naming `what` and the vertex when an entry is not a vertex of
/// `target` (the null vertex, or a descriptor of another mesh); the entries are looked up in a
/// hash set of the target's vertices, never dereferenced.
template <typename Index, typename Map, typename TargetMesh, typename Shape, typename TargetIndexMap>
std::vector<Index> vertex_map_indices(const Map& map, const TargetMesh& target, const Shape& source_shape,
                                      const TargetIndexMap& target_index, const std::string& what,
                                      const std::string& target_name)
{
  typedef typename boost::graph_traits<TargetMesh>::vertex_descriptor Vertex;
  std::unordered_set<Vertex> target_vertices;
  target_vertices.reserve(std::size_t(num_vertices(target)));
  for(Vertex v : vertices(target)) target_vertices.insert(v);
  std::vector<Index> out(source_shape.number_of_vertices());
  for(std::size_t i = 0; i < out.size(); ++i)
  {
    const Vertex t = get(map, source_shape.vertex(i));
    if(target_vertices.count(t) == 0)
      throw Invalid_map_error(what + ": vertex " + std::to_string(i) + " is mapped to a vertex that is not in " +
                              target_name);
    out[i] = static_cast<Index>(get(target_index, t));
  }
  return out;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Coupled refinement of two maps between prepared shapes (index-based form of
/// refine_coupled_maps()), followed by the selection of where the refined maps replace their
/// input. `map_12[i]` is the vertex of `shape_2` matched to vertex i of `shape_1`, `map_21` the
/// other way round; both are refined in place.
/// \throws Invalid_map_error when a map does not fit the shapes, Invalid_parameter_error
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Coupled_refinement_result refine_coupled_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                              const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                              Vertex_index_map_vector& map_12, Vertex_index_map_vector& map_21,
                                              const NamedParameters& np = parameters::default_values())
{
  check_vertex_map(map_12, shape_1.number_of_vertices(), shape_2.number_of_vertices(), "map 1->2");
  check_vertex_map(map_21, shape_2.number_of_vertices(), shape_1.number_of_vertices(), "map 2->1");
  const Matching_settings all = Matching_settings::from(np);
  const Refinement_settings settings = Refinement_settings::from(all.resolved(Map_origin::given));
  // The visitor is used through a reference when given as std::ref(v), else as a copy.
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Default_refinement_visitor>::reference Visitor_reference;
  Default_refinement_visitor default_visitor;
  Visitor_reference visitor = parameters::choose_parameter(
      parameters::get_parameter_reference(np, CGAL::internal_np::visitor), default_visitor);
  std::vector<int> x12 = internal::to_int_map(map_12), x21 = internal::to_int_map(map_21);
  const std::vector<int> input12 = x12, input21 = x21;
  Coupled_refinement_result r =
      internal::refine_coupled_maps<ConcurrencyTag>(shape_1.data(), shape_2.data(), x12, x21, settings, visitor);
  r.selection = internal::select_refined_maps<ConcurrencyTag>(shape_1.data(), shape_2.data(), input12, input21, x12,
                                                              x21, internal::Selection_settings::from(all));
  map_12.assign(x12.begin(), x12.end());
  map_21.assign(x21.begin(), x21.end());
  return r;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Refines a pair of imperfect point-to-point maps between two triangle meshes, jointly, into
/// accurate and cycle-consistent maps (Azencot, Dubrovina and Guibas 2019, Algorithm 1).
///
/// Each outer iteration j solves, for the map 1 -> 2 and then for the map 2 -> 1 (each using the
/// newest opposite map), the sparse relaxed quadratic assignment problem
/// \f[ \min_{x} \; \sum_i \big( \mu \| F_a(i) - F_b(x(i)) \|^2 + \lambda\, d_a(i, y(x(i))) \big)
///       + \sum_{(i,j) \in E_a} \big| d_a(i,j) - d_b(x(i), x(j)) \big| , \qquad x(i) \in \Phi(i), \f]
/// (y the current opposite map; the cycle term with \f$ \lambda \f$ is ours, 0 gives the paper's
/// energy)
/// as a Markov random field with TRW-S, where \f$ \Phi(i) \f$ is a farthest point sampling of
/// m target vertices in the union of the \f$ r_j \f$-ring neighbourhoods of the current match
/// \f$ x(i) \f$ and of the inverse of the opposite map \f$ \tilde x(i) \f$ (both always kept).
/// Distances are geodesic, divided by \f$ \sqrt{\mathrm{area}} \f$ of each shape, and the
/// descriptor stack is scale-invariant, so the parameters do not depend on units. The iteration
/// runs the ring schedule and keeps the most consistent refined iterate by Eq. (4) (the number of
/// vertices that are not fixed points of the cycles; the paper's early stop is an option); then
/// the refined maps replace their input everywhere when they are more consistent, else only
/// where they distort mid-range geodesic distances less (setting `refinement_selection`). For
/// the whole pipeline from two meshes (automatic or given initial maps), use match_shapes().
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (preprocessing, candidate
///   selection, the MRF terms and the TRW-S passes in parallel, with the same result)
/// \tparam TriangleMesh1, TriangleMesh2 models of `FaceListGraph` whose faces are triangles
/// \tparam VertexVertexMap12 a model of `ReadWritePropertyMap` from the vertices of `tm1` to those
///   of `tm2` (read: initial map; written: refined map); same for VertexVertexMap21
/// \param tm1, tm2 the two meshes
/// \param map_12, map_21 input and output: the maps to refine, refined in place
/// \param np optional named parameters: the settings of stages `preparation`, `refinement` and
///   `selection` of the registry (see Matching_settings and the settings table of the manual),
///   with the registry's defaults for given maps: `number_of_candidates` (m, 20), `ring_schedule`
///   ({6, 4, 3, 2, 1}; the paper used {6, 4, 3}), `unary_weight` (mu, 0.03), `consistency_weight`
///   (lambda, 1; 0: the paper's energy), `use_coupling` (false: the paper's non-coupled ablation),
///   `use_neighbor_matches`, `pairwise_rings`, `stop_when_consistency_worsens`,
///   `number_of_outer_iterations`, `trws_number_of_iterations` (100), `trws_relative_tolerance`,
///   `refinement_selection`, `selection_radius`, `selection_samples`, `selection_smoothing`;
///   `matching_settings`; `visitor` (default Default_refinement_visitor).
/// \param np1, np2 `vertex_point_map` and `vertex_index_map` of each mesh
/// \pre both meshes are connected manifold triangle meshes
/// \throws Invalid_mesh_error, Invalid_map_error (a map entry that is not a vertex of the other
///   mesh), Invalid_parameter_error
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename VertexVertexMap12, typename VertexVertexMap21,
          typename NamedParameters = parameters::Default_named_parameters,
          typename NamedParameters1 = parameters::Default_named_parameters,
          typename NamedParameters2 = parameters::Default_named_parameters>
Coupled_refinement_result refine_coupled_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                              VertexVertexMap12 map_12, VertexVertexMap21 map_21,
                                              const NamedParameters& np = parameters::default_values(),
                                              const NamedParameters1& np1 = parameters::default_values(),
                                              const NamedParameters2& np2 = parameters::default_values())
{
  const auto start = std::chrono::steady_clock::now();
  const Correspondence_shape<TriangleMesh1, ConcurrencyTag> s1(tm1, parameters::combine(np1, np),
                                                               internal::Shape_preparation{false}, "mesh 1");
  const Correspondence_shape<TriangleMesh2, ConcurrencyTag> s2(tm2, parameters::combine(np2, np),
                                                               internal::Shape_preparation{false}, "mesh 2");
  const double preprocessing = internal::seconds_since(start);
  auto vim1 = CGAL::get_initialized_vertex_index_map(tm1, np1);
  auto vim2 = CGAL::get_initialized_vertex_index_map(tm2, np2);
  Vertex_index_map_vector m12 = internal::vertex_map_indices<std::size_t>(map_12, tm2, s1, vim2, "map 1->2", "mesh 2");
  Vertex_index_map_vector m21 = internal::vertex_map_indices<std::size_t>(map_21, tm1, s2, vim1, "map 2->1", "mesh 1");
  Coupled_refinement_result r = refine_coupled_maps<ConcurrencyTag>(s1, s2, m12, m21, np);
  for(std::size_t i = 0; i < m12.size(); ++i) put(map_12, s1.vertex(i), s2.vertex(m12[i]));
  for(std::size_t k = 0; k < m21.size(); ++k) put(map_21, s2.vertex(k), s1.vertex(m21[k]));
  r.preprocessing_seconds = preprocessing;
  r.total_seconds = internal::seconds_since(start);
  return r;
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_REFINE_COUPLED_MAPS_H
