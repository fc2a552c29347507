// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the heat and wave kernel signatures share: both are, per vertex x and per column t,
//   D(x, t) = sum_j W(j, t) phi_j(x)^2
// for a k x d weight matrix W built from the eigenvalues, i.e. D = (Phi o Phi) W, a matrix
// product evaluated by blocks of rows (in parallel with CGAL::Parallel_tag).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SPECTRAL_SIGNATURE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SPECTRAL_SIGNATURE_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Returns scale * (Phi o Phi) * weights, an n x d matrix (weights k x d; Phi: the first k
/// columns of `eigenvectors`, which may have more).
template <typename ConcurrencyTag>
Eigen::MatrixXd squared_eigenvector_transform(const Eigen::MatrixXd& eigenvectors,
                                              const Eigen::MatrixXd& weights, double scale = 1.0)
{
  const Eigen::Index n = eigenvectors.rows();
  Eigen::MatrixXd out(n, weights.cols());
  const std::size_t block = 512;
  const std::size_t blocks = (static_cast<std::size_t>(n) + block - 1) / block;
  parallel_for<ConcurrencyTag>(blocks, [&](std::size_t b) {
    const Eigen::Index begin = static_cast<Eigen::Index>(b * block);
    const Eigen::Index rows = std::min<Eigen::Index>(static_cast<Eigen::Index>(block), n - begin);
    const Eigen::MatrixXd squared =
        eigenvectors.block(begin, 0, rows, weights.rows()).array().square().matrix();
    out.middleRows(begin, rows).noalias() = scale * (squared * weights);
  });
  return out;
}

/// The number k of leading eigenpairs of `spectrum` a signature uses: the named parameter
/// `number_of_eigenpairs` (1 <= k <= the spectrum's), by default all of them.
template <typename Spectrum, typename NamedParameters>
int signature_eigenpairs(const Spectrum& spectrum, const NamedParameters& np, const std::string& who)
{
  const int all = spectrum.number_of_eigenpairs();
  const int k = parameters::choose_parameter(parameters::get_parameter(np, internal_np::number_of_eigenpairs), all);
  if(k < 1 || k > all)
    throw Invalid_parameter_error(who + ": number_of_eigenpairs = " + std::to_string(k) + " must be in [1, " +
                                  std::to_string(all) + "] (the eigenpairs of the spectrum)");
  return k;
}

/// Checks a raw eigen-decomposition given to a descriptor: sizes agree, values are finite.
inline void check_eigenpairs(const Eigen::VectorXd& eigenvalues, const Eigen::MatrixXd& eigenvectors,
                             const std::string& who)
{
  if(eigenvalues.size() == 0 || eigenvectors.cols() != eigenvalues.size())
    throw Invalid_parameter_error(who + ": " + std::to_string(eigenvalues.size()) +
                                  " eigenvalues for " + std::to_string(eigenvectors.cols()) +
                                  " eigenvectors");
  if(!eigenvalues.allFinite() || !eigenvectors.allFinite())
    throw Invalid_parameter_error(who + ": non-finite eigenpairs");
}

/// Log-spaced samples from `first` to `last` (both > 0): count values, the geometric midpoint
/// when count == 1.
inline Eigen::VectorXd log_samples(double first, double last, int count)
{
  Eigen::VectorXd out(count);
  if(count == 1)
  {
    out[0] = std::sqrt(first * last);
    return out;
  }
  const double lf = std::log(first), ll = std::log(last);
  for(int i = 0; i < count; ++i) out[i] = std::exp(lf + (ll - lf) * i / (count - 1));
  return out;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SPECTRAL_SIGNATURE_H
