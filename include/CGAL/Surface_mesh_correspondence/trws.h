// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sequential tree-reweighted message passing (TRW-S) for pairwise discrete energies, written from
// V. Kolmogorov, "Convergent tree-reweighted message passing for energy minimization", IEEE PAMI
// 28(10), 2006.
//
// Two layers:
// - a flat one: `Discrete_energy<FT>` (label counts, unary costs, edge list and dense pairwise
//   tables stored contiguously, written in place by the caller) or
//   `Discrete_energy<FT, PairwiseCost>` (pairwise costs from a functor, no tables), minimised by
//   `Trws_solver<FT>` or `trws_minimize()`;
// - a generic one: `trws_labeling()` on any BGL graph (VertexListGraph + EdgeListGraph) with
//   property maps for label counts, costs and the output labeling.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_TRWS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_TRWS_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/internal/trws_energy_base.h>
#include <CGAL/Surface_mesh_correspondence/internal/trws_kernels.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Iterator_range.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/concept/assert.hpp>
#include <boost/graph/graph_concepts.hpp>
#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>
#include <boost/range/begin.hpp>
#include <boost/range/size.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <ostream>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Why a TRW-S run stopped.
enum class Trws_termination
{
  /// The energy of the best labeling is within the relative tolerance of the lower bound: the
  /// labeling is optimal (up to that tolerance).
  optimal,
  /// The lower bound changed by at most the relative tolerance in one iteration.
  converged,
  /// The maximum number of iterations was run.
  iteration_limit,
  /// The visitor returned `false`.
  visitor_stop
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The name of a termination reason ("optimal", "converged", "iteration_limit", "visitor_stop").
inline const char* to_string(Trws_termination t)
{
  switch(t)
  {
  case Trws_termination::optimal: return "optimal";
  case Trws_termination::converged: return "converged";
  case Trws_termination::iteration_limit: return "iteration_limit";
  default: return "visitor_stop";
  }
}

/// Writes `to_string(t)`.
inline std::ostream& operator<<(std::ostream& out, Trws_termination t)
{
  return out << to_string(t);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Summary of a TRW-S run.
struct Trws_result
{
  /// \f$E(x)\f$ of the returned labeling, summed in double precision.
  double energy = 0;
  /// The highest lower bound on \f$\min_x E(x)\f$ seen (\f$-\infty\f$ if no iteration ran).
  double lower_bound = -std::numeric_limits<double>::infinity();
  /// Number of iterations run (one iteration = one forward and one backward pass).
  std::size_t number_of_iterations = 0;
  /// Why the run stopped.
  Trws_termination termination = Trws_termination::iteration_limit;
  /// Threads that ran the passes: 1 when they ran sequentially (`CGAL::Sequential_tag`, an energy
  /// with functor costs or with fewer than `Trws_solver::minimum_parallel_nodes` nodes, or an arena
  /// of one thread), else the concurrency of the TBB arena the solver was called in.
  std::size_t number_of_threads = 1;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The default visitor of the TRW-S functions: never stops the run.
struct Trws_default_visitor
{
  bool iteration(std::size_t /*iteration*/, double /*energy*/, double /*lower_bound*/)
  {
    return true;
  }
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Tag selecting dense pairwise tables as the storage of the pairwise costs of a
/// `Discrete_energy` (the default).
struct Dense_pairwise_tables
{};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A pairwise discrete energy (a Markov random field) whose pairwise costs are given by a functor
/// evaluated on the fly: no table is stored, so the memory is \f$O(\sum_i K_i + |E|)\f$ for the
/// energy and \f$O(\sum_i K_i + |E| \max_i K_i)\f$ for the solver.
///
/// \f[ E(x) = \sum_{i} \theta_i(x_i) + \sum_{e = (s, t)} \theta_e(x_s, x_t),
///     \qquad x_i \in \{0, \dots, K_i - 1\}. \f]
///
/// Nodes are numbered 0 to n-1, edges 0 to m-1. Edge e joins `source(e)` and `target(e)`;
/// self-loops and two edges joining the same pair of nodes are rejected.
///
/// \tparam FT `float` or `double`: type of the stored costs and of the solver's messages.
/// \tparam PairwiseCost a copyable functor with `FT operator()(std::size_t e, std::size_t k,
///   std::size_t l) const` returning \f$\theta_e(k, l)\f$, `k` a label of `source(e)`, `l` a label
///   of `target(e)`. It may also provide
///   `void fill_table(std::size_t e, std::size_t K_s, std::size_t K_t, FT* table) const`, writing
///   the whole \f$K_s \times K_t\f$ row-major table of edge e at once; the solver then calls it
///   instead of the element-wise operator. Costs must be finite (checked in the first iteration).
///
/// The specialisation `Discrete_energy<FT, Dense_pairwise_tables>` (the default) stores the tables.
template <typename FT = double, typename PairwiseCost = Dense_pairwise_tables>
class Discrete_energy : public internal::Discrete_energy_base<FT>
{
public:
  /// Pairwise costs are computed, not stored.
  static constexpr bool has_tables = false;

  /// An energy without nodes.
  Discrete_energy() {}

  /// Builds the graph: `label_counts[i]` = \f$K_i \geq 1\f$ (a range of integers), `edges` a range
  /// of pairs (anything `std::get<0>` / `std::get<1>` reads: `std::pair`, `std::array<., 2>`,
  /// `std::tuple`) of node indices. Unary costs are set to zero.
  /// \throws Invalid_energy_error for a node without labels, an edge end out of range, a
  ///   self-loop or parallel edges.
  template <typename LabelCountRange, typename EdgeRange>
  Discrete_energy(const LabelCountRange& label_counts, const EdgeRange& edges,
                  const PairwiseCost& pairwise_cost = PairwiseCost())
    : cost_(pairwise_cost)
  {
    this->build_structure(label_counts, edges);
  }

  /// Rebuilds the graph (same arguments as the constructor), keeping the allocated memory and the
  /// functor. Unary costs are set to zero.
  template <typename LabelCountRange, typename EdgeRange>
  void reset(const LabelCountRange& label_counts, const EdgeRange& edges)
  {
    this->build_structure(label_counts, edges);
  }

  /// The pairwise cost functor.
  const PairwiseCost& pairwise_cost_functor() const { return cost_; }
  PairwiseCost& pairwise_cost_functor() { return cost_; }

  /// \f$\theta_e(k, l)\f$, `k` a label of `source(e)`, `l` a label of `target(e)`.
  FT pairwise_cost(std::size_t e, std::size_t k, std::size_t l) const { return FT(cost_(e, k, l)); }

  /// \f$E(x)\f$ in double precision; `labels[i]` is the label of node i.
  /// \throws Invalid_parameter_error if `labels` has the wrong size or a label out of range.
  template <typename LabelRange>
  double energy(const LabelRange& labels) const;

  /// Throws Invalid_energy_error naming the first NaN or infinite unary cost (pairwise costs
  /// of a functor are checked by the solver when it first evaluates them).
  void check_costs() const { this->check_unary_costs(); }

  /// Bytes of memory held by the energy.
  std::size_t memory_bytes() const { return this->structure_bytes(); }

private:
  PairwiseCost cost_;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A pairwise discrete energy (a Markov random field) with dense pairwise tables, stored
/// contiguously and written in place by the caller:
///
/// \f[ E(x) = \sum_{i} \theta_i(x_i) + \sum_{e = (s, t)} \theta_e(x_s, x_t),
///     \qquad x_i \in \{0, \dots, K_i - 1\}. \f]
///
/// Nodes are numbered 0 to n-1 and have their own label counts \f$K_i\f$; edges are numbered 0 to
/// m-1, edge e joins `source(e)` and `target(e)` and owns a \f$K_{source} \times K_{target}\f$
/// table, row-major: `pairwise_costs(e)[k * K_target + l]` = \f$\theta_e(k, l)\f$. Memory:
/// \f$O(\sum_i K_i + \sum_{(s,t)} K_s K_t)\f$ values of type FT.
///
/// Construction (which fixes the graph and allocates zeroed costs) and minimisation are separate:
/// write the costs through `unary_costs(i)` and `pairwise_costs(e)`, solve, change costs, solve
/// again; `reset()` changes the graph and reuses the memory. Both kinds of energy also provide
/// `number_of_nodes()`, `number_of_edges()`, `number_of_labels(i)`, `maximum_number_of_labels()`,
/// `source(e)`, `target(e)`, `unary_costs(i)` (pointer to the \f$K_i\f$ costs of node i, writable),
/// `unary_cost(i, k)`, `unary_data()` / `unary_offset(i)` (all unary costs, node after node).
///
/// Speed: the solver reads the tables in the order of the nodes. Numbering the edges by their
/// smaller end (e.g. pairs (i, j), i < j, sorted, as `internal::Indexed_mesh` lists mesh edges)
/// makes the forward pass read the tables in storage order (about 25% faster per iteration when
/// the tables do not fit in the cache, see doc/trws.md).
///
/// Self-loops and two edges joining the same pair of nodes are rejected (Invalid_energy_error):
/// sum their tables into one edge instead. Costs must be finite (checked by the solver); a
/// forbidden combination is expressed by a large finite cost.
///
/// \tparam FT `float` or `double`.
template <typename FT>
class Discrete_energy<FT, Dense_pairwise_tables> : public internal::Discrete_energy_base<FT>
{
public:
  /// Pairwise costs are stored in tables.
  static constexpr bool has_tables = true;

  /// An energy without nodes.
  Discrete_energy() { table_offsets_.assign(1, 0); }

  /// Builds the graph: `label_counts[i]` = \f$K_i \geq 1\f$ (a range of integers), `edges` a range
  /// of pairs (anything `std::get<0>` / `std::get<1>` reads: `std::pair`, `std::array<., 2>`,
  /// `std::tuple`) of node indices. All costs are set to zero.
  /// \throws Invalid_energy_error for a node without labels, an edge end out of range, a
  ///   self-loop or parallel edges.
  template <typename LabelCountRange, typename EdgeRange>
  Discrete_energy(const LabelCountRange& label_counts, const EdgeRange& edges)
  {
    reset(label_counts, edges);
  }

  /// Rebuilds the graph (same arguments as the constructor), keeping the allocated memory. All
  /// costs are set to zero.
  template <typename LabelCountRange, typename EdgeRange>
  void reset(const LabelCountRange& label_counts, const EdgeRange& edges)
  {
    this->build_structure(label_counts, edges);
    const std::size_t m = this->number_of_edges();
    table_offsets_.resize(m + 1);
    table_offsets_[0] = 0;
    for(std::size_t e = 0; e < m; ++e)
      table_offsets_[e + 1] =
          table_offsets_[e] +
          std::size_t(this->label_counts_[this->source(e)]) * this->label_counts_[this->target(e)];
    tables_.assign(table_offsets_[m], FT(0));
  }

  /// The \f$K_s \times K_t\f$ table of edge e = (s, t), row-major (row = label of s); write it in
  /// place.
  FT* pairwise_costs(std::size_t e) { return tables_.data() + table_offsets_[e]; }
  const FT* pairwise_costs(std::size_t e) const { return tables_.data() + table_offsets_[e]; }
  /// \f$\theta_e(k, l)\f$, `k` a label of `source(e)`, `l` a label of `target(e)`.
  FT& pairwise_cost(std::size_t e, std::size_t k, std::size_t l)
  {
    return tables_[table_offsets_[e] + k * this->label_counts_[this->target(e)] + l];
  }
  FT pairwise_cost(std::size_t e, std::size_t k, std::size_t l) const
  {
    return tables_[table_offsets_[e] + k * this->label_counts_[this->target(e)] + l];
  }
  /// All tables, edge after edge; edge e starts at `pairwise_offset(e)`.
  FT* pairwise_data() { return tables_.data(); }
  const FT* pairwise_data() const { return tables_.data(); }
  std::size_t pairwise_offset(std::size_t e) const { return table_offsets_[e]; }

  /// \f$E(x)\f$ in double precision; `labels[i]` is the label of node i.
  /// \throws Invalid_parameter_error if `labels` has the wrong size or a label out of range.
  template <typename LabelRange>
  double energy(const LabelRange& labels) const;

  /// Throws Invalid_energy_error naming the first NaN or infinite cost (node and label, or edge
  /// and labels).
  void check_costs() const
  {
    this->check_unary_costs();
    const std::size_t bad = internal::trws_first_non_finite(tables_.data(), tables_.size());
    if(bad == tables_.size()) return;
    const std::size_t e = std::upper_bound(table_offsets_.begin(), table_offsets_.end(), bad) -
                          table_offsets_.begin() - 1;
    const std::size_t kt = this->label_counts_[this->target(e)], r = bad - table_offsets_[e];
    throw Invalid_energy_error(internal::trws_message(
        "Discrete_energy: pairwise cost of edge ", e, " (", this->source(e), ", ", this->target(e),
        "), labels (", r / kt, ", ", r % kt, ") is ", tables_[bad], " (costs must be finite)"));
  }

  /// Bytes of memory held by the energy.
  std::size_t memory_bytes() const
  {
    return this->structure_bytes() + tables_.capacity() * sizeof(FT) +
           table_offsets_.capacity() * sizeof(std::size_t);
  }

private:
  template <typename, typename>
  friend class Trws_solver;

  std::vector<std::size_t> table_offsets_;
  std::vector<FT> tables_;
};

namespace internal {

template <typename Energy, typename LabelRange>
double trws_evaluate_energy(const Energy& energy, const LabelRange& labels)
{
  const std::size_t n = energy.number_of_nodes();
  if(static_cast<std::size_t>(boost::size(labels)) != n)
    throw Invalid_parameter_error(trws_message("Discrete_energy::energy(): ", boost::size(labels),
                                               " labels for ", n, " nodes"));
  auto first = boost::begin(labels);
  for(std::size_t i = 0; i < n; ++i)
    if(!trws_index_in_range(first[i], energy.number_of_labels(i)))
      throw Invalid_parameter_error(trws_message("label ", first[i], " of node ", i,
                                                 " is out of range [0, ",
                                                 energy.number_of_labels(i), ")"));
  double sum = 0;
  for(std::size_t i = 0; i < n; ++i) sum += double(energy.unary_cost(i, std::size_t(first[i])));
  for(std::size_t e = 0; e < energy.number_of_edges(); ++e)
    sum += double(energy.pairwise_cost(e, std::size_t(first[energy.source(e)]),
                                       std::size_t(first[energy.target(e)])));
  return sum;
}

// Does the functor provide fill_table(e, K_s, K_t, FT* table)?
template <typename C, typename FT, typename = void>
struct Trws_has_fill_table : std::false_type
{};
template <typename C, typename FT>
struct Trws_has_fill_table<C, FT,
                           std::void_t<decltype(std::declval<const C&>().fill_table(
                               std::size_t(), std::size_t(), std::size_t(), std::declval<FT*>()))> >
  : std::true_type
{};

// Visitors: an object with iteration(k, energy, bound), or a callable (k, energy, bound).
template <typename Visitor>
auto trws_call_visitor(Visitor& v, std::size_t k, double energy, double bound, int)
    -> decltype(bool(v.iteration(k, energy, bound)))
{
  return bool(v.iteration(k, energy, bound));
}
template <typename Visitor>
bool trws_call_visitor(Visitor& v, std::size_t k, double energy, double bound, long)
{
  return bool(v(k, energy, bound));
}

} // namespace internal

template <typename FT, typename PairwiseCost>
template <typename LabelRange>
double Discrete_energy<FT, PairwiseCost>::energy(const LabelRange& labels) const
{
  return internal::trws_evaluate_energy(*this, labels);
}

template <typename FT>
template <typename LabelRange>
double Discrete_energy<FT, Dense_pairwise_tables>::energy(const LabelRange& labels) const
{
  return internal::trws_evaluate_energy(*this, labels);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The sequential tree-reweighted message passing solver (TRW-S) of Kolmogorov (2006). It keeps
/// its workspace (messages, buffers) between calls, so solving many energies of similar size with
/// one solver allocates memory once.
///
/// Algorithm. Nodes are processed in the order of their indices \f$0, \dots, n-1\f$ (the
/// paper's ordering \f$i(\cdot)\f$; for a grid numbered row by row this is the raster order). Edges are covered by chains monotonic in that order; node s lies on
/// \f$n_s = \max(|\{t < s\}|, |\{t > s\}|)\f$ chains (t ranging over neighbours), so the paper's
/// weight of edge (s, t) relative to node s is \f$\gamma_{st} = 1 / n_s\f$. An iteration is a
/// forward pass (s = 0 .. n-1) and a backward pass (s = n-1 .. 0); each visit of node s computes
/// \f$\hat\theta_s = \theta_s + \sum_{t} M_{ts}\f$ and, for every neighbour t later in the pass,
/// \f[ M_{st}(l) = \min_k \big( \gamma_{st} \hat\theta_s(k) - M_{ts}(k) + \theta_{st}(k, l) \big)
///     - c_{st}, \f]
/// the normalisation constant \f$c_{st}\f$ being the value of the minimum for l = 0, so that
/// \f$M_{st}(0) = 0\f$ (any constant keeps the messages bounded and the bound below exact; this
/// one is known before the message is stored, which saves a pass over it). At the end of a
/// forward pass the lower bound of the chain decomposition is
/// \f[ \Phi = \sum_{(s,t)} c_{st} + \sum_s \frac{n_s - |\{t > s\}|}{n_s} \min_k \hat\theta_s(k) \f]
/// (the second sum counts the chains ending at s); TRW-S never decreases it.
/// A labeling is built during the forward pass as in the paper:
/// \f$x_s = \arg\min_k \theta_s(k) + \sum_{t < s} \theta_{ts}(x_t, k) + \sum_{t > s} M_{ts}(k)\f$,
/// and the best labeling seen is kept (never worse than the initial labeling, if given).
///
/// \tparam FT `float` or `double`: type of the messages (and of the energy's costs).
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default) or `CGAL::Parallel_tag` (requires TBB).
///   With `Parallel_tag`, energies with stored tables (`Discrete_energy<FT>`) of at least
///   `minimum_parallel_nodes` nodes are solved by all the threads of the current TBB arena, with
///   exactly the same result as sequentially (see below); other energies are solved sequentially.
///
/// **Parallel passes.** In a forward pass, node s reads only the messages of its earlier
/// neighbours (sent in this pass), the messages of its later neighbours (sent in the previous
/// backward pass, not changed by this one) and its own costs, and it writes only the messages to
/// its later neighbours. So two nodes can be processed at once when neither is an earlier neighbour
/// of the other: the nodes are grouped in levels (a node's level is one more than the highest level
/// of its earlier neighbours), and the threads take them level by level, each node waiting for its
/// earlier neighbours only. The backward pass is the mirror image. Every node computes exactly what
/// it computes in the sequential pass, and the bound and labeling energy are summed in the node
/// order afterwards, so the labeling, the energy and the bound are identical bit for bit (counted
/// on six 5000-vertex TOSCA_r meshes numbered breadth-first: 150-180 levels of about 30 nodes).
template <typename FT = double, typename ConcurrencyTag = CGAL::Sequential_tag>
class Trws_solver
{
public:
  /// Energies with fewer nodes are solved sequentially even with `Parallel_tag` (the threads'
  /// start and synchronisation would cost more than they save).
  static constexpr std::size_t minimum_parallel_nodes = 1000;

  /// Minimises `energy` and writes the best labeling found into `labeling` (resized to the number
  /// of nodes).
  ///
  /// \tparam PairwiseCost `Dense_pairwise_tables` or a pairwise cost functor.
  /// \tparam Integer an integer type.
  /// \tparam NamedParameters a sequence of named parameters.
  ///
  /// \param energy the energy.
  /// \param labeling output: `labeling[i]` is the label of node i.
  /// \param np optional named parameters among:
  /// - `number_of_iterations` (CGAL's): maximum number of iterations; type `std::size_t`
  ///   (or any integer); default 100; must be at least 1.
  /// - `relative_tolerance`: stop when the lower bound changes by at most
  ///   `relative_tolerance` \f$\cdot \max(|\Phi_k|, |\Phi_{k-1}|)\f$ in one iteration, or when the
  ///   best energy is within `relative_tolerance` \f$\cdot \max(|E|, |\Phi|)\f$ of the bound; type
  ///   `double`; default 1e-5; must be \f$\geq 0\f$.
  /// - `initial_labeling`: a labeling to start from (kept unless a better one is found); a
  ///   random-access range of integers indexed by node; default: none.
  /// - `visitor` (CGAL's): called after every iteration k (1-based) as
  ///   `visitor.iteration(k, energy, lower_bound)` if it has such a member function, else
  ///   `visitor(k, energy, lower_bound)`; `energy` is the best energy so far and `lower_bound` the
  ///   bound of that iteration; returns `bool`, `false` stops the run. Pass `std::ref(v)` to
  ///   keep the visitor's state. Default: `Trws_default_visitor`.
  ///
  /// \returns energy, lower bound, iterations run, the termination reason and the threads used.
  /// \throws Invalid_energy_error for a NaN or infinite cost (naming the node or edge).
  /// \throws Invalid_parameter_error for a bad parameter or initial labeling.
  /// \throws Numerical_error if the messages overflow (costs too large for FT).
  template <typename PairwiseCost, typename Integer,
            typename NamedParameters = parameters::Default_named_parameters>
  Trws_result solve(const Discrete_energy<FT, PairwiseCost>& energy, std::vector<Integer>& labeling,
                    const NamedParameters& np = parameters::default_values());

  /// Bytes of memory held by the solver's workspace.
  std::size_t memory_bytes() const
  {
    std::size_t scratch = 0;
    for(const Scratch& w : scratch_)
      scratch += (w.theta.capacity() + w.costs.capacity() + w.shifted.capacity() + w.table.capacity()) * sizeof(FT);
    return (messages_.capacity() + conditional_.capacity()) * sizeof(FT) +
           links_.capacity() * sizeof(Link) + (node_data_.capacity()) * sizeof(Node_data) +
           (labels_.capacity() + best_labels_.capacity()) * sizeof(std::uint32_t) +
           (node_energy_.capacity() + node_bound_.capacity() + link_bound_.capacity()) * sizeof(double) +
           (forward_order_.capacity() + backward_order_.capacity()) * sizeof(std::uint32_t) +
           done_.capacity() * sizeof(std::atomic<std::uint32_t>) + scratch;
  }

private:
  // One incident edge of a node, seen from that node (s): offsets of the messages into s and
  // into the neighbour t along the edge, and where the table is.
  struct Link
  {
    std::size_t message_in;  // M_ts (K_s values)
    std::size_t message_out; // M_st (K_t values)
    std::size_t table;       // offset of the edge's table (tables only)
    std::uint32_t edge;
    std::uint32_t neighbor;
    std::uint32_t neighbor_labels;
    bool source; // s is the source of the edge (rows of the table)
  };
  struct Node_data
  {
    std::size_t links_begin, links_split, links_end; // incidences; earlier neighbours first
    FT gamma;                                        // 1 / n_s
    double bound_weight;                             // (n_s - #later neighbours) / n_s
  };
  // Per-thread work arrays of one node's update (K values each; `table` for functor costs).
  struct Scratch
  {
    std::vector<FT> theta, costs, shifted, table;
  };

  template <typename PairwiseCost>
  void prepare(const Discrete_energy<FT, PairwiseCost>& energy);

  // The threads that run the passes of `energy` (1: sequential passes; see the class comment).
  template <typename PairwiseCost>
  static std::size_t number_of_threads(const Discrete_energy<FT, PairwiseCost>& energy);
  // Whether the passes of the prepared energy run on several threads (one scratch per thread).
  bool parallel() const { return scratch_.size() > 1; }

  // The levels of the parallel passes: forward_order_ and backward_order_ list the nodes level by
  // level.
  void prepare_levels(std::size_t n);

  // The table of link L of node s, as stored or as computed into w.table.
  template <typename PairwiseCost>
  const FT* edge_table(const Discrete_energy<FT, PairwiseCost>& energy, const Link& L,
                       std::size_t ks, bool check, Scratch& w);

  // Forward pass: messages to later neighbours, labeling, bound. Returns the bound; the energy of
  // the labeling goes to `labeling_energy`.
  template <typename PairwiseCost>
  double forward_pass(const Discrete_energy<FT, PairwiseCost>& energy, bool check,
                      double& labeling_energy);
  template <typename PairwiseCost>
  void backward_pass(const Discrete_energy<FT, PairwiseCost>& energy);

  // The forward update of node s: its label, its share of the labeling energy (node_energy_[s])
  // and of the bound (node_bound_[s], and link_bound_ for the messages it sends).
  template <typename PairwiseCost>
  void forward_node(const Discrete_energy<FT, PairwiseCost>& energy, std::size_t s, bool check, Scratch& w);
  // The backward update of node s: its messages to its earlier neighbours.
  template <typename PairwiseCost>
  void backward_node(const Discrete_energy<FT, PairwiseCost>& energy, std::size_t s, Scratch& w);

  // Calls update(s, scratch) for every node of `order` on the threads of the arena, each node after
  // its earlier (forward) or later (backward) neighbours.
  template <typename Update, typename Prefetch>
  void parallel_pass(const std::vector<std::uint32_t>& order, bool forward, const Update& update,
                     const Prefetch& prefetch);

  // Asks the memory system for the tables that node s reads in the pass: the tables are read in
  // the order of the nodes, not of their storage, so the hardware prefetchers cannot guess the
  // next one. Measured (bench_trws, float tables, edges numbered by their smaller end): 4.8 ->
  // 3.6 ms per iteration on the 5k-vertex MRF with 20 labels, 34 -> 19 ms on the 256 x 256 grid.
  // Forced inline: GCC sees no side effect in a function that only prefetches and drops the call.
  template <typename PairwiseCost>
  CGAL_SMC_TRWS_INLINE void prefetch_tables(const Discrete_energy<FT, PairwiseCost>& energy,
                                            std::size_t s, bool forward) const;

  // Sends the message from node s along link L; returns the normalisation constant c_st.
  FT send(const FT* theta, FT gamma, std::size_t ks, const Link& L, const FT* table, Scratch& w);

  std::vector<FT> messages_;    // per edge: M_ts (K_s values) then M_st (K_t values)
  std::vector<FT> conditional_; // same layout: theta_st(x_s, .) left by the earlier end s
  std::vector<Link> links_;
  std::vector<Node_data> node_data_;
  std::vector<std::uint32_t> labels_, best_labels_;
  std::vector<double> node_energy_, node_bound_, link_bound_;
  std::vector<Scratch> scratch_; // one per thread (one sequentially)
  // Parallel passes: the nodes level by level, and the pass in which each node was last updated.
  std::vector<std::uint32_t> forward_order_, backward_order_;
  std::vector<std::atomic<std::uint32_t> > done_;
  std::uint32_t pass_ = 0;
};

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
std::size_t Trws_solver<FT, ConcurrencyTag>::number_of_threads(const Discrete_energy<FT, PairwiseCost>& energy)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(internal::Is_parallel<ConcurrencyTag>::value && Discrete_energy<FT, PairwiseCost>::has_tables &&
     energy.number_of_nodes() >= minimum_parallel_nodes)
    return static_cast<std::size_t>((std::max)(1, tbb::this_task_arena::max_concurrency()));
#else
  (void)energy;
  (void)internal::Is_parallel<ConcurrencyTag>::value;
#endif
  return 1;
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
void Trws_solver<FT, ConcurrencyTag>::prepare(const Discrete_energy<FT, PairwiseCost>& energy)
{
  const internal::Discrete_energy_base<FT>& base = energy;
  const std::size_t n = base.number_of_nodes(), m = base.number_of_edges();
  // Messages of edge e: M_ts (into the source, K_s values) then M_st (into the target).
  std::vector<std::size_t> message_offsets(m + 1, 0);
  for(std::size_t e = 0; e < m; ++e)
    message_offsets[e + 1] = message_offsets[e] + base.label_counts_[base.source(e)] +
                             base.label_counts_[base.target(e)];
  messages_.assign(message_offsets[m], FT(0));
  conditional_.resize(message_offsets[m]);
  links_.resize(2 * m);
  node_data_.resize(n);
  for(std::size_t s = 0; s < n; ++s)
  {
    Node_data& d = node_data_[s];
    d.links_begin = base.adjacency_offsets_[s];
    d.links_end = base.adjacency_offsets_[s + 1];
    d.links_split = d.links_begin;
    for(std::size_t i = d.links_begin; i < d.links_end; ++i)
    {
      const internal::Trws_incidence& inc = base.incidences_[i];
      Link& L = links_[i];
      L.edge = inc.edge;
      L.neighbor = inc.neighbor;
      L.neighbor_labels = base.label_counts_[inc.neighbor];
      L.source = (base.source(inc.edge) == s);
      const std::size_t into_source = message_offsets[inc.edge];
      const std::size_t into_target = into_source + base.label_counts_[base.source(inc.edge)];
      L.message_in = L.source ? into_source : into_target;
      L.message_out = L.source ? into_target : into_source;
      if constexpr(Discrete_energy<FT, PairwiseCost>::has_tables)
        L.table = energy.table_offsets_[inc.edge];
      else
        L.table = 0;
      if(inc.neighbor < s) d.links_split = i + 1;
    }
    const std::size_t earlier = d.links_split - d.links_begin, later = d.links_end - d.links_split;
    const std::size_t chains = (std::max)(std::size_t(1), (std::max)(earlier, later));
    d.gamma = FT(1) / FT(chains);
    d.bound_weight = double(chains - later) / double(chains);
  }
  node_energy_.assign(n, 0.0);
  node_bound_.assign(n, 0.0);
  link_bound_.assign(2 * m, 0.0);
  const std::size_t k = base.maximum_number_of_labels();
  scratch_.resize(number_of_threads(energy));
  if(parallel()) prepare_levels(n);
  for(Scratch& w : scratch_)
  {
    w.theta.resize(k);
    w.costs.resize(k);
    w.shifted.resize(k);
    if constexpr(!Discrete_energy<FT, PairwiseCost>::has_tables) w.table.resize(k * k);
  }
  labels_.assign(n, 0);
}

template <typename FT, typename ConcurrencyTag>
void Trws_solver<FT, ConcurrencyTag>::prepare_levels(std::size_t n)
{
  // Level of a node: 0 without earlier (forward) or later (backward) neighbours, else one more
  // than the highest level among them; then a counting sort by level.
  auto order_by_levels = [&](bool forward, std::vector<std::uint32_t>& order) {
    std::vector<std::uint32_t> level(n, 0);
    std::uint32_t levels = 0;
    for(std::size_t r = 0; r < n; ++r)
    {
      const std::size_t s = forward ? r : n - 1 - r;
      const Node_data& d = node_data_[s];
      const std::size_t first = forward ? d.links_begin : d.links_split;
      const std::size_t last = forward ? d.links_split : d.links_end;
      std::uint32_t l = 0;
      for(std::size_t i = first; i < last; ++i) l = (std::max)(l, level[links_[i].neighbor] + 1);
      level[s] = l;
      levels = (std::max)(levels, l + 1);
    }
    std::vector<std::size_t> start(std::size_t(levels) + 1, 0);
    for(std::size_t s = 0; s < n; ++s) ++start[level[s] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    order.resize(n);
    for(std::size_t r = 0; r < n; ++r)
    {
      const std::size_t s = forward ? r : n - 1 - r;
      order[start[level[s]]++] = static_cast<std::uint32_t>(s);
    }
  };
  order_by_levels(true, forward_order_);
  order_by_levels(false, backward_order_);
  if(done_.size() != n)
    done_ = std::vector<std::atomic<std::uint32_t> >(n);  // value-initialised: 0
  else
    for(std::atomic<std::uint32_t>& flag : done_) flag.store(0, std::memory_order_relaxed);
  pass_ = 0;
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
const FT* Trws_solver<FT, ConcurrencyTag>::edge_table(const Discrete_energy<FT, PairwiseCost>& energy,
                                                      const Link& L, std::size_t ks, bool check, Scratch& w)
{
  if constexpr(Discrete_energy<FT, PairwiseCost>::has_tables)
  {
    (void)ks;
    (void)check;
    (void)w;
    return energy.tables_.data() + L.table;
  }
  else
  {
    const std::size_t rows = L.source ? ks : L.neighbor_labels;
    const std::size_t cols = L.source ? L.neighbor_labels : ks;
    const PairwiseCost& cost = energy.pairwise_cost_functor();
    FT* table = w.table.data();
    if constexpr(internal::Trws_has_fill_table<PairwiseCost, FT>::value)
      cost.fill_table(L.edge, rows, cols, table);
    else
    {
      FT* out = table;
      for(std::size_t k = 0; k < rows; ++k)
        for(std::size_t l = 0; l < cols; ++l) *out++ = FT(cost(std::size_t(L.edge), k, l));
    }
    if(check)
    {
      const std::size_t bad = internal::trws_first_non_finite(table, rows * cols);
      if(bad < rows * cols)
        throw Invalid_energy_error(internal::trws_message(
            "Discrete_energy: pairwise cost of edge ", L.edge, " (", energy.source(L.edge), ", ",
            energy.target(L.edge), "), labels (", bad / cols, ", ", bad % cols, ") is ",
            table[bad], " (costs must be finite)"));
    }
    return table;
  }
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
void Trws_solver<FT, ConcurrencyTag>::prefetch_tables(const Discrete_energy<FT, PairwiseCost>& energy,
                                                      std::size_t s, bool forward) const
{
#if defined(__GNUC__) && !defined(CGAL_SMC_TRWS_NO_PREFETCH)
  if constexpr(Discrete_energy<FT, PairwiseCost>::has_tables)
  {
    const Node_data& d = node_data_[s];
    const std::size_t first = forward ? d.links_split : d.links_begin;
    const std::size_t last = forward ? d.links_end : d.links_split;
    const std::size_t ks = energy.number_of_labels(s);
    for(std::size_t i = first; i < last; ++i)
    {
      const FT* table = energy.tables_.data() + links_[i].table;
      const std::size_t size = ks * links_[i].neighbor_labels;
      for(std::size_t j = 0; j < size; j += 64 / sizeof(FT)) __builtin_prefetch(table + j);
    }
    return;
  }
#endif
  (void)energy;
  (void)s;
  (void)forward;
}

template <typename FT, typename ConcurrencyTag>
FT Trws_solver<FT, ConcurrencyTag>::send(const FT* theta, FT gamma, std::size_t ks, const Link& L,
                                         const FT* table, Scratch& w)
{
  const FT* CGAL_SMC_TRWS_RESTRICT in = messages_.data() + L.message_in;
  FT* CGAL_SMC_TRWS_RESTRICT shifted = w.shifted.data();
  for(std::size_t k = 0; k < ks; ++k) shifted[k] = gamma * theta[k] - in[k];
  FT* out = messages_.data() + L.message_out;
  // The kernels normalise the message by its first entry and return that constant.
  return L.source ? internal::trws_min_plus_to_target(shifted, table, ks, L.neighbor_labels, out)
                  : internal::trws_min_plus_to_source(shifted, table, L.neighbor_labels, ks, out);
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
void Trws_solver<FT, ConcurrencyTag>::forward_node(const Discrete_energy<FT, PairwiseCost>& energy,
                                                   std::size_t s, bool check, Scratch& w)
{
  FT* theta = w.theta.data();
  FT* costs = w.costs.data();
  const Node_data& d = node_data_[s];
  const std::size_t ks = energy.number_of_labels(s);
  const FT* unary = energy.unary_costs(s);
  // theta = theta_s + all incoming messages; costs = theta_s + messages from later neighbours
  // + pairwise costs to the labels already chosen for earlier neighbours, theta_ts(x_t, .),
  // which node t left in conditional_ when it chose x_t.
  for(std::size_t k = 0; k < ks; ++k) theta[k] = costs[k] = unary[k];
  for(std::size_t i = d.links_begin; i < d.links_split; ++i)
  {
    const FT* in = messages_.data() + links_[i].message_in;
    const FT* conditional = conditional_.data() + links_[i].message_in;
    for(std::size_t k = 0; k < ks; ++k)
    {
      theta[k] += in[k];
      costs[k] += conditional[k];
    }
  }
  for(std::size_t i = d.links_split; i < d.links_end; ++i)
  {
    const FT* in = messages_.data() + links_[i].message_in;
    for(std::size_t k = 0; k < ks; ++k)
    {
      theta[k] += in[k];
      costs[k] += in[k];
    }
  }
  std::size_t best = 0;
  FT theta_min = theta[0];
  for(std::size_t k = 1; k < ks; ++k)
  {
    if(costs[k] < costs[best]) best = k;
    theta_min = theta[k] < theta_min ? theta[k] : theta_min;
  }
  labels_[s] = static_cast<std::uint32_t>(best);
  // Exact energy of the labeling, each edge counted at its later end.
  double e_s = double(unary[best]);
  for(std::size_t i = d.links_begin; i < d.links_split; ++i)
    e_s += double(conditional_[links_[i].message_in + best]);
  node_energy_[s] = e_s;
  node_bound_[s] = d.bound_weight * double(theta_min);
  for(std::size_t i = d.links_split; i < d.links_end; ++i)
  {
    const Link& L = links_[i];
    const FT* table = edge_table(energy, L, ks, check, w);
    link_bound_[i] = double(send(theta, d.gamma, ks, L, table, w));
    // theta_st(x_s, .) for the neighbour, read while the table is in cache.
    FT* conditional = conditional_.data() + L.message_out;
    const std::size_t kt = L.neighbor_labels;
    if(L.source) // s indexes the rows: row x_s
      std::copy(table + best * kt, table + best * kt + kt, conditional);
    else // s indexes the columns: column x_s
      for(std::size_t l = 0; l < kt; ++l) conditional[l] = table[l * ks + best];
  }
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
void Trws_solver<FT, ConcurrencyTag>::backward_node(const Discrete_energy<FT, PairwiseCost>& energy,
                                                    std::size_t s, Scratch& w)
{
  const Node_data& d = node_data_[s];
  if(d.links_split == d.links_begin) return; // no earlier neighbour to send to
  FT* theta = w.theta.data();
  const std::size_t ks = energy.number_of_labels(s);
  const FT* unary = energy.unary_costs(s);
  for(std::size_t k = 0; k < ks; ++k) theta[k] = unary[k];
  for(std::size_t i = d.links_begin; i < d.links_end; ++i)
  {
    const FT* in = messages_.data() + links_[i].message_in;
    for(std::size_t k = 0; k < ks; ++k) theta[k] += in[k];
  }
  for(std::size_t i = d.links_begin; i < d.links_split; ++i)
  {
    const Link& L = links_[i];
    send(theta, d.gamma, ks, L, edge_table(energy, L, ks, false, w), w);
  }
}

template <typename FT, typename ConcurrencyTag>
template <typename Update, typename Prefetch>
void Trws_solver<FT, ConcurrencyTag>::parallel_pass(const std::vector<std::uint32_t>& order, bool forward,
                                                    const Update& update, const Prefetch& prefetch)
{
#ifdef CGAL_LINKED_WITH_TBB
  const std::uint32_t pass = ++pass_;
  const std::size_t n = order.size();
  std::atomic<std::size_t> next(0);
  const std::size_t chunk = 4;  // nodes taken at once (fewer atomic operations; neighbours often together)
  // Each worker takes the next chunk of nodes in level order and waits, before each node, for
  // the neighbours it depends on. They come earlier in the order: in a chunk that this worker took
  // (done) or that a running worker is processing, so the wait ends even when TBB runs several
  // workers one after the other on the same thread.
  tbb::parallel_for(std::size_t(0), scratch_.size(), [&](std::size_t worker) {
    Scratch& w = scratch_[worker];
    for(std::size_t begin = next.fetch_add(chunk, std::memory_order_relaxed); begin < n;
        begin = next.fetch_add(chunk, std::memory_order_relaxed))
      for(std::size_t p = begin, end = (std::min)(n, begin + chunk); p < end; ++p)
      {
        const std::size_t s = order[p];
        if(p + 1 < n) prefetch(order[p + 1]);
        const Node_data& d = node_data_[s];
        const std::size_t first = forward ? d.links_begin : d.links_split;
        const std::size_t last = forward ? d.links_split : d.links_end;
        for(std::size_t i = first; i < last; ++i)
        {
          const std::atomic<std::uint32_t>& flag = done_[links_[i].neighbor];
          for(unsigned spins = 0; flag.load(std::memory_order_acquire) != pass; ++spins)
            if(spins >= 4096) std::this_thread::yield();
        }
        update(s, w);
        done_[s].store(pass, std::memory_order_release);
      }
  });
#else
  (void)order;
  (void)forward;
  (void)update;
  (void)prefetch;
#endif
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
double Trws_solver<FT, ConcurrencyTag>::forward_pass(const Discrete_energy<FT, PairwiseCost>& energy, bool check,
                                                     double& labeling_energy)
{
  const std::size_t n = energy.number_of_nodes();
  if(parallel())
    parallel_pass(
        forward_order_, true, [&](std::size_t s, Scratch& w) { forward_node(energy, s, check, w); },
        [&](std::size_t s) { prefetch_tables(energy, s, true); });
  else
    for(std::size_t s = 0; s < n; ++s)
    {
      if(s + 1 < n) prefetch_tables(energy, s + 1, true);
      forward_node(energy, s, check, scratch_[0]);
    }
  // Summed in the node order, as the sequential pass would (the same result with any schedule).
  double bound = 0, labeling = 0;
  for(std::size_t s = 0; s < n; ++s)
  {
    const Node_data& d = node_data_[s];
    labeling += node_energy_[s];
    if(d.bound_weight > 0) bound += node_bound_[s];
    for(std::size_t i = d.links_split; i < d.links_end; ++i) bound += link_bound_[i];
  }
  labeling_energy = labeling;
  return bound;
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost>
void Trws_solver<FT, ConcurrencyTag>::backward_pass(const Discrete_energy<FT, PairwiseCost>& energy)
{
  if(parallel())
  {
    parallel_pass(
        backward_order_, false, [&](std::size_t s, Scratch& w) { backward_node(energy, s, w); },
        [&](std::size_t s) { prefetch_tables(energy, s, false); });
    return;
  }
  for(std::size_t s = energy.number_of_nodes(); s-- > 0;)
  {
    if(s > 0) prefetch_tables(energy, s - 1, false);
    backward_node(energy, s, scratch_[0]);
  }
}

template <typename FT, typename ConcurrencyTag>
template <typename PairwiseCost, typename Integer, typename NamedParameters>
Trws_result Trws_solver<FT, ConcurrencyTag>::solve(const Discrete_energy<FT, PairwiseCost>& energy,
                                   std::vector<Integer>& labeling, const NamedParameters& np)
{
  static_assert(std::is_integral<Integer>::value, "labels must be integers");
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::get_parameter_reference;

  const auto max_iterations_param =
      choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 100);
  if(!(max_iterations_param >= 1))
    throw Invalid_parameter_error(internal::trws_message(
        "TRW-S: number_of_iterations must be at least 1 (got ", max_iterations_param, ")"));
  const std::size_t max_iterations = static_cast<std::size_t>(max_iterations_param);
  const double tolerance =
      choose_parameter(get_parameter(np, internal_np::relative_tolerance), 1e-5);
  if(!(tolerance >= 0))
    throw Invalid_parameter_error(internal::trws_message(
        "TRW-S: relative_tolerance must be non-negative (got ", tolerance, ")"));

  typedef typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::visitor_t, NamedParameters, Trws_default_visitor>::reference Visitor;
  Trws_default_visitor default_visitor;
  Visitor visitor =
      choose_parameter(get_parameter_reference(np, CGAL::internal_np::visitor), default_visitor);

  const std::size_t n = energy.number_of_nodes();
  Trws_result result;
  energy.check_costs();
  prepare(energy);
  result.number_of_threads = scratch_.size();

  double best_energy = std::numeric_limits<double>::infinity();
  best_labels_.assign(n, 0);
  if constexpr(!parameters::is_default_parameter<NamedParameters,
                                                 internal_np::initial_labeling_t>::value)
  {
    const auto& initial = get_parameter_reference(np, internal_np::initial_labeling);
    if(static_cast<std::size_t>(boost::size(initial)) != n)
      throw Invalid_parameter_error(internal::trws_message(
          "TRW-S: the initial labeling has ", boost::size(initial), " labels for ", n, " nodes"));
    auto first = boost::begin(initial);
    for(std::size_t i = 0; i < n; ++i)
    {
      if(!internal::trws_index_in_range(first[i], energy.number_of_labels(i)))
        throw Invalid_parameter_error(
            internal::trws_message("TRW-S: initial label ", first[i], " of node ", i,
                                   " is out of range [0, ", energy.number_of_labels(i), ")"));
      best_labels_[i] = static_cast<std::uint32_t>(first[i]);
    }
    best_energy = energy.energy(best_labels_);
  }

  if(n == 0)
  {
    result.energy = 0;
    result.lower_bound = 0;
    result.termination = Trws_termination::optimal;
    labeling.clear();
    return result;
  }

  double previous_bound = -std::numeric_limits<double>::infinity();
  for(std::size_t iteration = 1;; ++iteration)
  {
    double labeling_energy = 0;
    const double bound = forward_pass(energy, iteration == 1, labeling_energy);
    if(!std::isfinite(bound))
      throw Numerical_error(internal::trws_message(
          "TRW-S: the lower bound is ", bound, " at iteration ", iteration,
          " (costs too large for the floating-point type of the messages?)"));
    if(labeling_energy < best_energy)
    {
      best_energy = labeling_energy;
      best_labels_ = labels_;
    }
    result.lower_bound = (std::max)(result.lower_bound, bound);
    result.number_of_iterations = iteration;
    const bool go_on = internal::trws_call_visitor(visitor, iteration, best_energy, bound, 0);
    const double scale = (std::max)(std::abs(best_energy), std::abs(result.lower_bound));
    if(!go_on)
    {
      result.termination = Trws_termination::visitor_stop;
      break;
    }
    if(best_energy - result.lower_bound <= tolerance * scale)
    {
      result.termination = Trws_termination::optimal;
      break;
    }
    if(iteration > 1 && std::abs(bound - previous_bound) <=
                            tolerance * (std::max)(std::abs(bound), std::abs(previous_bound)))
    {
      result.termination = Trws_termination::converged;
      break;
    }
    if(iteration >= max_iterations)
    {
      result.termination = Trws_termination::iteration_limit;
      break;
    }
    previous_bound = bound;
    backward_pass(energy);
  }

  labeling.resize(n);
  for(std::size_t i = 0; i < n; ++i) labeling[i] = static_cast<Integer>(best_labels_[i]);
  result.energy = energy.energy(best_labels_);
  return result;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Minimises a `Discrete_energy` with TRW-S: `Trws_solver<FT, ConcurrencyTag>().solve(energy,
/// labeling, np)` (see `Trws_solver::solve()` for the named parameters and exceptions).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default) or `CGAL::Parallel_tag` (requires TBB):
///   parallel passes on energies with stored tables of at least
///   `Trws_solver::minimum_parallel_nodes` nodes, with the sequential result bit for bit (see
///   `Trws_solver`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename FT, typename PairwiseCost, typename Integer,
          typename NamedParameters = parameters::Default_named_parameters>
Trws_result trws_minimize(const Discrete_energy<FT, PairwiseCost>& energy,
                          std::vector<Integer>& labeling,
                          const NamedParameters& np = parameters::default_values())
{
  Trws_solver<FT, ConcurrencyTag> solver;
  return solver.solve(energy, labeling, np);
}

namespace internal {

// A pairwise cost map whose values are functors (k, l) -> cost rather than tables.
template <typename T>
struct Trws_is_cost_functor
  : std::integral_constant<bool, std::is_invocable<const T&, std::size_t, std::size_t>::value>
{};

// The pairwise costs of trws_labeling() on the functor path: the flat edge e stands for the
// graph edges members[offsets[e] .. offsets[e+1]) (several when parallel edges are merged), each
// evaluated through the user's map, transposed when the graph edge runs the other way.
template <typename FT, typename EdgeDescriptor, typename PairwiseCostMap>
class Trws_graph_pairwise_cost
{
public:
  Trws_graph_pairwise_cost() {}
  Trws_graph_pairwise_cost(PairwiseCostMap map, const std::vector<EdgeDescriptor>* members,
                           const std::vector<std::size_t>* offsets,
                           const std::vector<unsigned char>* flipped)
    : map_(map), members_(members), offsets_(offsets), flipped_(flipped)
  {}

  FT operator()(std::size_t e, std::size_t k, std::size_t l) const
  {
    double sum = 0;
    for(std::size_t i = (*offsets_)[e]; i < (*offsets_)[e + 1]; ++i)
    {
      auto&& f = get(map_, (*members_)[i]);
      sum += (*flipped_)[i] ? double(f(l, k)) : double(f(k, l));
    }
    return FT(sum);
  }

  void fill_table(std::size_t e, std::size_t ks, std::size_t kt, FT* table) const
  {
    for(std::size_t i = (*offsets_)[e]; i < (*offsets_)[e + 1]; ++i)
    {
      auto&& f = get(map_, (*members_)[i]);
      const bool first = (i == (*offsets_)[e]), flipped = (*flipped_)[i] != 0;
      for(std::size_t k = 0; k < ks; ++k)
        for(std::size_t l = 0; l < kt; ++l)
        {
          const FT c = FT(flipped ? f(l, k) : f(k, l));
          table[k * kt + l] = first ? c : table[k * kt + l] + c;
        }
    }
  }

private:
  PairwiseCostMap map_;
  const std::vector<EdgeDescriptor>* members_ = nullptr;
  const std::vector<std::size_t>* offsets_ = nullptr;
  const std::vector<unsigned char>* flipped_ = nullptr;
};

// Graphs whose vertices(g) is a range (CGAL's graphs) get CGAL's initialised vertex index map;
// others (Boost's, whose vertices(g) is a std::pair of iterators) their own vertex_index map.
template <typename Graph, typename = void>
struct Trws_vertices_are_range : std::false_type
{};
template <typename Graph>
struct Trws_vertices_are_range<
    Graph, std::void_t<decltype(vertices(std::declval<const Graph&>()).begin())> > : std::true_type
{};

template <typename Graph, typename NamedParameters>
auto trws_vertex_index_map(const Graph& g, const NamedParameters& np)
{
  if constexpr(!parameters::is_default_parameter<NamedParameters,
                                                 CGAL::internal_np::vertex_index_t>::value)
    return parameters::get_parameter(np, CGAL::internal_np::vertex_index);
  else if constexpr(Trws_vertices_are_range<Graph>::value)
    return CGAL::get_initialized_vertex_index_map(g);
  else
    return get(boost::vertex_index, g);
}


/// The nodes of trws_labeling(): the vertices in the order of the vertex index map and their
/// numbers of labels.
template <typename VertexDescriptor>
struct Trws_graph_nodes
{
  std::vector<VertexDescriptor> vertex_of;
  std::vector<std::size_t> label_count;
};

/// Numbers the vertices of `g` by the vertex index map, which must be a bijection onto [0, n),
/// and reads their numbers of labels (at least 1).
template <typename Graph, typename VertexIndexMap, typename LabelCountMap>
Trws_graph_nodes<typename boost::graph_traits<Graph>::vertex_descriptor>
trws_graph_nodes(const Graph& g, const VertexIndexMap& vertex_index, LabelCountMap& label_counts)
{
  typedef typename boost::graph_traits<Graph>::vertex_descriptor vertex_descriptor;
  const std::size_t n = static_cast<std::size_t>(num_vertices(g));
  Trws_graph_nodes<vertex_descriptor> nodes;
  nodes.vertex_of.resize(n);
  nodes.label_count.resize(n);
  std::vector<unsigned char> seen(n, 0);
  std::size_t visited = 0;
  for(vertex_descriptor v : make_range(vertices(g)))
  {
    const auto i = get(vertex_index, v);
    if(!trws_index_in_range(i, n) || seen[std::size_t(i)])
      throw Invalid_parameter_error(
          trws_message("trws_labeling: the vertex index map is not a bijection onto [0, ", n,
                       ") (index ", i, "); pass an initialised vertex_index_map"));
    seen[std::size_t(i)] = 1;
    nodes.vertex_of[std::size_t(i)] = v;
    const auto k = get(label_counts, v);
    if(!(k >= 1))
      throw Invalid_energy_error(trws_message("trws_labeling: vertex ", i, " has no label"));
    nodes.label_count[std::size_t(i)] = static_cast<std::size_t>(k);
    ++visited;
  }
  if(visited != n)
    throw Invalid_parameter_error(trws_message("trws_labeling: vertices(g) has ", visited,
                                               " vertices but num_vertices(g) is ", n));
  return nodes;
}

/// The edges of trws_labeling(): parallel graph edges are merged into one flat edge, whose
/// members are the graph edges of its group.
template <typename EdgeDescriptor>
struct Trws_graph_edges
{
  /// The node indices of each graph edge, in the order of edges(g).
  std::vector<std::pair<std::size_t, std::size_t> > ends;
  /// The merged edges, numbered by (smaller, larger) node index; each keeps the orientation of its
  /// first graph edge.
  std::vector<std::pair<std::size_t, std::size_t> > flat_edges;
  /// Flat edge f stands for members[member_offsets[f] .. member_offsets[f + 1]).
  std::vector<std::size_t> member_offsets;
  std::vector<EdgeDescriptor> members;
  std::vector<unsigned char> flipped;     ///< the member runs against its flat edge
  std::vector<std::size_t> member_edge;   ///< the member's index in `ends`
};

/// Reads the edges of `g` (no self-loops) and merges the parallel ones; the first one of a group
/// (in the order of edges(g)) gives the orientation of the merged edge.
template <typename Graph, typename VertexIndexMap>
Trws_graph_edges<typename boost::graph_traits<Graph>::edge_descriptor>
trws_graph_edges(const Graph& g, const VertexIndexMap& vertex_index)
{
  typedef typename boost::graph_traits<Graph>::edge_descriptor edge_descriptor;
  Trws_graph_edges<edge_descriptor> r;
  std::vector<edge_descriptor> graph_edges;
  std::vector<std::pair<std::size_t, std::size_t> >& ends = r.ends;
  for(edge_descriptor e : make_range(edges(g)))
  {
    const std::size_t s = std::size_t(get(vertex_index, source(e, g)));
    const std::size_t t = std::size_t(get(vertex_index, target(e, g)));
    if(s == t) throw Invalid_energy_error(trws_message("trws_labeling: self-loop at vertex ", s));
    graph_edges.push_back(e);
    ends.emplace_back(s, t);
  }
  const std::size_t m = ends.size();
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto key = [&](std::size_t i) {
    return std::make_pair((std::min)(ends[i].first, ends[i].second),
                          (std::max)(ends[i].first, ends[i].second));
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return key(a) < key(b) || (key(a) == key(b) && a < b);
  });
  // Merged edges are numbered by (smaller, larger) vertex index, so that the forward pass reads
  // their tables in storage order; each keeps the orientation of its first graph edge.
  std::vector<std::size_t> representative(m); // first edge of each graph edge's group
  std::vector<std::size_t> group(m, std::size_t(-1));
  for(std::size_t j = 0; j < m; ++j)
  {
    const std::size_t i = order[j];
    if(j > 0 && key(order[j - 1]) == key(i))
      representative[i] = representative[order[j - 1]];
    else
    {
      representative[i] = i;
      group[i] = r.flat_edges.size();
      r.flat_edges.push_back(ends[i]);
    }
  }
  const std::size_t flat_m = r.flat_edges.size();
  r.member_offsets.assign(flat_m + 1, 0);
  for(std::size_t i = 0; i < m; ++i) ++r.member_offsets[group[representative[i]] + 1];
  for(std::size_t f = 0; f < flat_m; ++f) r.member_offsets[f + 1] += r.member_offsets[f];
  r.members.resize(m);
  r.flipped.resize(m);
  r.member_edge.resize(m);
  std::vector<std::size_t> fill(r.member_offsets.begin(), r.member_offsets.end() - 1);
  for(std::size_t i = 0; i < m; ++i)
  {
    const std::size_t f = group[representative[i]], slot = fill[f]++;
    r.members[slot] = graph_edges[i];
    r.member_edge[slot] = i;
    r.flipped[slot] = (ends[i].first != r.flat_edges[f].first) ? 1 : 0;
  }
  return r;
}

/// Copies the unary costs of the nodes into `energy`, checking their sizes and values.
template <typename FT, typename Energy, typename UnaryCostMap, typename VertexDescriptor>
void trws_fill_unary_costs(Energy& energy, UnaryCostMap& unary_costs, const Trws_graph_nodes<VertexDescriptor>& nodes)
{
  for(std::size_t i = 0; i < nodes.vertex_of.size(); ++i)
  {
    auto&& costs = get(unary_costs, nodes.vertex_of[i]);
    const std::size_t size = static_cast<std::size_t>(boost::size(costs));
    if(size != nodes.label_count[i])
      throw Invalid_energy_error(trws_message("trws_labeling: vertex ", i, " has ",
                                              nodes.label_count[i], " labels but ", size,
                                              " unary costs"));
    auto first = boost::begin(costs);
    FT* out = energy.unary_costs(i);
    for(std::size_t k = 0; k < size; ++k)
    {
      const double c = double(first[k]);
      if(!std::isfinite(c))
        throw Invalid_energy_error(trws_message("trws_labeling: unary cost of vertex ", i,
                                                ", label ", k, " is ", c,
                                                " (costs must be finite)"));
      out[k] = FT(c);
    }
  }
}

/// Adds the pairwise tables of the graph edges to those of their flat edges in `energy` (the
/// tables of members running against their flat edge are transposed), checking sizes and values.
template <typename FT, typename PairwiseCostMap, typename VertexDescriptor, typename EdgeDescriptor>
void trws_fill_pairwise_tables(Discrete_energy<FT>& energy, PairwiseCostMap& pairwise_costs,
                               const Trws_graph_nodes<VertexDescriptor>& nodes,
                               const Trws_graph_edges<EdgeDescriptor>& edges)
{
  const std::vector<std::size_t>& label_count = nodes.label_count;
  const std::vector<std::pair<std::size_t, std::size_t> >& ends = edges.ends;
  for(std::size_t f = 0; f < edges.flat_edges.size(); ++f)
  {
    const std::size_t ks = label_count[edges.flat_edges[f].first],
                      kt = label_count[edges.flat_edges[f].second];
    FT* table = energy.pairwise_costs(f);
    for(std::size_t j = edges.member_offsets[f]; j < edges.member_offsets[f + 1]; ++j)
    {
      const std::size_t i = edges.member_edge[j];
      auto&& costs = get(pairwise_costs, edges.members[j]);
      const std::size_t size = static_cast<std::size_t>(boost::size(costs));
      if(size != ks * kt)
        throw Invalid_energy_error(trws_message(
            "trws_labeling: the pairwise table of edge (", ends[i].first, ", ", ends[i].second,
            ") has ", size, " costs instead of ", label_count[ends[i].first], " x ",
            label_count[ends[i].second], " = ", ks * kt));
      auto first = boost::begin(costs);
      const std::size_t cols = label_count[ends[i].second]; // columns in the graph edge's order
      for(std::size_t k = 0; k < ks; ++k)
        for(std::size_t l = 0; l < kt; ++l)
        {
          const std::size_t r = edges.flipped[j] ? l * cols + k : k * cols + l;
          const double c = double(first[r]);
          if(!std::isfinite(c))
            throw Invalid_energy_error(trws_message(
                "trws_labeling: pairwise cost of edge (", ends[i].first, ", ", ends[i].second,
                "), labels (", r / cols, ", ", r % cols, ") is ", c, " (costs must be finite)"));
          table[k * kt + l] += FT(c);
        }
    }
  }
}

/// Solves the energy of trws_labeling(), starting from the `initial_labeling` named parameter
/// (read from its vertex map into a vector indexed by node) when there is one.
template <typename FT, typename ConcurrencyTag, typename Energy, typename VertexDescriptor, typename NamedParameters>
Trws_result trws_solve_graph_energy(const Energy& energy, const std::vector<VertexDescriptor>& vertex_of,
                                    const NamedParameters& np, std::vector<std::size_t>& labels)
{
  Trws_solver<FT, ConcurrencyTag> solver;
  if constexpr(!parameters::is_default_parameter<NamedParameters,
                                                 internal_np::initial_labeling_t>::value)
  {
    const auto initial_map = parameters::get_parameter(np, internal_np::initial_labeling);
    std::vector<long long> initial(vertex_of.size());
    for(std::size_t i = 0; i < vertex_of.size(); ++i)
      initial[i] = static_cast<long long>(get(initial_map, vertex_of[i]));
    return solver.solve(energy, labels, parameters::initial_labeling(initial, np));
  }
  else
    return solver.solve(energy, labels, np);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Minimises a pairwise discrete energy defined on the vertices and edges of a graph with TRW-S
/// (see `Trws_solver` for the algorithm):
/// \f[ E(x) = \sum_{v} \theta_v(x_v) + \sum_{e = (s, t)} \theta_e(x_s, x_t),
///     \qquad x_v \in \{0, \dots, K_v - 1\}, \f]
/// and writes the best labeling found into `labeling`.
///
/// Nodes are the vertices, processed in the order of the vertex index map. Parallel edges (two
/// edges joining the same two vertices, in either direction) are merged: their costs are summed.
/// Self-loops are rejected. The edges are enumerated with `edges(g)`, so no edge index map is
/// needed (an `adjacency_list` without an `edge_index` property works).
///
/// The pairwise costs of edge e are read once per edge as `get(pairwise_costs, e)`, whose type
/// selects the storage:
/// - a functor `c` with `c(k, l)` (k a label of `source(e, g)`, l of `target(e, g)`) convertible
///   to FT, e.g. a lambda or an `Eigen::MatrixXd`: costs are evaluated on the fly, memory
///   \f$O(\sum_v K_v + |E| \max_v K_v)\f$, each cost evaluated twice per iteration;
/// - otherwise a random-access range (e.g. `std::vector<double>`) of \f$K_s K_t\f$ costs, row-major
///   (row = label of `source(e, g)`): the costs are copied into contiguous tables of type FT,
///   memory \f$O(\sum_v K_v + \sum_{(s,t)} K_s K_t)\f$.
///
/// \tparam FT `float` or `double`: type of the stored costs and of the messages (float halves the
///   memory and is faster; double is more accurate).
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default) or `CGAL::Parallel_tag` (requires TBB):
///   with table costs and at least `Trws_solver::minimum_parallel_nodes` vertices, the passes run
///   on the threads of the current TBB arena, with the sequential result bit for bit (see
///   `Trws_solver`); functor costs are always solved sequentially.
/// \tparam Graph a model of `VertexListGraph` and `EdgeListGraph` (e.g. `boost::adjacency_list`,
///   or a `FaceGraph` such as `CGAL::Surface_mesh` seen as the graph of its vertices and edges).
/// \tparam LabelCountMap a model of `ReadablePropertyMap`, vertex descriptor to integer
///   \f$K_v \geq 1\f$.
/// \tparam UnaryCostMap a model of `ReadablePropertyMap`, vertex descriptor to a random-access
///   range of \f$K_v\f$ numbers \f$\theta_v(0 .. K_v - 1)\f$.
/// \tparam PairwiseCostMap a model of `ReadablePropertyMap`, edge descriptor to a functor or a
///   table (see above).
/// \tparam LabelingMap a model of `WritablePropertyMap`, vertex descriptor to an integer type.
/// \tparam NamedParameters a sequence of named parameters.
///
/// \param g the graph.
/// \param label_counts number of labels of each vertex.
/// \param unary_costs unary costs of each vertex.
/// \param pairwise_costs pairwise costs of each edge.
/// \param labeling output: the label of each vertex.
/// \param np optional named parameters among:
/// - `vertex_index_map` (CGAL's): a `ReadablePropertyMap` from vertices to distinct indices in
///   [0, `num_vertices(g)`); default: the graph's initialised vertex index map
///   (`CGAL::get_initialized_vertex_index_map(g)`). It fixes the node order of TRW-S.
/// - `number_of_iterations` (CGAL's): maximum number of iterations; integer; default 100.
/// - `relative_tolerance`: stop when the lower bound's relative change in one iteration, or the
///   relative gap between the best energy and the bound, is at most this; `double`; default 1e-5.
/// - `initial_labeling`: a `ReadablePropertyMap` from vertices to integer labels to start from
///   (kept unless a better labeling is found); default: none.
/// - `visitor` (CGAL's): called after every iteration k as `visitor.iteration(k, energy,
///   lower_bound)` if that member exists, else `visitor(k, energy, lower_bound)`; returns `bool`,
///   `false` stops. Default: `Trws_default_visitor`.
///
/// \returns energy, lower bound, iterations run, the termination reason and the threads used.
/// \throws Invalid_energy_error naming the vertex or edge (by vertex indices): a vertex with no
///   label, a unary range or table of the wrong size, a NaN or infinite cost, a self-loop.
/// \throws Invalid_parameter_error for an invalid vertex index map, a bad initial labeling or a
///   bad parameter value.
/// \throws Numerical_error if the messages overflow (costs too large for FT).
template <typename FT = double, typename ConcurrencyTag = CGAL::Sequential_tag, typename Graph,
          typename LabelCountMap, typename UnaryCostMap, typename PairwiseCostMap, typename LabelingMap,
          typename NamedParameters = parameters::Default_named_parameters>
Trws_result trws_labeling(const Graph& g, LabelCountMap label_counts, UnaryCostMap unary_costs,
                          PairwiseCostMap pairwise_costs, LabelingMap labeling,
                          const NamedParameters& np = parameters::default_values())
{
  BOOST_CONCEPT_ASSERT((boost::VertexListGraphConcept<Graph>));
  BOOST_CONCEPT_ASSERT((boost::EdgeListGraphConcept<Graph>));
  typedef typename boost::graph_traits<Graph>::edge_descriptor edge_descriptor;
  typedef typename boost::property_traits<PairwiseCostMap>::value_type Pairwise_value;

  // Nodes: vertices numbered by the vertex index map, which must be a bijection onto [0, n).
  const auto vertex_index = internal::trws_vertex_index_map(g, np);
  const auto nodes = internal::trws_graph_nodes(g, vertex_index, label_counts);
  // Edges; parallel edges are grouped, the first one of a group (in the order of edges(g)) gives
  // the orientation of the merged edge.
  const auto graph_edges = internal::trws_graph_edges(g, vertex_index);

  std::vector<std::size_t> labels;
  Trws_result result;
  if constexpr(internal::Trws_is_cost_functor<Pairwise_value>::value)
  {
    typedef internal::Trws_graph_pairwise_cost<FT, edge_descriptor, PairwiseCostMap> Cost;
    Discrete_energy<FT, Cost> energy(nodes.label_count, graph_edges.flat_edges,
                                     Cost(pairwise_costs, &graph_edges.members, &graph_edges.member_offsets,
                                          &graph_edges.flipped));
    internal::trws_fill_unary_costs<FT>(energy, unary_costs, nodes);
    result = internal::trws_solve_graph_energy<FT, ConcurrencyTag>(energy, nodes.vertex_of, np, labels);
  }
  else
  {
    Discrete_energy<FT> energy(nodes.label_count, graph_edges.flat_edges);
    internal::trws_fill_unary_costs<FT>(energy, unary_costs, nodes);
    internal::trws_fill_pairwise_tables(energy, pairwise_costs, nodes, graph_edges);
    result = internal::trws_solve_graph_energy<FT, ConcurrencyTag>(energy, nodes.vertex_of, np, labels);
  }

  typedef typename boost::property_traits<LabelingMap>::value_type Label;
  for(std::size_t i = 0; i < nodes.vertex_of.size(); ++i)
    put(labeling, nodes.vertex_of[i], static_cast<Label>(labels[i]));
  return result;
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_TRWS_H
