// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Functional maps (Ovsjanikov, Ben-Chen, Solomon, Butscher and Guibas, "Functional maps: a
// flexible representation of maps between shapes", SIGGRAPH 2012) in Laplace-Beltrami bases:
// estimation from descriptors with Laplacian commutativity, descriptor commutativity (Nogneng
// and Ovsjanikov 2017), an orientation-preserving term (Ren, Poulenard, Liu, Melzi and
// Ovsjanikov 2018) and an optional bijectivity term, and the conversions between functional and
// point-to-point maps.
//
// Convention. For a point-to-point map T from a source shape S to a target shape T (one target
// vertex per source vertex), its functional map is the k_S x k_T matrix
//     C = Phi_S^+ Pi Phi_T,       Pi(x, y) = 1 iff T(x) = y,
// which transfers a function on the target (coefficients a) to the source (coefficients C a of
// f o T): it is the pull-back by T. Bases are the Laplace-Beltrami eigenvectors of the shapes
// scaled to unit area (Phi' = Phi sqrt(A), M' = M / A), so that C is orthogonal for an isometry
// even between shapes of different sizes.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_FUNCTIONAL_MAP_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_FUNCTIONAL_MAP_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/nearest_neighbors.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/tags.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Weights of the functional map energy (see fit_functional_map()).
struct Functional_map_weights
{
  /// Weight of descriptor preservation, \f$ w_d \f$.
  double descriptor = 1.0;
  /// Weight of commutativity with the Laplace-Beltrami operators, \f$ w_\Delta \f$.
  double laplacian = 1e-3;
  /// Weight of commutativity with the descriptor multiplication operators, \f$ w_c \f$.
  double commutativity = 1e-1;
  /// Weight of commutativity with the orientation operators, \f$ w_o \f$.
  double orientation = 1e-1;
  /// +1: the map preserves orientation (\f$ C O^T_f = O^S_f C \f$); -1: it reverses it
  /// (\f$ C O^T_f = -O^S_f C \f$).
  int orientation_sign = 1;
  /// Weight of the bijectivity term \f$ w_b \f$, used when an inverse functional map is given.
  double bijectivity = 0.0;
};

namespace internal {

/// The reduced quantities of one shape that the functional map energy uses (all at unit area).
struct Functional_map_shape_terms
{
  /// The k eigenvalues (of the shape scaled to unit area).
  Eigen::VectorXd eigenvalues;
  /// The k x d coefficients of the d descriptor functions in the basis (columns correspond
  /// across shapes).
  Eigen::MatrixXd descriptor_coefficients;
  /// Multiplication operators X_f (k x k) of some descriptors (corresponding across shapes).
  std::vector<Eigen::MatrixXd> multiplication_operators;
  /// Orientation operators O_f (k x k) of some descriptors (corresponding across shapes).
  std::vector<Eigen::MatrixXd> orientation_operators;

  int basis_size() const { return static_cast<int>(eigenvalues.size()); }
};

/// Checks that two shapes' terms can be fitted together.
inline void check_functional_map_terms(const Functional_map_shape_terms& s,
                                       const Functional_map_shape_terms& t,
                                       const Eigen::VectorXd& column_weights)
{
  const int ks = s.basis_size(), kt = t.basis_size();
  if(ks < 1 || kt < 1)
    throw Invalid_parameter_error("functional map: empty basis");
  if(s.descriptor_coefficients.rows() != ks || t.descriptor_coefficients.rows() != kt ||
     s.descriptor_coefficients.cols() != t.descriptor_coefficients.cols())
    throw Invalid_parameter_error("functional map: descriptor coefficients of sizes " +
                                  std::to_string(s.descriptor_coefficients.rows()) + " x " +
                                  std::to_string(s.descriptor_coefficients.cols()) + " and " +
                                  std::to_string(t.descriptor_coefficients.rows()) + " x " +
                                  std::to_string(t.descriptor_coefficients.cols()) +
                                  " do not match the bases (" + std::to_string(ks) + ", " +
                                  std::to_string(kt) + ")");
  if(column_weights.size() != 0 && column_weights.size() != s.descriptor_coefficients.cols())
    throw Invalid_parameter_error("functional map: " + std::to_string(column_weights.size()) +
                                  " descriptor weights for " +
                                  std::to_string(s.descriptor_coefficients.cols()) + " descriptors");
  if(s.multiplication_operators.size() != t.multiplication_operators.size() ||
     s.orientation_operators.size() != t.orientation_operators.size())
    throw Invalid_parameter_error("functional map: the two shapes have different numbers of "
                                  "descriptor operators");
}

/// The normalised squared eigenvalue differences D(i, j) = ((lambda^S_i - lambda^T_j) / lambda_max)^2.
inline Eigen::MatrixXd laplacian_commutativity_weights(const Functional_map_shape_terms& s,
                                                       const Functional_map_shape_terms& t)
{
  const double scale =
      std::max({s.eigenvalues.cwiseAbs().maxCoeff(), t.eigenvalues.cwiseAbs().maxCoeff(), 1e-300});
  Eigen::MatrixXd d(s.basis_size(), t.basis_size());
  for(int j = 0; j < t.basis_size(); ++j)
    for(int i = 0; i < s.basis_size(); ++i)
    {
      const double diff = (s.eigenvalues[i] - t.eigenvalues[j]) / scale;
      d(i, j) = diff * diff;
    }
  return d;
}

/// The energy of `C` (k_S x k_T) and its terms, for diagnostics and tests (see fit_functional_map()).
struct Functional_map_energy_terms
{
  double descriptor = 0, laplacian = 0, commutativity = 0, orientation = 0, bijectivity = 0;
  double total() const { return descriptor + laplacian + commutativity + orientation + bijectivity; }
};

inline Functional_map_energy_terms functional_map_energy(const Eigen::MatrixXd& C,
                                                         const Functional_map_shape_terms& s,
                                                         const Functional_map_shape_terms& t,
                                                         const Functional_map_weights& w,
                                                         const Eigen::VectorXd& column_weights = Eigen::VectorXd(),
                                                         const Eigen::MatrixXd* inverse = nullptr)
{
  Functional_map_energy_terms e;
  const Eigen::Index d = s.descriptor_coefficients.cols();
  if(d > 0)
  {
    Eigen::MatrixXd r = C * t.descriptor_coefficients - s.descriptor_coefficients;
    if(column_weights.size() == d) r = r * column_weights.cwiseSqrt().asDiagonal();
    e.descriptor = w.descriptor / double(d) * r.squaredNorm();
  }
  e.laplacian = w.laplacian * laplacian_commutativity_weights(s, t).cwiseProduct(C.cwiseAbs2()).sum();
  const std::size_t m = s.multiplication_operators.size();
  for(std::size_t f = 0; f < m; ++f)
    e.commutativity += (C * t.multiplication_operators[f] - s.multiplication_operators[f] * C).squaredNorm();
  if(m > 0) e.commutativity *= w.commutativity / double(m);
  const std::size_t o = s.orientation_operators.size();
  for(std::size_t f = 0; f < o; ++f)
    e.orientation += (C * t.orientation_operators[f] -
                      double(w.orientation_sign) * s.orientation_operators[f] * C).squaredNorm();
  if(o > 0) e.orientation *= w.orientation / double(o);
  if(inverse && w.bijectivity > 0)
  {
    const Eigen::MatrixXd a = C * (*inverse), b = (*inverse) * C;
    e.bijectivity = w.bijectivity * ((a - Eigen::MatrixXd::Identity(a.rows(), a.cols())).squaredNorm() +
                                     (b - Eigen::MatrixXd::Identity(b.rows(), b.cols())).squaredNorm());
  }
  return e;
}

/// The quadratic form of the energy in the k_S x k_T unknown C: the energy is
/// <C, N(C)> - 2 <C, R> + const, with N the normal operator; `Normal_operator` applies N and
/// gives its diagonal, for the matrix-free solver, and assembles it densely for the direct one.
class Functional_map_normal_equations
{
public:
  Functional_map_normal_equations(const Functional_map_shape_terms& s,
                                  const Functional_map_shape_terms& t, const Functional_map_weights& w,
                                  const Eigen::VectorXd& column_weights, const Eigen::MatrixXd* inverse)
      : s_(s), t_(t), w_(w), inverse_(inverse && w.bijectivity > 0 ? inverse : nullptr)
  {
    check_functional_map_terms(s, t, column_weights);
    ks_ = s.basis_size();
    kt_ = t.basis_size();
    if(inverse_ && (inverse_->rows() != kt_ || inverse_->cols() != ks_))
      throw Invalid_parameter_error("functional map: the inverse map must be " + std::to_string(kt_) +
                                    " x " + std::to_string(ks_));
    const Eigen::Index d = s.descriptor_coefficients.cols();
    // Descriptor term: (w_d / d) sum_c omega_c |C b_c - a_c|^2.
    Eigen::VectorXd omega = column_weights.size() == d ? column_weights : Eigen::VectorXd::Ones(d);
    const double wd = d > 0 ? w.descriptor / double(d) : 0.0;
    descriptor_gram_ = wd * t.descriptor_coefficients * omega.asDiagonal() *
                       t.descriptor_coefficients.transpose();                  // kt x kt
    rhs_ = wd * s.descriptor_coefficients * omega.asDiagonal() *
           t.descriptor_coefficients.transpose();                              // ks x kt
    laplacian_ = w.laplacian * laplacian_commutativity_weights(s, t);
    // Commutativity terms: sum_f c_f |C T_f - sigma_f S_f C|^2.
    const std::size_t m = s.multiplication_operators.size(), o = s.orientation_operators.size();
    const double cm = m > 0 ? w.commutativity / double(m) : 0.0;
    const double co = o > 0 ? w.orientation / double(o) : 0.0;
    for(std::size_t f = 0; f < m; ++f)
      add_commutation(s.multiplication_operators[f], t.multiplication_operators[f], cm, 1.0);
    for(std::size_t f = 0; f < o; ++f)
      add_commutation(s.orientation_operators[f], t.orientation_operators[f], co,
                      double(w.orientation_sign));
    // Target-side and source-side Gram matrices of the commutation terms.
    target_gram_ = descriptor_gram_;
    source_gram_ = Eigen::MatrixXd::Zero(ks_, ks_);
    for(const Commutation& c : commutations_)
    {
      target_gram_.noalias() += c.weight * c.target * c.target.transpose();
      source_gram_.noalias() += c.weight * c.source.transpose() * c.source;
    }
    if(inverse_)
    {
      // w_b (|C Q - I|^2 + |Q C - I|^2), Q = inverse (kt x ks).
      target_gram_.noalias() += w.bijectivity * (*inverse_) * inverse_->transpose();
      source_gram_.noalias() += w.bijectivity * inverse_->transpose() * (*inverse_);
      rhs_ += 2.0 * w.bijectivity * inverse_->transpose();
    }
  }

  int source_size() const { return ks_; }
  int target_size() const { return kt_; }
  /// Without commutation terms and source-side terms the rows of C decouple:
  /// row i solves c_i (G_T + diag(D_i.)) = r_i.
  bool separable() const { return commutations_.empty() && !inverse_; }
  const Eigen::MatrixXd& target_gram() const { return target_gram_; }
  const Eigen::MatrixXd& laplacian_weights() const { return laplacian_; }
  const Eigen::MatrixXd& right_hand_side() const { return rhs_; }

  /// N(C) for a k_S x k_T matrix C.
  void apply(const Eigen::MatrixXd& C, Eigen::MatrixXd& out) const
  {
    out.noalias() = C * target_gram_;
    out.noalias() += source_gram_ * C;
    out += laplacian_.cwiseProduct(C);
    for(const Commutation& c : commutations_)
    {
      // cross terms: -sigma c (S C T^T + S^T C T)
      const double a = -c.sign * c.weight;
      out.noalias() += a * (c.source * C * c.target.transpose());
      out.noalias() += a * (c.source.transpose() * C * c.target);
    }
  }

  /// The diagonal of N, as a k_S x k_T matrix.
  Eigen::MatrixXd diagonal() const
  {
    Eigen::MatrixXd d = laplacian_;
    for(int j = 0; j < kt_; ++j)
      for(int i = 0; i < ks_; ++i) d(i, j) += target_gram_(j, j) + source_gram_(i, i);
    for(const Commutation& c : commutations_)
      for(int j = 0; j < kt_; ++j)
        for(int i = 0; i < ks_; ++i) d(i, j) -= 2.0 * c.sign * c.weight * c.source(i, i) * c.target(j, j);
    return d;
  }

  /// The dense (k_S k_T) x (k_S k_T) matrix of N in the column-major vectorisation
  /// vec(C)[i + k_S j] = C(i, j).
  Eigen::MatrixXd assemble() const
  {
    const Eigen::Index K = Eigen::Index(ks_) * kt_;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(K, K);
    // C G_T: H[(i, j), (i, j')] += G_T(j', j); G_S C: H[(i, j), (i', j)] += G_S(i, i').
    for(int j = 0; j < kt_; ++j)
      for(int jp = 0; jp < kt_; ++jp)
      {
        const double g = target_gram_(jp, j);
        for(int i = 0; i < ks_; ++i) H(i + ks_ * j, i + ks_ * jp) += g;
      }
    for(int j = 0; j < kt_; ++j)
      H.block(ks_ * j, ks_ * j, ks_, ks_) += source_gram_;
    for(int j = 0; j < kt_; ++j)
      for(int i = 0; i < ks_; ++i) H(i + ks_ * j, i + ks_ * j) += laplacian_(i, j);
    if(!commutations_.empty())
    {
      // Cross terms of all commutations at once with one matrix product:
      // G[(j, j'), (i, i')] = sum_f sigma_f c_f T_f(j, j') S_f(i, i'), and
      // H[(i, j), (i', j')] -= G[(j', j), (i', i)] + G[(j, j'), (i, i')]  (the two cross terms).
      const Eigen::Index nc = static_cast<Eigen::Index>(commutations_.size());
      Eigen::MatrixXd U(Eigen::Index(kt_) * kt_, nc), V(Eigen::Index(ks_) * ks_, nc);
      for(Eigen::Index f = 0; f < nc; ++f)
      {
        const Commutation& c = commutations_[f];
        U.col(f) = Eigen::Map<const Eigen::VectorXd>(c.target.data(), c.target.size());
        V.col(f) = c.sign * c.weight * Eigen::Map<const Eigen::VectorXd>(c.source.data(), c.source.size());
      }
      const Eigen::MatrixXd G = U * V.transpose();
      for(int jp = 0; jp < kt_; ++jp)
        for(int ip = 0; ip < ks_; ++ip)
        {
          const Eigen::Index col = ip + Eigen::Index(ks_) * jp;
          for(int j = 0; j < kt_; ++j)
            for(int i = 0; i < ks_; ++i)
              H(i + Eigen::Index(ks_) * j, col) -=
                  G(jp + Eigen::Index(kt_) * j, ip + Eigen::Index(ks_) * i) +
                  G(j + Eigen::Index(kt_) * jp, i + Eigen::Index(ks_) * ip);
        }
    }
    return H;
  }

private:
  struct Commutation
  {
    const Eigen::MatrixXd& source;  // S_f (ks x ks)
    const Eigen::MatrixXd& target;  // T_f (kt x kt)
    double weight, sign;
  };
  void add_commutation(const Eigen::MatrixXd& S, const Eigen::MatrixXd& T, double weight, double sign)
  {
    if(S.rows() != ks_ || S.cols() != ks_ || T.rows() != kt_ || T.cols() != kt_)
      throw Invalid_parameter_error("functional map: a descriptor operator does not match the bases");
    if(weight > 0) commutations_.push_back({S, T, weight, sign});
  }

  const Functional_map_shape_terms& s_;
  const Functional_map_shape_terms& t_;
  Functional_map_weights w_;
  const Eigen::MatrixXd* inverse_;
  int ks_ = 0, kt_ = 0;
  Eigen::MatrixXd descriptor_gram_, target_gram_, source_gram_, rhs_, laplacian_;
  std::vector<Commutation> commutations_;
};

/// Solves the normal equations densely (Cholesky of the (k_S k_T)^2 matrix): exact, fast up to
/// k_S k_T of about 2000.
inline Eigen::MatrixXd solve_functional_map_direct(const Functional_map_normal_equations& eq)
{
  const int ks = eq.source_size(), kt = eq.target_size();
  Eigen::MatrixXd H = eq.assemble();
  // A tiny ridge keeps the system positive definite when terms are switched off.
  const double ridge = 1e-12 * std::max(1.0, H.diagonal().cwiseAbs().maxCoeff());
  H.diagonal().array() += ridge;
  const Eigen::Map<const Eigen::VectorXd> b(eq.right_hand_side().data(), Eigen::Index(ks) * kt);
  Eigen::LLT<Eigen::MatrixXd> llt(H);
  if(llt.info() != Eigen::Success)
    throw Numerical_error("functional map: the normal equations are not positive definite");
  const Eigen::VectorXd x = llt.solve(b);
  if(!x.allFinite()) throw Numerical_error("functional map: non-finite solution");
  return Eigen::Map<const Eigen::MatrixXd>(x.data(), ks, kt);
}

/// Solves separable normal equations (see Functional_map_normal_equations::separable()) row by
/// row: k_S Cholesky factorisations of k_T x k_T matrices.
inline Eigen::MatrixXd solve_functional_map_separable(const Functional_map_normal_equations& eq)
{
  const int ks = eq.source_size(), kt = eq.target_size();
  Eigen::MatrixXd C(ks, kt);
  const double ridge = 1e-12 * std::max(1.0, eq.target_gram().diagonal().cwiseAbs().maxCoeff());
  for(int i = 0; i < ks; ++i)
  {
    Eigen::MatrixXd H = eq.target_gram();
    H.diagonal() += eq.laplacian_weights().row(i).transpose();
    H.diagonal().array() += ridge;
    Eigen::LLT<Eigen::MatrixXd> llt(H);
    if(llt.info() != Eigen::Success)
      throw Numerical_error("functional map: the normal equations are not positive definite");
    C.row(i) = llt.solve(eq.right_hand_side().row(i).transpose()).transpose();
  }
  if(!C.allFinite()) throw Numerical_error("functional map: non-finite solution");
  return C;
}

/// Solves the normal equations by conjugate gradients with matrix-free products and a Jacobi
/// preconditioner, from `initial` (zero if empty). Returns the number of iterations in `iterations`.
inline Eigen::MatrixXd solve_functional_map_cg(const Functional_map_normal_equations& eq,
                                               const Eigen::MatrixXd& initial, double tolerance,
                                               int max_iterations, int* iterations = nullptr)
{
  const int ks = eq.source_size(), kt = eq.target_size();
  Eigen::MatrixXd x = initial.size() == Eigen::Index(ks) * kt ? initial : Eigen::MatrixXd::Zero(ks, kt);
  const Eigen::MatrixXd& b = eq.right_hand_side();
  Eigen::MatrixXd inv_diag = eq.diagonal();
  for(Eigen::Index i = 0; i < inv_diag.size(); ++i)
    inv_diag.data()[i] = inv_diag.data()[i] > 0 ? 1.0 / inv_diag.data()[i] : 1.0;
  Eigen::MatrixXd r(ks, kt), z(ks, kt), p(ks, kt), q(ks, kt);
  eq.apply(x, q);
  r = b - q;
  const double b_norm = std::max(b.norm(), 1e-300);
  z = inv_diag.cwiseProduct(r);
  p = z;
  double rz = (r.array() * z.array()).sum();
  int it = 0;
  for(; it < max_iterations && r.norm() > tolerance * b_norm; ++it)
  {
    eq.apply(p, q);
    const double pq = (p.array() * q.array()).sum();
    if(!(pq > 0)) break;
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    z = inv_diag.cwiseProduct(r);
    const double rz_new = (r.array() * z.array()).sum();
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  if(iterations) *iterations = it;
  if(!x.allFinite()) throw Numerical_error("functional map: non-finite solution");
  return x;
}

/// Largest k_S k_T for which fit_functional_map() uses the direct solver.
constexpr int functional_map_direct_size_limit = 2500;

/// Minimises the functional map energy; see the public fit_functional_map().
inline Eigen::MatrixXd minimize_functional_map_energy(const Functional_map_shape_terms& source,
                                          const Functional_map_shape_terms& target,
                                          const Functional_map_weights& weights,
                                          const Eigen::VectorXd& column_weights = Eigen::VectorXd(),
                                          const Eigen::MatrixXd* inverse = nullptr,
                                          const Eigen::MatrixXd& initial = Eigen::MatrixXd())
{
  Functional_map_normal_equations eq(source, target, weights, column_weights, inverse);
  if(eq.separable()) return solve_functional_map_separable(eq);
  if(eq.source_size() * eq.target_size() <= functional_map_direct_size_limit)
    return solve_functional_map_direct(eq);
  return solve_functional_map_cg(eq, initial, 1e-8, 20000);
}

/// The unit-area basis Phi sqrt(A) (first k columns) and masses M / A of a spectrum.
inline Eigen::MatrixXd unit_area_basis(const Laplace_beltrami_spectrum& s, int k)
{
  return s.eigenvectors().leftCols(k) * std::sqrt(s.total_area());
}
inline Eigen::VectorXd unit_area_mass(const Laplace_beltrami_spectrum& s)
{
  return s.mass() / s.total_area();
}

/// The functional map C = Phi_S^+ Pi Phi_T (k_S x k_T) of a point map, with Phi_S^+ = Phi_S^T M_S
/// (M-orthonormal bases), on given bases and source masses.
inline Eigen::MatrixXd functional_map_from_point_map(const Eigen::Ref<const Eigen::MatrixXd>& source_basis,
                                                     const Eigen::Ref<const Eigen::VectorXd>& source_mass,
                                                     const Eigen::Ref<const Eigen::MatrixXd>& target_basis,
                                                     const int* map)
{
  const Eigen::Index n = source_basis.rows();
  Eigen::MatrixXd pulled(n, target_basis.cols());
  for(Eigen::Index x = 0; x < n; ++x) pulled.row(x) = source_mass[x] * target_basis.row(map[x]);
  return source_basis.transpose() * pulled;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Minimises the functional map energy of Ovsjanikov et al. 2012 with commutativity terms, over
/// the \f$ k_S \times k_T \f$ matrix \f$ C \f$ that pulls functions back from the target to the
/// source (see the convention at the top of this header):
/// \f[ E(C) = \frac{w_d}{d} \sum_{c=1}^{d} \omega_c \| C b_c - a_c \|^2
///    + w_\Delta \sum_{ij} \Big(\frac{\lambda^S_i - \lambda^T_j}{\lambda_{\max}}\Big)^2 C_{ij}^2
///    + \frac{w_c}{m} \sum_{f} \| C X^T_f - X^S_f C \|^2
///    + \frac{w_o}{o} \sum_{f} \| C O^T_f - \sigma O^S_f C \|^2
///    + w_b \big( \| C Q - I \|^2 + \| Q C - I \|^2 \big), \f]
/// with \f$ a_c, b_c \f$ the coefficients of corresponding descriptors on source and target,
/// \f$ \omega_c \f$ their weights, \f$ X_f \f$ the multiplication operators and \f$ O_f \f$ the
/// orientation operators of corresponding descriptors, \f$ \sigma \f$ = `orientation_sign`
/// and \f$ Q \f$ an optional inverse map (\f$ k_T \times k_S \f$). All terms are quadratic: the
/// normal equations are solved directly (dense Cholesky) when \f$ k_S k_T \le 2500 \f$, else by
/// preconditioned conjugate gradients with matrix-free operator products.
///
/// \param source the reduced terms of the source shape (internal::Functional_map_shape_terms)
/// \param target the reduced terms of the target shape
/// \param weights the weights of the terms
/// \param column_weights optional \f$ \omega_c \f$ (size d; empty: all 1)
/// \param inverse optional \f$ Q \f$, used when `weights.bijectivity > 0`
/// \returns \f$ C \f$, \f$ k_S \times k_T \f$.
/// \throws Invalid_parameter_error on inconsistent sizes, Numerical_error if the system is singular.
inline Eigen::MatrixXd fit_functional_map(const internal::Functional_map_shape_terms& source,
                                          const internal::Functional_map_shape_terms& target,
                                          const Functional_map_weights& weights,
                                          const Eigen::VectorXd& column_weights = Eigen::VectorXd(),
                                          const Eigen::MatrixXd* inverse = nullptr)
{
  return internal::minimize_functional_map_energy(source, target, weights, column_weights, inverse);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Converts a functional map to a point-to-point map by nearest neighbours in the spectral
/// embedding (Ovsjanikov et al. 2012): \f$ T(x) = \arg\min_y \| \Phi'_S(x)\, C - \Phi'_T(y) \| \f$,
/// with the unit-area bases \f$ \Phi' = \Phi \sqrt{A} \f$ restricted to the sizes of C.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag`
/// \param source the spectrum of the source shape (at least k_S eigenpairs)
/// \param target the spectrum of the target shape (at least k_T eigenpairs)
/// \param C the functional map, k_S x k_T (pull-back from target to source)
/// \param map output: `map[x]` is the target vertex matched to source vertex x
/// \throws Invalid_parameter_error if C is larger than the spectra.
template <typename ConcurrencyTag = CGAL::Sequential_tag>
void point_map_from_functional_map(const Laplace_beltrami_spectrum& source,
                                   const Laplace_beltrami_spectrum& target, const Eigen::MatrixXd& C,
                                   std::vector<std::size_t>& map)
{
  const int ks = static_cast<int>(C.rows()), kt = static_cast<int>(C.cols());
  if(ks < 1 || kt < 1 || ks > source.number_of_eigenpairs() || kt > target.number_of_eigenpairs())
    throw Invalid_parameter_error("point_map_from_functional_map: a " + std::to_string(ks) + " x " +
                                  std::to_string(kt) + " functional map needs spectra of at least "
                                  "as many eigenpairs (" + std::to_string(source.number_of_eigenpairs()) +
                                  " and " + std::to_string(target.number_of_eigenpairs()) + " given)");
  const Eigen::MatrixXd embedded = internal::unit_area_basis(source, ks) * C;
  std::vector<int> nearest(static_cast<std::size_t>(source.number_of_vertices()));
  internal::Nearest_neighbor_search search(internal::unit_area_basis(target, kt));
  search.query<ConcurrencyTag>(embedded, nearest.data());
  map.assign(nearest.begin(), nearest.end());
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The functional map \f$ C = \Phi_S'^{+} \Pi \Phi'_T \f$ (\f$ k_S \times k_T \f$) of a
/// point-to-point map, in the unit-area bases (\f$ \Phi'^+ = \Phi'^\top M' \f$).
///
/// \param source the spectrum of the source shape
/// \param target the spectrum of the target shape
/// \param map `map[x]` is the target vertex matched to source vertex x (size n_S)
/// \param source_size k_S, at most the number of source eigenpairs
/// \param target_size k_T, at most the number of target eigenpairs
/// \throws Invalid_map_error if the map has the wrong size or entries out of range,
///   Invalid_parameter_error if the sizes exceed the spectra.
inline Eigen::MatrixXd functional_map_from_point_map(const Laplace_beltrami_spectrum& source,
                                                     const Laplace_beltrami_spectrum& target,
                                                     const std::vector<std::size_t>& map,
                                                     int source_size, int target_size)
{
  if(source_size < 1 || target_size < 1 || source_size > source.number_of_eigenpairs() ||
     target_size > target.number_of_eigenpairs())
    throw Invalid_parameter_error("functional_map_from_point_map: sizes " + std::to_string(source_size) +
                                  " x " + std::to_string(target_size) + " exceed the spectra (" +
                                  std::to_string(source.number_of_eigenpairs()) + " and " +
                                  std::to_string(target.number_of_eigenpairs()) + " eigenpairs)");
  if(map.size() != static_cast<std::size_t>(source.number_of_vertices()))
    throw Invalid_map_error("functional_map_from_point_map: the map has " + std::to_string(map.size()) +
                            " entries for a source of " + std::to_string(source.number_of_vertices()) +
                            " vertices");
  std::vector<int> m(map.size());
  for(std::size_t i = 0; i < map.size(); ++i)
  {
    if(map[i] >= static_cast<std::size_t>(target.number_of_vertices()))
      throw Invalid_map_error("functional_map_from_point_map: map[" + std::to_string(i) + "] = " +
                              std::to_string(map[i]) + " is not a vertex of the target (" +
                              std::to_string(target.number_of_vertices()) + " vertices)");
    m[i] = static_cast<int>(map[i]);
  }
  return internal::functional_map_from_point_map(internal::unit_area_basis(source, source_size),
                                                 internal::unit_area_mass(source),
                                                 internal::unit_area_basis(target, target_size), m.data());
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_FUNCTIONAL_MAP_H
