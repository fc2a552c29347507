// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Heat Kernel Signature (J. Sun, M. Ovsjanikov, L. Guibas, "A concise and provably
// informative multi-scale signature based on heat diffusion", SGP 2009).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_HEAT_KERNEL_SIGNATURE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_HEAT_KERNEL_SIGNATURE_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/spectral_signature.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/tags.h>

#include <Eigen/Core>

#include <cmath>
#include <string>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Default number of HKS time samples.

template <typename NamedParameters>
int number_of_hks_scales(const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const int d = choose_parameter(get_parameter(np, internal_np::number_of_hks_scales),
                                 internal::matching_defaults().number_of_hks_scales);
  if(d < 1)
    throw Invalid_parameter_error("heat kernel signature: number_of_hks_scales = " +
                                  std::to_string(d) + " must be at least 1");
  return d;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The heat kernel diagonal \f$ k_t(x, x) = \sum_j e^{-\lambda_j t} \phi_j(x)^2 \f$ for given
/// eigenpairs and times, without any normalisation ("raw" HKS).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (rows in parallel)
/// \param eigenvalues the k eigenvalues \f$ \lambda_j \f$
/// \param eigenvectors the n x k matrix of eigenvectors (M-orthonormal for the usual meaning)
/// \param times the d times t
/// \returns the n x d matrix \f$ (k_{t_c}(x_i, x_i))_{ic} \f$.
/// \pre eigenvalues and eigenvectors are finite, with as many eigenvectors as eigenvalues
///   (else Invalid_parameter_error).
template <typename ConcurrencyTag = CGAL::Sequential_tag>
Eigen::MatrixXd heat_kernel_signature(const Eigen::VectorXd& eigenvalues,
                                      const Eigen::MatrixXd& eigenvectors,
                                      const Eigen::VectorXd& times)
{
  internal::check_eigenpairs(eigenvalues, eigenvectors, "heat kernel signature");
  Eigen::MatrixXd weights(eigenvalues.size(), times.size());
  for(Eigen::Index c = 0; c < times.size(); ++c)
    weights.col(c) = (-eigenvalues.array() * times[c]).exp().matrix();
  return internal::squared_eigenvector_transform<ConcurrencyTag>(eigenvectors, weights);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The automatic HKS times of a spectrum, in unit-area units (the times used with the
/// eigenvalues \f$ \lambda_j A \f$ of the surface scaled to area 1):
/// `number_of_hks_scales` times log-spaced from \f$ 4 \ln 10 / \lambda'_{\max} \f$ to
/// \f$ 4 \ln 10 / \lambda'_1 \f$, where \f$ \lambda' = \lambda A \f$, \f$ \lambda'_1 \f$ is the first
/// non-zero eigenvalue and \f$ \lambda'_{\max} \f$ the largest one used (the k-th, see `number_of_eigenpairs`).
/// \tparam NamedParameters a sequence of named parameters
/// \param spectrum the spectrum
/// \param np optional named parameters among:
///   - `number_of_hks_scales`: number of times d; type: `int`; default: 16; at least 1.
///   - `number_of_eigenpairs`: k, the signature uses the first k eigenpairs of the spectrum; type:
///     `int`; default: all of them; 1 <= k <= `spectrum.number_of_eigenpairs()`.
/// \pre the spectrum has at least one non-zero eigenvalue (else Invalid_parameter_error).
template <typename NamedParameters = parameters::Default_named_parameters>
Eigen::VectorXd heat_kernel_signature_times(const Laplace_beltrami_spectrum& spectrum,
                                            const NamedParameters& np = parameters::default_values())
{
  const int d = internal::number_of_hks_scales(np);
  const int k = internal::signature_eigenpairs(spectrum, np, "heat kernel signature");
  const int first = std::min(spectrum.number_of_zero_eigenvalues(), k);
  if(first >= k || !(spectrum.eigenvalues()[first] > 0))
    throw Invalid_parameter_error(
        "heat kernel signature: the spectrum has no non-zero eigenvalue (" + std::to_string(k) +
        " eigenpairs, " + std::to_string(spectrum.number_of_components()) +
        " components); request more eigenpairs");
  const double area = spectrum.total_area();
  const double lambda_first = spectrum.eigenvalues()[first] * area;
  const double lambda_max = spectrum.eigenvalues()[k - 1] * area;
  const double c = 4.0 * std::log(10.0);
  return internal::log_samples(c / lambda_max, c / lambda_first, d);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The scale-invariant, heat-trace-normalised Heat Kernel Signature (Sun, Ovsjanikov and
/// Guibas 2009) of every vertex.
///
/// The spectrum is first normalised to unit total area A: \f$ \lambda'_j = \lambda_j A \f$,
/// \f$ \phi'_j = \phi_j \sqrt{A} \f$ (so a uniformly scaled copy of a shape gets the same
/// descriptors). For the times \f$ t_c \f$ of heat_kernel_signature_times(), column c is
/// \f[ \mathrm{HKS}(x, t_c) = \frac{\sum_{j} e^{-\lambda'_j t_c} \phi'_j(x)^2}
///                              {\sum_{j} e^{-\lambda'_j t_c}}, \f]
/// the heat kernel diagonal divided by the (truncated) heat trace. Sums run over the k
/// eigenpairs used (zero eigenvalues included). Each column has unit mean over the surface:
/// \f$ \sum_i (M_{ii}/A)\,\mathrm{HKS}(x_i, t) = 1 \f$. For raw values use the overload taking
/// eigenvalues, eigenvectors and times.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (rows in parallel)
/// \tparam NamedParameters a sequence of named parameters
/// \param spectrum the Laplace-Beltrami spectrum
/// \param np optional named parameters among:
///   - `number_of_hks_scales`: number of times d; type: `int`; default: 16; at least 1.
///   - `number_of_eigenpairs`: k, the signature uses the first k eigenpairs of the spectrum; type:
///     `int`; default: all of them; 1 <= k <= `spectrum.number_of_eigenpairs()`.
/// \returns the n x d matrix whose row i is the descriptor of vertex i.
/// \pre the spectrum has at least one non-zero eigenvalue (else Invalid_parameter_error).
template <typename ConcurrencyTag = CGAL::Sequential_tag,
          typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXd heat_kernel_signature(const Laplace_beltrami_spectrum& spectrum,
                                      const NamedParameters& np = parameters::default_values())
{
  const Eigen::VectorXd times = heat_kernel_signature_times(spectrum, np);
  const double area = spectrum.total_area();
  const int k = internal::signature_eigenpairs(spectrum, np, "heat kernel signature");
  const Eigen::ArrayXd lambda = spectrum.eigenvalues().head(k).array() * area;
  Eigen::MatrixXd weights(lambda.size(), times.size());
  for(Eigen::Index c = 0; c < times.size(); ++c)
  {
    weights.col(c) = (-lambda * times[c]).exp().matrix();
    weights.col(c) /= weights.col(c).sum();  // heat trace
  }
  return internal::squared_eigenvector_transform<ConcurrencyTag>(spectrum.eigenvectors(), weights,
                                                                 area);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Convenience overload: computes the Laplace_beltrami_spectrum of `tm` (with the named
/// parameters of its constructor) and returns its normalised HKS.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag`
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam NamedParameters a sequence of named parameters
/// \param tm the triangle mesh
/// \param np the named parameters of Laplace_beltrami_spectrum's constructor
///   (`number_of_eigenpairs`, `use_intrinsic_delaunay`, `eigen_shift`, `vertex_point_map`,
///   `vertex_index_map`) and `number_of_hks_scales`.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXd heat_kernel_signature(const TriangleMesh& tm,
                                      const NamedParameters& np = parameters::default_values())
{
  const Laplace_beltrami_spectrum spectrum(tm, np);
  return heat_kernel_signature<ConcurrencyTag>(spectrum, np);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_HEAT_KERNEL_SIGNATURE_H
