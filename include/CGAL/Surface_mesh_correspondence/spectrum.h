// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The first eigenpairs of the Laplace-Beltrami operator, L phi = lambda M phi, computed once and
// shared by the descriptors (HKS, WKS), functional maps and the refinement.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_SPECTRUM_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_SPECTRUM_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/laplacian.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Settings of the sparse generalised eigensolver (Spectra, shift-invert mode).
struct Eigensolver_settings
{
  /// Shift sigma in units of 1 / (area of the component): L - sigma M is factorised, so sigma
  /// must be negative (then L - sigma M is positive definite).
  double relative_shift = -1e-2;
  /// Dimension of the Krylov subspace; 0 chooses it from the number of eigenpairs.
  int krylov_dimension = 0;
  /// Relative tolerance on the Ritz values (Spectra's `tol`).
  double tolerance = 1e-10;
  /// Maximum number of implicit restarts.
  int max_restarts = 1000;
  /// Components with at most this many vertices are solved with a dense eigensolver.
  int dense_threshold = 400;
};

/// What the eigensolver did, for benchmarks.
struct Eigensolver_statistics
{
  int restarts = 0;          ///< Lanczos restarts, summed over the components
  int operations = 0;        ///< applications of (L - sigma M)^{-1} M
  int dense_components = 0;  ///< components solved densely
  int krylov_dimension = 0;  ///< Krylov dimension used for the largest component
};

/// Default Krylov dimension for k eigenpairs (measured in benchmark/bench_spectral.cpp).
inline int default_krylov_dimension(int k) { return std::max(2 * k + 1, k + 20); }

/// Spectra operator y = (L - sigma M)^{-1} x, with L - sigma M factorised once by a sparse LDLT.
class Shift_invert_ldlt
{
public:
  typedef double Scalar;
  Shift_invert_ldlt(const Eigen::SparseMatrix<double>& stiffness, const Eigen::VectorXd& mass)
      : stiffness_(stiffness), mass_(mass)
  {}
  Eigen::Index rows() const { return stiffness_.rows(); }
  Eigen::Index cols() const { return stiffness_.cols(); }
  void set_shift(double sigma)
  {
    Eigen::SparseMatrix<double> shifted = stiffness_;
    for(Eigen::Index i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) -= sigma * mass_[i];
    ldlt_.compute(shifted);
    if(ldlt_.info() != Eigen::Success)
      throw Numerical_error("Laplace-Beltrami spectrum: the sparse LDLT factorisation of L - sigma M "
                            "failed (sigma = " + std::to_string(sigma) + ")");
  }
  void perform_op(const double* x_in, double* y_out) const
  {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = ldlt_.solve(x);
  }

private:
  const Eigen::SparseMatrix<double>& stiffness_;
  const Eigen::VectorXd& mass_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int> > ldlt_;
};

/// Spectra operator y = M x for the diagonal mass matrix.
class Diagonal_product
{
public:
  typedef double Scalar;
  explicit Diagonal_product(const Eigen::VectorXd& diagonal) : diagonal_(diagonal) {}
  Eigen::Index rows() const { return diagonal_.size(); }
  Eigen::Index cols() const { return diagonal_.size(); }
  void perform_op(const double* x_in, double* y_out) const
  {
    for(Eigen::Index i = 0; i < diagonal_.size(); ++i) y_out[i] = diagonal_[i] * x_in[i];
  }

private:
  const Eigen::VectorXd& diagonal_;
};

/// Relative size of the third moment below which the sign falls back to the largest entry.
constexpr double sign_moment_threshold = 1e-6;

/// Fixes the sign of each column of `vectors` (M-normalised, supported on a region of area
/// `area`): the sign that makes \f$ \sum_i M_{ii} \phi_i^3 \f$ positive; when that moment is
/// below 1e-6 / sqrt(area) (e.g. odd functions on symmetric shapes), the sign that makes the
/// entry of largest magnitude positive, the lowest vertex index winning among entries within a
/// relative 1e-6 of the largest.
inline void fix_eigenvector_signs(Eigen::MatrixXd& vectors, const Eigen::VectorXd& mass, double area)
{
  for(Eigen::Index j = 0; j < vectors.cols(); ++j)
  {
    auto phi = vectors.col(j);
    const double moment = (mass.array() * phi.array().cube()).sum();
    double sign = 1;
    if(std::abs(moment) * std::sqrt(area) > sign_moment_threshold)
      sign = moment > 0 ? 1 : -1;
    else
    {
      const double largest = phi.cwiseAbs().maxCoeff();
      for(Eigen::Index i = 0; i < phi.size(); ++i)
        if(std::abs(phi[i]) >= (1 - 1e-6) * largest)
        {
          sign = phi[i] >= 0 ? 1 : -1;
          break;
        }
    }
    if(sign < 0) phi = -phi;
  }
}

/// The k smallest eigenpairs of L phi = lambda M phi for one connected component (k <= n).
/// Eigenvalues ascending, eigenvectors M-orthonormal, the first pair set exactly to
/// (0, 1 / sqrt(area)), signs fixed by fix_eigenvector_signs().
inline void connected_eigenpairs(const Eigen::SparseMatrix<double>& stiffness,
                                 const Eigen::VectorXd& mass, int k,
                                 const Eigensolver_settings& settings, Eigen::VectorXd& values,
                                 Eigen::MatrixXd& vectors, Eigensolver_statistics& statistics)
{
  const int n = static_cast<int>(mass.size());
  const double area = mass.sum();
  const int ncv = std::min(n, settings.krylov_dimension > 0 ? std::max(settings.krylov_dimension, k + 1)
                                                            : default_krylov_dimension(k));
  if(n <= settings.dense_threshold || k >= n - 1 || ncv >= n)
  {
    // Dense: the symmetric matrix M^{-1/2} L M^{-1/2} has the same eigenvalues.
    const Eigen::VectorXd inv_sqrt_mass = mass.cwiseSqrt().cwiseInverse();
    Eigen::MatrixXd a = Eigen::MatrixXd(stiffness);
    a = inv_sqrt_mass.asDiagonal() * a * inv_sqrt_mass.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a);
    if(solver.info() != Eigen::Success)
      throw Numerical_error("Laplace-Beltrami spectrum: the dense eigensolver failed on a component "
                            "of " + std::to_string(n) + " vertices");
    values = solver.eigenvalues().head(k);
    vectors = inv_sqrt_mass.asDiagonal() * solver.eigenvectors().leftCols(k);
    ++statistics.dense_components;
  }
  else
  {
    const double sigma = settings.relative_shift / area;
    Shift_invert_ldlt op(stiffness, mass);
    Diagonal_product bop(mass);
    typedef Spectra::SymGEigsShiftSolver<Shift_invert_ldlt, Diagonal_product,
                                         Spectra::GEigsMode::ShiftInvert> Solver;
    try
    {
      Solver solver(op, bop, k, ncv, sigma);
      solver.init();
      const Eigen::Index converged =
          solver.compute(Spectra::SortRule::LargestMagn, settings.max_restarts, settings.tolerance,
                         Spectra::SortRule::SmallestAlge);
      statistics.restarts += static_cast<int>(solver.num_iterations());
      statistics.operations += static_cast<int>(solver.num_operations());
      statistics.krylov_dimension = std::max(statistics.krylov_dimension, ncv);
      if(solver.info() != Spectra::CompInfo::Successful || converged < k)
        throw Numerical_error(
            "Laplace-Beltrami spectrum: Spectra did not converge: " + std::to_string(converged) +
            " of the " + std::to_string(k) + " requested eigenpairs converged (component of " +
            std::to_string(n) + " vertices, Krylov dimension " + std::to_string(ncv) + ", " +
            std::to_string(settings.max_restarts) +
            " restarts); request fewer eigenpairs or change eigen_shift");
      values = solver.eigenvalues();
      vectors = solver.eigenvectors();
    }
    catch(const std::invalid_argument& e)
    {
      throw Numerical_error(std::string("Laplace-Beltrami spectrum: Spectra failed: ") + e.what());
    }
  }
  if(!values.allFinite() || !vectors.allFinite())
    throw Numerical_error("Laplace-Beltrami spectrum: non-finite eigenpairs");
  // The kernel of L on a connected component is spanned by the constant function.
  values[0] = 0;
  vectors.col(0).setConstant(1.0 / std::sqrt(area));
  fix_eigenvector_signs(vectors, mass, area);
}

/// The k smallest eigenpairs of L phi = lambda M phi, solving each connected component on its
/// own (L is block diagonal) and merging: eigenvalues ascending (ties in component order), each
/// eigenvector supported on one component; the zero eigenvalue appears once per component.
/// \pre 1 <= k < n
inline void laplace_beltrami_eigenpairs(const Eigen::SparseMatrix<double>& stiffness,
                                        const Eigen::VectorXd& mass, const std::vector<int>& component,
                                        int number_of_components, int k,
                                        const Eigensolver_settings& settings, Eigen::VectorXd& values,
                                        Eigen::MatrixXd& vectors,
                                        Eigensolver_statistics* statistics = nullptr)
{
  Eigensolver_statistics local_statistics;
  Eigensolver_statistics& stats = statistics ? *statistics : local_statistics;
  stats = Eigensolver_statistics();
  const int n = static_cast<int>(mass.size());
  if(number_of_components <= 1)
  {
    connected_eigenpairs(stiffness, mass, k, settings, values, vectors, stats);
    return;
  }
  // Split into blocks.
  std::vector<int> local(n), size(number_of_components, 0);
  for(int v = 0; v < n; ++v) local[v] = size[component[v]]++;
  std::vector<std::vector<Eigen::Triplet<double> > > triplets(number_of_components);
  for(Eigen::Index j = 0; j < stiffness.outerSize(); ++j)
    for(Eigen::SparseMatrix<double>::InnerIterator it(stiffness, j); it; ++it)
    {
      const int c = component[it.row()];
      triplets[c].emplace_back(local[it.row()], local[it.col()], it.value());
    }
  struct Pair
  {
    double value;
    int component, index;
  };
  std::vector<Pair> pairs;
  std::vector<Eigen::VectorXd> block_values(number_of_components);
  std::vector<Eigen::MatrixXd> block_vectors(number_of_components);
  std::vector<std::vector<int> > block_vertices(number_of_components);
  for(int v = 0; v < n; ++v) block_vertices[component[v]].push_back(v);
  for(int c = 0; c < number_of_components; ++c)
  {
    Eigen::SparseMatrix<double> block(size[c], size[c]);
    block.setFromTriplets(triplets[c].begin(), triplets[c].end());
    block.makeCompressed();
    std::vector<Eigen::Triplet<double> >().swap(triplets[c]);
    Eigen::VectorXd block_mass(size[c]);
    for(int i = 0; i < size[c]; ++i) block_mass[i] = mass[block_vertices[c][i]];
    connected_eigenpairs(block, block_mass, std::min(k, size[c]), settings, block_values[c],
                         block_vectors[c], stats);
    for(Eigen::Index i = 0; i < block_values[c].size(); ++i)
      pairs.push_back({block_values[c][i], c, static_cast<int>(i)});
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.value < b.value || (a.value == b.value && a.component < b.component);
  });
  values.resize(k);
  vectors = Eigen::MatrixXd::Zero(n, k);
  for(int j = 0; j < k; ++j)
  {
    const Pair& p = pairs[j];
    values[j] = p.value;
    const std::vector<int>& vs = block_vertices[p.component];
    for(std::size_t i = 0; i < vs.size(); ++i) vectors(vs[i], j) = block_vectors[p.component](i, p.index);
  }
}

/// Default number of eigenpairs of Laplace_beltrami_spectrum.

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The first eigenpairs of the Laplace-Beltrami operator of a triangle mesh, computed once and
/// shared by the descriptors (heat_kernel_signature(), wave_kernel_signature()), functional maps
/// and the refinement.
///
/// Solves the generalised eigenproblem \f$ L \phi = \lambda M \phi \f$ with the matrices of
/// laplace_beltrami_matrices() for the `k` smallest eigenvalues, with Spectra's
/// `SymGEigsShiftSolver` in shift-invert mode: \f$ L - \sigma M \f$ (with a small negative
/// shift \f$ \sigma \f$, so that it is positive definite) is factorised once with a sparse LDLT.
/// Each connected component is solved on its own (small ones densely), and the results merged.
///
/// Guarantees:
/// - eigenvalues ascending; the zero eigenvalue appears exactly (as 0) once per connected
///   component, with the eigenvector \f$ 1/\sqrt{A_c} \f$ on that component and 0 elsewhere;
/// - eigenvectors M-orthonormal, \f$ \Phi^\top M \Phi = I \f$; each is supported on a single
///   component;
/// - deterministic signs: each eigenvector \f$ \phi \f$ is oriented so that
///   \f$ \sum_i M_{ii} \phi_i^3 > 0 \f$ (an intrinsic rule, independent of the vertex order);
///   when this moment is negligible (\f$ |\sum_i M_{ii}\phi_i^3| \sqrt{A_c} \le 10^{-6} \f$, e.g. odd
///   functions on symmetric shapes), the entry of largest magnitude is made positive (the lowest
///   vertex index wins among entries within a relative \f$ 10^{-6} \f$ of the largest).
///
/// Vertex i is the vertex of index i in the vertex index map.
class Laplace_beltrami_spectrum
{
public:
  /// Computes the spectrum of a triangle mesh.
  ///
  /// \tparam TriangleMesh a model of `FaceListGraph`
  /// \tparam NamedParameters a sequence of named parameters
  ///
  /// \param tm the triangle mesh
  /// \param np optional named parameters among:
  ///   - `number_of_eigenpairs`: k, the number of eigenpairs; type: `int`; default: 100, reduced
  ///     to n - 1 on meshes with at most 100 vertices. A value given explicitly must satisfy
  ///     1 <= k < n (else Invalid_parameter_error).
  ///   - `use_intrinsic_delaunay`: assemble the operator on the intrinsic Delaunay triangulation;
  ///     type: `bool`; default: `true`.
  ///   - `eigen_shift`: the shift \f$ \sigma \f$ of the shift-invert transform, in units of
  ///     1 / (area of the component); type: `double`; default: -0.01; must be negative.
  ///   - `vertex_point_map`: the vertex positions; type: a readable property map from vertex
  ///     descriptors to points of a CGAL kernel; default: `get(CGAL::vertex_point, tm)`.
  ///   - `vertex_index_map`: a bijection from the vertices onto [0, n); default: the mesh's own.
  ///
  /// \pre `tm` is a non-empty, manifold triangle mesh without isolated vertices, degenerate faces
  ///   or non-finite coordinates (else Invalid_mesh_error).
  /// \throws Numerical_error when the eigensolver does not converge.
  template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters,
            typename std::enable_if<!std::is_same<TriangleMesh, internal::Indexed_mesh>::value &&
                                        !std::is_same<TriangleMesh, Laplace_beltrami_spectrum>::value,
                                    int>::type = 0>
  explicit Laplace_beltrami_spectrum(const TriangleMesh& tm,
                                     const NamedParameters& np = parameters::default_values())
  {
    compute(internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(),
                                        "Laplace-Beltrami spectrum: mesh"),
            np);
  }

  /// Computes the spectrum of an indexed mesh (the package's internal flat copy); the named
  /// parameters are those of the other constructor, without the property maps.
  template <typename NamedParameters = parameters::Default_named_parameters>
  explicit Laplace_beltrami_spectrum(const internal::Indexed_mesh& mesh,
                                     const NamedParameters& np = parameters::default_values())
  {
    compute(mesh, np);
  }

  /// The first `k` eigenpairs of `larger` with its matrices: the spectrum of the same mesh with
  /// fewer eigenpairs, without a second eigensolve. It equals a spectrum computed with
  /// `number_of_eigenpairs(k)` up to the eigensolver's tolerance (and, within an eigenspace that
  /// the k-th eigenvalue splits, up to a rotation of the eigenvectors).
  /// \throws Invalid_parameter_error unless 1 <= k <= larger.number_of_eigenpairs()
  Laplace_beltrami_spectrum(const Laplace_beltrami_spectrum& larger, int k)
      : matrices_(larger.matrices_), total_area_(larger.total_area_),
        number_of_components_(larger.number_of_components_), use_intrinsic_delaunay_(larger.use_intrinsic_delaunay_),
        statistics_(larger.statistics_)
  {
    if(k < 1 || k > larger.number_of_eigenpairs())
      throw Invalid_parameter_error("Laplace-Beltrami spectrum: cannot take " + std::to_string(k) +
                                    " eigenpairs from a spectrum of " +
                                    std::to_string(larger.number_of_eigenpairs()));
    eigenvalues_ = larger.eigenvalues_.head(k);
    eigenvectors_ = larger.eigenvectors_.leftCols(k);
  }

  /// The k eigenvalues, ascending (\f$ \lambda_0 = 0 \f$).
  const Eigen::VectorXd& eigenvalues() const { return eigenvalues_; }
  /// The n x k matrix of M-orthonormal eigenvectors (column j goes with eigenvalue j).
  const Eigen::MatrixXd& eigenvectors() const { return eigenvectors_; }
  /// The diagonal of the lumped mass matrix (vertex areas), of size n.
  const Eigen::VectorXd& mass() const { return matrices_.mass; }
  /// The cotangent stiffness matrix L (n x n).
  const Eigen::SparseMatrix<double>& stiffness_matrix() const { return matrices_.stiffness_matrix; }
  /// The diagonal mass matrix M (n x n).
  const Eigen::SparseMatrix<double>& mass_matrix() const { return matrices_.mass_matrix; }
  /// The total surface area (the sum of the vertex masses).
  double total_area() const { return total_area_; }
  /// n, the number of vertices.
  int number_of_vertices() const { return static_cast<int>(matrices_.mass.size()); }
  /// k, the number of eigenpairs.
  int number_of_eigenpairs() const { return static_cast<int>(eigenvalues_.size()); }
  /// The number of connected components, which is also the number of zero eigenvalues (when
  /// k is at least that large).
  int number_of_components() const { return number_of_components_; }
  /// The number of leading eigenvalues that are zero: min(k, number of components).
  int number_of_zero_eigenvalues() const
  {
    return std::min(number_of_components_, number_of_eigenpairs());
  }
  /// Whether the operator was built on the intrinsic Delaunay triangulation.
  bool uses_intrinsic_delaunay() const { return use_intrinsic_delaunay_; }
  /// The number of intrinsic edge flips made (0 without intrinsic Delaunay).
  int number_of_flips() const { return matrices_.number_of_flips; }

private:
  template <typename NamedParameters>
  void compute(const internal::Indexed_mesh& mesh, const NamedParameters& np)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    const int n = mesh.number_of_vertices();
    const bool k_given =
        !parameters::is_default_parameter<NamedParameters, internal_np::number_of_eigenpairs_t>::value;
    int k = choose_parameter(get_parameter(np, internal_np::number_of_eigenpairs),
                             internal::matching_defaults().number_of_eigenpairs);
    if(!k_given) k = std::min(k, n - 1);
    if(k < 1 || k >= n)
      throw Invalid_parameter_error("Laplace-Beltrami spectrum: number_of_eigenpairs = " +
                                    std::to_string(k) + " must be in [1, n - 1] = [1, " +
                                    std::to_string(n - 1) + "] for a mesh of " + std::to_string(n) +
                                    " vertices");
    internal::Eigensolver_settings settings;
    settings.relative_shift = choose_parameter(get_parameter(np, internal_np::eigen_shift),
                                               settings.relative_shift);
    if(!(settings.relative_shift < 0) || !std::isfinite(settings.relative_shift))
      throw Invalid_parameter_error("Laplace-Beltrami spectrum: eigen_shift = " +
                                    std::to_string(settings.relative_shift) +
                                    " must be negative (L - sigma M must be positive definite)");
    use_intrinsic_delaunay_ = choose_parameter(get_parameter(np, internal_np::use_intrinsic_delaunay),
                                               internal::default_use_intrinsic_delaunay);
    matrices_ = internal::laplace_beltrami_matrices(mesh, use_intrinsic_delaunay_);
    for(int v = 0; v < n; ++v)
      if(!(matrices_.mass[v] > 0))
        throw Invalid_mesh_error("Laplace-Beltrami spectrum: vertex " + std::to_string(v) +
                                 " has no area (it is isolated)");
    total_area_ = matrices_.mass.sum();
    number_of_components_ = mesh.number_of_components;
    internal::laplace_beltrami_eigenpairs(matrices_.stiffness_matrix, matrices_.mass, mesh.component,
                                          mesh.number_of_components, k, settings, eigenvalues_,
                                          eigenvectors_, &statistics_);
  }

public:
  /// Solver statistics (restarts, operator applications), for benchmarks.
  const internal::Eigensolver_statistics& solver_statistics() const { return statistics_; }

private:
  Laplace_beltrami_matrices matrices_;
  Eigen::VectorXd eigenvalues_;
  Eigen::MatrixXd eigenvectors_;
  double total_area_ = 0;
  int number_of_components_ = 0;
  bool use_intrinsic_delaunay_ = internal::default_use_intrinsic_delaunay;
  internal::Eigensolver_statistics statistics_;
};

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_SPECTRUM_H
