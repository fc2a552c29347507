// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exact nearest neighbours in moderately high dimension (spectral embeddings, 10 to 300
// coordinates), by blocked brute force: for a block of queries q and all data points y,
//   argmin_y |q - y|^2 = argmin_y (|y|^2 / 2 - <q, y>),
// where the inner products of the block are one single-precision matrix product (Eigen GEMM).
// Kd-trees do not help in these dimensions (measured in benchmark/bench_init.cpp); the GEMM runs
// near the machine's peak and the blocks are independent (parallel with CGAL::Parallel_tag).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_NEIGHBORS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_NEIGHBORS_H

#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Exact Euclidean nearest-neighbour search among the rows of a dense matrix.
///
/// The data are stored in single precision, transposed (one point per column), with their
/// half squared norms. A query block of `query_block` rows is multiplied with all data points at
/// once and the best score of each row kept; ties go to the lowest data index, so results do not
/// depend on the number of threads.
class Nearest_neighbor_search
{
public:
  typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic> Matrixf;

  Nearest_neighbor_search() = default;

  /// Indexes the rows of `data` (n x d).
  template <typename Derived>
  explicit Nearest_neighbor_search(const Eigen::MatrixBase<Derived>& data)
  {
    build(data);
  }

  /// Indexes the rows of `data` (n x d), replacing the previous data.
  template <typename Derived>
  void build(const Eigen::MatrixBase<Derived>& data)
  {
    points_ = data.transpose().template cast<float>();
    half_norms_ = 0.5f * points_.colwise().squaredNorm().transpose();
    extra_squared_norms_.resize(0);
  }

  /// Indexes points y_j = [data_j, e_j] of a larger space whose coordinates beyond the rows of
  /// `data` (n x d) are known only by their squared norms |e_j|^2 = `extra_squared_norms[j]`.
  /// Queries are given by their inner products with the data part alone: a query row q finds the
  /// j minimising |y_j|^2 / 2 - <q, data_j>, which is the nearest y_j to any point whose inner
  /// product with every y_j is <q, data_j> (for one, [q, 0]); the squared distances reported are
  /// those to [q, 0]. Used by the coupled ZoomOut, whose joint embeddings reduce to half their
  /// dimension this way.
  template <typename Derived>
  void build(const Eigen::MatrixBase<Derived>& data, const Eigen::VectorXd& extra_squared_norms)
  {
    CGAL_precondition(extra_squared_norms.size() == data.rows());
    points_ = data.transpose().template cast<float>();
    extra_squared_norms_ = extra_squared_norms;
    half_norms_ = (0.5 * (points_.template cast<double>().colwise().squaredNorm().transpose() + extra_squared_norms))
                      .template cast<float>();
  }

  Eigen::Index size() const { return points_.cols(); }
  Eigen::Index dimension() const { return points_.rows(); }

  /// For every row i of `queries` (m x d), writes the index of the nearest data row into
  /// `nearest[i]`, and its squared distance into `squared_distances[i]` when that pointer is not
  /// null (the squared distance is recomputed in double precision for the winner).
  template <typename ConcurrencyTag, typename Derived>
  void query(const Eigen::MatrixBase<Derived>& queries, int* nearest,
             double* squared_distances = nullptr, Eigen::Index query_block = 128) const
  {
    const Eigen::Index m = queries.rows();
    const Eigen::Index n = points_.cols();
    if(m == 0 || n == 0) return;
    // Negated queries: the product then gives -<q, y> directly (negation is exact), without a
    // second pass over the scores.
    const Matrixf q_all = -queries.template cast<float>();
    const std::size_t blocks = static_cast<std::size_t>((m + query_block - 1) / query_block);
    parallel_for<ConcurrencyTag>(blocks, [&](std::size_t b) {
      const Eigen::Index begin = static_cast<Eigen::Index>(b) * query_block;
      const Eigen::Index rows = std::min(query_block, m - begin);
      // scores(j, r) = |y_j|^2 / 2 - <q_r, y_j>: one contiguous column per query.
      Matrixf scores(n, rows);
      scores.noalias() = points_.transpose() * q_all.middleRows(begin, rows).transpose();
      for(Eigen::Index r = 0; r < rows; ++r)
      {
        auto column = scores.col(r);
        column += half_norms_;
        const float best = column.minCoeff();  // vectorised; then the first index reaching it
        int best_j = 0;
        while(column[best_j] != best) ++best_j;
        nearest[begin + r] = best_j;
        if(squared_distances)
        {
          double d2 = 0;
          for(Eigen::Index c = 0; c < queries.cols(); ++c)
          {
            const double diff = double(queries(begin + r, c)) - double(points_(c, best_j));
            d2 += diff * diff;
          }
          if(extra_squared_norms_.size() > 0) d2 += extra_squared_norms_[best_j];
          squared_distances[begin + r] = d2;
        }
      }
    });
  }

private:
  Matrixf points_;      // d x n, one data point per column
  Eigen::VectorXf half_norms_;  // |y_j|^2 / 2
  Eigen::VectorXd extra_squared_norms_;  // |e_j|^2 of the coordinates beyond points_, or empty
};

/// Convenience: nearest row of `data` for every row of `queries`.
template <typename ConcurrencyTag, typename DerivedQ, typename DerivedD>
std::vector<int> nearest_rows(const Eigen::MatrixBase<DerivedQ>& queries,
                              const Eigen::MatrixBase<DerivedD>& data)
{
  std::vector<int> out(static_cast<std::size_t>(queries.rows()));
  Nearest_neighbor_search search(data);
  search.template query<ConcurrencyTag>(queries, out.data());
  return out;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_NEIGHBORS_H
