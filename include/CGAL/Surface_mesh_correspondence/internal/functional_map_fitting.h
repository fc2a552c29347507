// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The functional map fits of the automatic initialisation: the descriptors of a shape (WKS, HKS,
// signed), the landmark wave kernel maps, the reduced descriptor terms and operators, and the fit
// of one candidate configuration.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FUNCTIONAL_MAP_FITTING_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FUNCTIONAL_MAP_FITTING_H

#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/orientation_operator.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// `functions` (one per column) projected on the first `smoothing` eigenfunctions of `spectrum`
/// (at most all of them; unchanged for 0): the smoothing of the orientation-sensitive descriptors
/// and of the landmarks' chirality features.
inline Eigen::MatrixXd smooth_on_eigenfunctions(const Laplace_beltrami_spectrum& spectrum, Eigen::MatrixXd functions,
                                                int smoothing)
{
  smoothing = std::min(smoothing, spectrum.number_of_eigenpairs());
  if(smoothing <= 0) return functions;
  const Eigen::MatrixXd& phi = spectrum.eigenvectors();
  return phi.leftCols(smoothing) * (phi.leftCols(smoothing).transpose() * (spectrum.mass().asDiagonal() * functions));
}

/// The descriptors of one shape used by the initialisation, n x d (see
/// Initialization_descriptor_layout): WKS columns (if wks_weight > 0), HKS columns (if
/// hks_weight > 0), then orientation-sensitive columns <n, grad f x grad g> for pairs of them,
/// smoothed by projection on the first `signed_descriptor_smoothing` eigenfunctions. Compute once
/// per shape; initialization_descriptor_weights() gives the column weights.
template <typename ConcurrencyTag>
Eigen::MatrixXd initialization_descriptors(const Indexed_mesh& mesh, const Laplace_beltrami_spectrum& spectrum,
                                           const Initialization_settings& s)
{
  const int n = spectrum.number_of_vertices();
  const Initialization_descriptor_layout l = initialization_descriptor_layout(s);
  Eigen::MatrixXd out(n, l.total());
  // The pass's eigenpairs only: the descriptors, and so the passes, do not depend on the final size.
  const int k = std::min(pass_final_size(s), spectrum.number_of_eigenpairs());
  if(l.wks > 0)
    out.leftCols(l.wks) = wave_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_wks_energies(
                      l.wks, parameters::wks_variance(s.wks_variance, parameters::number_of_eigenpairs(k))));
  if(l.hks > 0)
    out.middleCols(l.wks, l.hks) = heat_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_hks_scales(l.hks, parameters::number_of_eigenpairs(k)));
  if(!l.signed_pairs.empty())
  {
    const Eigen::MatrixXd g = smooth_on_eigenfunctions(
        spectrum,
        gradient_cross_products(mesh, out.leftCols(l.plain()), l.signed_pairs, 1.0 / std::sqrt(spectrum.total_area())),
        s.signed_descriptor_smoothing);
    out.rightCols(g.cols()) = g;
  }
  return out;
}

/// Signed volume of a closed mesh (0 with a boundary): its sign tells the orientation.
inline double signed_volume(const Indexed_mesh& m)
{
  if(m.has_boundary()) return 0;
  double v = 0;
  for(int t = 0; t < m.number_of_triangles(); ++t)
    v += m.point(m.triangles(t, 0)).dot(m.point(m.triangles(t, 1)).cross(m.point(m.triangles(t, 2))));
  return v / 6.0;
}

/// Wave kernel maps from landmark vertices: for landmark p and energy e, the vertex function
/// sum_{j: lambda_j > 0} g_j(e) phi_j(p) phi_j(x) / sum_j g_j(e) (unit-area eigenpairs), which
/// does not depend on the signs of the eigenvectors.
inline Eigen::MatrixXd landmark_wave_kernel_maps(const Eigen::MatrixXd& basis, const Eigen::VectorXd& values,
                                                 const std::vector<int>& points, int energies)
{
  const Eigen::Index k = basis.cols();
  int first = 0;
  while(first < k && !(values[first] > 1e-9 * values[k - 1])) ++first;
  const double lo = std::log(values[std::min<Eigen::Index>(first, k - 1)]), hi = std::log(values[k - 1]);
  const double delta = energies > 1 ? (hi - lo) / (energies - 1) : (hi - lo);
  const double sigma = 7.0 * delta;
  // Column (l, e) of the result is basis * (g_e .* phi(p_l)): one matrix product for all of them.
  Eigen::MatrixXd spectral(k, Eigen::Index(points.size()) * energies);
  for(int e = 0; e < energies; ++e)
  {
    const double energy = energies > 1 ? lo + e * delta : 0.5 * (lo + hi);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(k);
    for(Eigen::Index j = first; j < k; ++j)
    {
      const double d = energy - std::log(values[j]);
      g[j] = std::exp(-d * d / (2 * sigma * sigma));
    }
    g /= std::max(g.sum(), 1e-300);
    for(std::size_t l = 0; l < points.size(); ++l)
      spectral.col(Eigen::Index(l) * energies + e) = g.cwiseProduct(basis.row(points[l]).transpose());
  }
  return basis * spectral;
}

/// Divides each descriptor column by its L2 norm for the masses `mass` (columns of norm 0 stay).
inline void normalize_descriptor_columns(Eigen::MatrixXd& D, const Eigen::VectorXd& mass)
{
  for(Eigen::Index c = 0; c < D.cols(); ++c)
  {
    const double norm = std::sqrt(D.col(c).cwiseAbs2().dot(mass));
    if(norm > 0) D.col(c) /= norm;
  }
}

/// The descriptor columns that get multiplication and orientation operators: `count` evenly
/// spread columns among the first `plain` (WKS and HKS) of positive weight.
inline std::vector<Eigen::Index> operator_descriptor_columns(const Eigen::VectorXd& column_weights, int plain,
                                                             int count)
{
  std::vector<Eigen::Index> operator_columns;
  std::vector<Eigen::Index> candidates;
  for(Eigen::Index c = 0; c < plain; ++c)
    if(column_weights[c] > 0) candidates.push_back(c);
  const std::size_t m = std::min<std::size_t>(candidates.size(), std::size_t(std::max(0, count)));
  for(std::size_t i = 0; i < m; ++i)
    operator_columns.push_back(candidates[(i * candidates.size() + candidates.size() / (2 * m)) / m]);
  return operator_columns;
}

/// The reduced terms of one shape at basis size k: descriptor coefficients and, for the columns
/// `operator_columns`, the multiplication and orientation operators.
template <typename ConcurrencyTag>
Functional_map_shape_terms initialization_terms(const Indexed_mesh& mesh, const Eigen::MatrixXd& basis_k,
                                                const Eigen::VectorXd& mass, const Eigen::VectorXd& values_k,
                                                double area, const Eigen::MatrixXd& descriptors,
                                                const std::vector<Eigen::Index>& operator_columns,
                                                const Initialization_settings& s)
{
  Functional_map_shape_terms t;
  t.eigenvalues = values_k;
  t.descriptor_coefficients = basis_k.transpose() * (mass.asDiagonal() * descriptors);
  const std::size_t m = operator_columns.size();
  if(m == 0) return t;
  const Reduced_operator_geometry g =
      reduced_operator_geometry(mesh, basis_k, mass, 1.0 / std::sqrt(area), 1.0 / area);
  t.multiplication_operators.resize(m);
  t.orientation_operators.resize(m);
  parallel_for<ConcurrencyTag>(m, [&](std::size_t i) {
    const Eigen::VectorXd f = descriptors.col(operator_columns[i]);
    t.multiplication_operators[i] = reduced_multiplication_operator(g, f);
    t.orientation_operators[i] = reduced_orientation_operator(mesh, g, f, s.normalize_orientation_gradients);
  });
  return t;
}

/// The terms restricted to the first k basis functions (the reduced operators of a smaller basis
/// are the leading blocks of those of a larger one).
inline Functional_map_shape_terms leading_terms(const Functional_map_shape_terms& t, int k)
{
  Functional_map_shape_terms r;
  r.eigenvalues = t.eigenvalues.head(k);
  r.descriptor_coefficients = t.descriptor_coefficients.topRows(k);
  for(const Eigen::MatrixXd& x : t.multiplication_operators) r.multiplication_operators.push_back(x.topLeftCorner(k, k));
  for(const Eigen::MatrixXd& x : t.orientation_operators) r.orientation_operators.push_back(x.topLeftCorner(k, k));
  return r;
}

/// Divides each pair of corresponding operators (S_f, T_f) by the mean of their Frobenius norms,
/// so that the commutativity terms measure relative residuals.
inline void normalize_operator_pairs(Functional_map_shape_terms& a, Functional_map_shape_terms& b)
{
  auto normalize = [](std::vector<Eigen::MatrixXd>& x, std::vector<Eigen::MatrixXd>& y) {
    for(std::size_t f = 0; f < x.size(); ++f)
    {
      const double scale = 0.5 * (x[f].norm() + y[f].norm());
      if(scale > 0)
      {
        x[f] /= scale;
        y[f] /= scale;
      }
    }
  };
  normalize(a.multiplication_operators, b.multiplication_operators);
  normalize(a.orientation_operators, b.orientation_operators);
}

/// The orthogonal matrix nearest to C in the Frobenius norm (U V^T of the SVD).
inline Eigen::MatrixXd nearest_orthogonal(const Eigen::MatrixXd& C)
{
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return svd.matrixU() * svd.matrixV().transpose();
}

/// The fit of one candidate configuration in one direction (`forward`: C12, from the terms of
/// mesh 1 to those of mesh 2; else C21), from the reduced terms T1 and T2 at the largest candidate
/// size: their leading blocks of size k0, the operator pairs normalised, the signed descriptor
/// columns [signed_begin, signed_begin + signed_count) of mesh 2 negated for the mirror
/// hypothesis (`sign` -1), the orientation term of sign `orientation_sign * sign`; with
/// `procrustes`, the nearest orthogonal map.
inline Eigen::MatrixXd fit_candidate_map(const Functional_map_shape_terms& T1, const Functional_map_shape_terms& T2,
                                         const Fit_candidate& config, int sign, int orientation_sign,
                                         Eigen::Index signed_begin, Eigen::Index signed_count,
                                         const Eigen::VectorXd& column_weights, const Initialization_settings& s,
                                         bool forward)
{
  Functional_map_shape_terms a = leading_terms(T1, config.basis_size);
  Functional_map_shape_terms b = leading_terms(T2, config.basis_size);
  normalize_operator_pairs(a, b);
  Functional_map_weights w = s.weights;
  w.orientation = config.orientation_weight;
  w.commutativity = config.commutativity_weight;
  w.orientation_sign = orientation_sign * sign;
  if(sign < 0)
  {
    // The mirror hypothesis: the signed descriptors of mesh 2 change sign.
    b.descriptor_coefficients.middleCols(signed_begin, signed_count) *= -1.0;
  }
  Eigen::MatrixXd C = forward ? minimize_functional_map_energy(a, b, w, column_weights)
                              : minimize_functional_map_energy(b, a, w, column_weights);
  if(s.procrustes) C = nearest_orthogonal(C);
  return C;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_FUNCTIONAL_MAP_FITTING_H
