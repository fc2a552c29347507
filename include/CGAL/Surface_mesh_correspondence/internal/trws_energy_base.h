// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The structure shared by both kinds of Discrete_energy (trws.h): label counts, unary costs, the
// edge list and a compressed adjacency (incident edges of every node, sorted by neighbour index),
// validated when built.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_ENERGY_BASE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_ENERGY_BASE_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/trws_kernels.h>

#include <boost/range/begin.hpp>
#include <boost/range/end.hpp>
#include <boost/range/size.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

template <typename FT, typename ConcurrencyTag>
class Trws_solver;

namespace internal {

/// One incident edge of a node: the edge and the node at its other end.
struct Trws_incidence
{
  std::uint32_t edge;
  std::uint32_t neighbor;
};

template <typename... T>
std::string trws_message(const T&... parts)
{
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

// Whether the integer v is in [0, n), without signed/unsigned comparison warnings.
template <typename Integer>
bool trws_index_in_range(Integer v, std::size_t n)
{
  if constexpr(std::is_signed<Integer>::value)
    if(v < 0) return false;
  return static_cast<unsigned long long>(v) < n;
}

template <typename FT>
class Discrete_energy_base
{
  static_assert(std::is_floating_point<FT>::value, "FT must be float or double");

public:
  typedef FT Cost;

  /// Number of nodes.
  std::size_t number_of_nodes() const { return label_counts_.size(); }
  /// Number of edges.
  std::size_t number_of_edges() const { return edge_nodes_.size() / 2; }
  /// Number of labels \f$K_i\f$ of node `i`.
  std::size_t number_of_labels(std::size_t i) const { return label_counts_[i]; }
  /// Largest number of labels of a node (0 without nodes).
  std::size_t maximum_number_of_labels() const { return max_labels_; }
  /// First end of edge `e` (its pairwise table has one row per label of this node).
  std::size_t source(std::size_t e) const { return edge_nodes_[2 * e]; }
  /// Second end of edge `e` (one column per label of this node).
  std::size_t target(std::size_t e) const { return edge_nodes_[2 * e + 1]; }

  /// The \f$K_i\f$ unary costs \f$\theta_i(0), \dots, \theta_i(K_i - 1)\f$ of node `i`, stored
  /// contiguously; write them in place.
  FT* unary_costs(std::size_t i) { return unary_.data() + unary_offsets_[i]; }
  const FT* unary_costs(std::size_t i) const { return unary_.data() + unary_offsets_[i]; }
  /// \f$\theta_i(k)\f$.
  FT& unary_cost(std::size_t i, std::size_t k) { return unary_[unary_offsets_[i] + k]; }
  FT unary_cost(std::size_t i, std::size_t k) const { return unary_[unary_offsets_[i] + k]; }
  /// All unary costs, node after node (\f$\sum_i K_i\f$ values); node `i` starts at
  /// `unary_offset(i)`.
  FT* unary_data() { return unary_.data(); }
  const FT* unary_data() const { return unary_.data(); }
  std::size_t unary_offset(std::size_t i) const { return unary_offsets_[i]; }

protected:
  template <typename, typename>
  friend class CGAL::Surface_mesh_correspondence::Trws_solver;

  // Builds the structure; throws Invalid_energy_error for a node without labels, an edge with an
  // end out of range, a self-loop or two edges joining the same nodes.
  template <typename LabelCountRange, typename EdgeRange>
  void build_structure(const LabelCountRange& label_counts, const EdgeRange& edges)
  {
    const std::size_t n = static_cast<std::size_t>(boost::size(label_counts));
    if(n >= std::numeric_limits<std::uint32_t>::max())
      throw Invalid_energy_error(trws_message("Discrete_energy: too many nodes (", n, ")"));
    label_counts_.resize(n);
    unary_offsets_.resize(n + 1);
    unary_offsets_[0] = 0;
    max_labels_ = 0;
    std::size_t i = 0;
    for(auto it = boost::begin(label_counts); it != boost::end(label_counts); ++it, ++i)
    {
      const auto k = *it;
      if(!(k >= 1))
        throw Invalid_energy_error(trws_message("Discrete_energy: node ", i, " has no label"));
      if(static_cast<unsigned long long>(k) >= (1ull << 31))
        throw Invalid_energy_error(
            trws_message("Discrete_energy: node ", i, " has too many labels (", k, ")"));
      label_counts_[i] = static_cast<std::uint32_t>(k);
      unary_offsets_[i + 1] = unary_offsets_[i] + label_counts_[i];
      max_labels_ = (std::max)(max_labels_, std::size_t(label_counts_[i]));
    }
    unary_.assign(unary_offsets_[n], FT(0));

    const std::size_t m = static_cast<std::size_t>(boost::size(edges));
    if(m >= std::numeric_limits<std::uint32_t>::max())
      throw Invalid_energy_error(trws_message("Discrete_energy: too many edges (", m, ")"));
    edge_nodes_.resize(2 * m);
    std::size_t e = 0;
    for(auto it = boost::begin(edges); it != boost::end(edges); ++it, ++e)
    {
      const auto s = std::get<0>(*it);
      const auto t = std::get<1>(*it);
      if(!trws_index_in_range(s, n) || !trws_index_in_range(t, n))
        throw Invalid_energy_error(trws_message("Discrete_energy: edge ", e, " (", s, ", ", t,
                                                ") has an end out of range [0, ", n, ")"));
      if(s == t)
        throw Invalid_energy_error(
            trws_message("Discrete_energy: edge ", e, " is a self-loop at node ", s));
      edge_nodes_[2 * e] = static_cast<std::uint32_t>(s);
      edge_nodes_[2 * e + 1] = static_cast<std::uint32_t>(t);
    }

    // Compressed adjacency, each node's incidences sorted by neighbour (then edge) index.
    adjacency_offsets_.assign(n + 1, 0);
    for(std::size_t f = 0; f < m; ++f)
    {
      ++adjacency_offsets_[edge_nodes_[2 * f] + 1];
      ++adjacency_offsets_[edge_nodes_[2 * f + 1] + 1];
    }
    for(std::size_t v = 0; v < n; ++v) adjacency_offsets_[v + 1] += adjacency_offsets_[v];
    incidences_.resize(2 * m);
    std::vector<std::size_t> fill(adjacency_offsets_.begin(), adjacency_offsets_.end() - 1);
    for(std::size_t f = 0; f < m; ++f)
    {
      const std::uint32_t s = edge_nodes_[2 * f], t = edge_nodes_[2 * f + 1];
      incidences_[fill[s]++] = Trws_incidence{static_cast<std::uint32_t>(f), t};
      incidences_[fill[t]++] = Trws_incidence{static_cast<std::uint32_t>(f), s};
    }
    for(std::size_t v = 0; v < n; ++v)
    {
      Trws_incidence* b = incidences_.data() + adjacency_offsets_[v];
      Trws_incidence* end = incidences_.data() + adjacency_offsets_[v + 1];
      std::sort(b, end, [](const Trws_incidence& x, const Trws_incidence& y) {
        return x.neighbor < y.neighbor || (x.neighbor == y.neighbor && x.edge < y.edge);
      });
      for(Trws_incidence* p = b; p + 1 < end; ++p)
        if(p->neighbor == (p + 1)->neighbor)
          throw Invalid_energy_error(trws_message(
              "Discrete_energy: edges ", p->edge, " and ", (p + 1)->edge, " both join nodes ", v,
              " and ", p->neighbor, " (parallel edges: merge them by summing their tables)"));
    }
  }

  std::size_t structure_bytes() const
  {
    return label_counts_.capacity() * sizeof(std::uint32_t) +
           unary_offsets_.capacity() * sizeof(std::size_t) + unary_.capacity() * sizeof(FT) +
           edge_nodes_.capacity() * sizeof(std::uint32_t) +
           adjacency_offsets_.capacity() * sizeof(std::size_t) +
           incidences_.capacity() * sizeof(Trws_incidence);
  }

  // Throws Invalid_energy_error naming the first NaN or infinite unary cost.
  void check_unary_costs() const
  {
    const std::size_t bad = trws_first_non_finite(unary_.data(), unary_.size());
    if(bad == unary_.size()) return;
    const std::size_t i = std::upper_bound(unary_offsets_.begin(), unary_offsets_.end(), bad) -
                          unary_offsets_.begin() - 1;
    throw Invalid_energy_error(trws_message("Discrete_energy: unary cost of node ", i, ", label ",
                                            bad - unary_offsets_[i], " is ", unary_[bad],
                                            " (costs must be finite)"));
  }

  std::vector<std::uint32_t> label_counts_;
  std::vector<std::size_t> unary_offsets_;
  std::vector<FT> unary_;
  std::vector<std::uint32_t> edge_nodes_;
  std::vector<std::size_t> adjacency_offsets_;
  std::vector<Trws_incidence> incidences_;
  std::size_t max_labels_ = 0;
};

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_ENERGY_BASE_H
