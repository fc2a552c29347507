// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Wave Kernel Signature (M. Aubry, U. Schlickewei, D. Cremers, "The wave kernel signature:
// a quantum mechanical approach to shape analysis", ICCV Workshops 2011).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_WAVE_KERNEL_SIGNATURE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_WAVE_KERNEL_SIGNATURE_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/spectral_signature.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/tags.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The log-energies of the WKS and the width of its energy filters.
struct Wave_kernel_signature_energies
{
  /// The d log-energies \f$ e_c \f$ (in unit-area units when returned by
  /// wave_kernel_signature_energies()).
  Eigen::VectorXd log_energies;
  /// The standard deviation \f$ \sigma \f$ of the log-normal energy filters.
  double sigma = 0;
};

namespace internal {


/// The weights W(j, c) = exp(-(e_c - log lambda_j)^2 / (2 sigma^2)), 0 for lambda_j <= 0.
inline Eigen::MatrixXd wave_kernel_weights(const Eigen::VectorXd& eigenvalues,
                                           const Eigen::VectorXd& log_energies, double sigma)
{
  Eigen::MatrixXd weights(eigenvalues.size(), log_energies.size());
  const double inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  for(Eigen::Index j = 0; j < eigenvalues.size(); ++j)
  {
    if(!(eigenvalues[j] > 0))
    {
      weights.row(j).setZero();
      continue;
    }
    const double log_lambda = std::log(eigenvalues[j]);
    for(Eigen::Index c = 0; c < log_energies.size(); ++c)
    {
      const double d = log_energies[c] - log_lambda;
      weights(j, c) = std::exp(-d * d * inv_two_sigma2);
    }
  }
  return weights;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The un-normalised wave kernel signature
/// \f$ \sum_{j : \lambda_j > 0} \phi_j(x)^2 \exp\!\big(-\frac{(e - \log\lambda_j)^2}{2\sigma^2}\big) \f$
/// for given eigenpairs, log-energies e and filter width \f$ \sigma \f$ ("raw" WKS; zero
/// eigenvalues are skipped).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (rows in parallel)
/// \param eigenvalues the k eigenvalues
/// \param eigenvectors the n x k eigenvectors
/// \param log_energies the d log-energies e
/// \param sigma the filter width, > 0
/// \returns the n x d matrix of values.
/// \pre consistent, finite eigenpairs and sigma > 0 (else Invalid_parameter_error).
template <typename ConcurrencyTag = CGAL::Sequential_tag>
Eigen::MatrixXd wave_kernel_signature(const Eigen::VectorXd& eigenvalues,
                                      const Eigen::MatrixXd& eigenvectors,
                                      const Eigen::VectorXd& log_energies, double sigma)
{
  internal::check_eigenpairs(eigenvalues, eigenvectors, "wave kernel signature");
  if(!(sigma > 0) || !std::isfinite(sigma))
    throw Invalid_parameter_error("wave kernel signature: sigma = " + std::to_string(sigma) +
                                  " must be positive");
  return internal::squared_eigenvector_transform<ConcurrencyTag>(
      eigenvectors, internal::wave_kernel_weights(eigenvalues, log_energies, sigma));
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The automatic WKS energies of a spectrum, in unit-area units: with
/// \f$ \lambda' = \lambda A \f$, `number_of_wks_energies` = d log-energies evenly spaced from
/// \f$ \log\lambda'_1 \f$ (first non-zero eigenvalue) to \f$ \log\lambda'_{\max} \f$ (largest
/// one used, the k-th), step \f$ \delta = (\log\lambda'_{\max} - \log\lambda'_1)/(d-1) \f$, and
/// \f$ \sigma = \f$ `wks_variance` \f$ \times \delta \f$ (Aubry et al. 2011). With d = 1 the single
/// energy is the midpoint and \f$ \delta \f$ the whole range.
/// \tparam NamedParameters a sequence of named parameters
/// \param spectrum the spectrum
/// \param np optional named parameters among:
///   - `number_of_wks_energies`: d; type: `int`; default: 100; at least 1.
///   - `wks_variance`: the filter width in multiples of the energy step; type: `double`;
///     default: 7; positive.
///   - `number_of_eigenpairs`: k, the signature uses the first k eigenpairs of the spectrum; type:
///     `int`; default: all of them; 1 <= k <= `spectrum.number_of_eigenpairs()`.
/// \pre the spectrum has at least two distinct non-zero eigenvalues (else Invalid_parameter_error).
template <typename NamedParameters = parameters::Default_named_parameters>
Wave_kernel_signature_energies
wave_kernel_signature_energies(const Laplace_beltrami_spectrum& spectrum,
                               const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const int d = choose_parameter(get_parameter(np, internal_np::number_of_wks_energies),
                                 internal::matching_defaults().number_of_wks_energies);
  const double variance = choose_parameter(get_parameter(np, internal_np::wks_variance),
                                           internal::matching_defaults().wks_variance);
  if(d < 1)
    throw Invalid_parameter_error("wave kernel signature: number_of_wks_energies = " +
                                  std::to_string(d) + " must be at least 1");
  if(!(variance > 0) || !std::isfinite(variance))
    throw Invalid_parameter_error("wave kernel signature: wks_variance = " + std::to_string(variance) +
                                  " must be positive");
  const int k = internal::signature_eigenpairs(spectrum, np, "wave kernel signature");
  const int first = std::min(spectrum.number_of_zero_eigenvalues(), k);
  const double area = spectrum.total_area();
  if(first >= k || !(spectrum.eigenvalues()[first] > 0) ||
     !(spectrum.eigenvalues()[k - 1] > spectrum.eigenvalues()[first]))
    throw Invalid_parameter_error(
        "wave kernel signature: the spectrum needs at least two distinct non-zero eigenvalues (" +
        std::to_string(k) + " eigenpairs, " + std::to_string(spectrum.number_of_components()) +
        " components); request more eigenpairs");
  const double e_min = std::log(spectrum.eigenvalues()[first] * area);
  const double e_max = std::log(spectrum.eigenvalues()[k - 1] * area);
  Wave_kernel_signature_energies out;
  out.log_energies.resize(d);
  double step = e_max - e_min;
  if(d == 1)
    out.log_energies[0] = 0.5 * (e_min + e_max);
  else
  {
    step /= (d - 1);
    for(int c = 0; c < d; ++c) out.log_energies[c] = e_min + step * c;
  }
  out.sigma = variance * step;
  return out;
}

namespace internal {

/// The k x d weights of the normalised WKS of wave_kernel_signature(spectrum, np): the filters
/// g_j(e_c) of the unit-area eigenvalues, each column divided by its sum.
template <typename NamedParameters>
Eigen::MatrixXd normalized_wave_kernel_weights(const Laplace_beltrami_spectrum& spectrum, const NamedParameters& np)
{
  const Wave_kernel_signature_energies energies = wave_kernel_signature_energies(spectrum, np);
  const int k = signature_eigenpairs(spectrum, np, "wave kernel signature");
  Eigen::MatrixXd weights =
      wave_kernel_weights(spectrum.eigenvalues().head(k) * spectrum.total_area(), energies.log_energies, energies.sigma);
  for(Eigen::Index c = 0; c < weights.cols(); ++c)
  {
    const double normaliser = weights.col(c).sum();
    if(normaliser > 0) weights.col(c) /= normaliser;
  }
  return weights;
}

/// The rows of wave_kernel_signature(spectrum, np) at `vertices` (indices of the spectrum's
/// vertices, in range), computed from those rows of the eigenvectors alone.
template <typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXd wave_kernel_signature_rows(const Laplace_beltrami_spectrum& spectrum, const std::vector<int>& vertices,
                                           const NamedParameters& np = parameters::default_values())
{
  const Eigen::MatrixXd weights = normalized_wave_kernel_weights(spectrum, np);
  Eigen::MatrixXd rows(Eigen::Index(vertices.size()), weights.rows());
  for(std::size_t i = 0; i < vertices.size(); ++i)
    rows.row(Eigen::Index(i)) = spectrum.eigenvectors().row(vertices[i]).head(weights.rows());
  return squared_eigenvector_transform<CGAL::Sequential_tag>(rows, weights, spectrum.total_area());
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The scale-invariant, normalised Wave Kernel Signature (Aubry, Schlickewei and Cremers 2011)
/// of every vertex.
///
/// The spectrum is normalised to unit total area A (\f$ \lambda'_j = \lambda_j A \f$,
/// \f$ \phi'_j = \phi_j \sqrt{A} \f$); for the energies \f$ e_c \f$ and width \f$ \sigma \f$ of
/// wave_kernel_signature_energies(), column c is
/// \f[ \mathrm{WKS}(x, e_c) = \frac{\sum_{j:\lambda_j>0} \phi'_j(x)^2\, g_j(e_c)}
///                               {\sum_{j:\lambda_j>0} g_j(e_c)}, \quad
///     g_j(e) = \exp\!\Big(-\frac{(e - \log\lambda'_j)^2}{2\sigma^2}\Big), \f]
/// the per-energy normalisation \f$ C_e \f$ of the paper. Zero eigenvalues (one per component)
/// are skipped. Each column has unit mean over the surface:
/// \f$ \sum_i (M_{ii}/A)\,\mathrm{WKS}(x_i, e) = 1 \f$. For raw values use the overload taking
/// eigenvalues, eigenvectors, energies and sigma.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (rows in parallel)
/// \tparam NamedParameters a sequence of named parameters
/// \param spectrum the Laplace-Beltrami spectrum
/// \param np optional named parameters among:
///   - `number_of_wks_energies`: d; type: `int`; default: 100; at least 1.
///   - `wks_variance`: the filter width in multiples of the energy step; type: `double`;
///     default: 7; positive.
///   - `number_of_eigenpairs`: k, the signature uses the first k eigenpairs of the spectrum; type:
///     `int`; default: all of them; 1 <= k <= `spectrum.number_of_eigenpairs()`.
/// \returns the n x d matrix whose row i is the descriptor of vertex i.
/// \pre the spectrum has at least two distinct non-zero eigenvalues (else Invalid_parameter_error).
template <typename ConcurrencyTag = CGAL::Sequential_tag,
          typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXd wave_kernel_signature(const Laplace_beltrami_spectrum& spectrum,
                                      const NamedParameters& np = parameters::default_values())
{
  return internal::squared_eigenvector_transform<ConcurrencyTag>(
      spectrum.eigenvectors(), internal::normalized_wave_kernel_weights(spectrum, np), spectrum.total_area());
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Convenience overload: computes the Laplace_beltrami_spectrum of `tm` (with the named
/// parameters of its constructor) and returns its normalised WKS.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag`
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam NamedParameters a sequence of named parameters
/// \param tm the triangle mesh
/// \param np the named parameters of Laplace_beltrami_spectrum's constructor
///   (`number_of_eigenpairs`, `use_intrinsic_delaunay`, `eigen_shift`, `vertex_point_map`,
///   `vertex_index_map`) and `number_of_wks_energies`, `wks_variance`.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXd wave_kernel_signature(const TriangleMesh& tm,
                                      const NamedParameters& np = parameters::default_values())
{
  const Laplace_beltrami_spectrum spectrum(tm, np);
  return wave_kernel_signature<ConcurrencyTag>(spectrum, np);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_WAVE_KERNEL_SIGNATURE_H
