// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Operators induced by a scalar function f (a descriptor), written in a reduced basis Phi
// (n x k, M-orthonormal), for the commutativity terms of functional maps:
//
// - the multiplication operator g -> f g (Nogneng and Ovsjanikov 2017):
//     X_f = Phi^T M diag(f) Phi                                      (k x k, symmetric);
// - the orientation operator g -> <n, grad f x grad g> (Ren, Poulenard, Liu, Melzi and
//   Ovsjanikov 2018), evaluated per triangle and integrated against the basis:
//     O_f(i, j) = sum_t a_t * mean_{v in t} phi_i(v) * <n_t, grad_t f x grad_t phi_j>.
//   The gradient of a piecewise linear function on the triangle t = (a, b, c) with unit normal
//   n_t and area a_t is grad_t f = sum_v f_v (n_t x e_v) / (2 a_t), with e_v the edge opposite v
//   (counter-clockwise). A map that preserves orientation commutes with O_f; one that reverses
//   it anti-commutes. Optionally grad f is normalised per triangle (only its direction is used).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_ORIENTATION_OPERATOR_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_ORIENTATION_OPERATOR_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <Eigen/Core>

#include <cmath>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Per-triangle data shared by the orientation operators of one shape and one basis.
struct Reduced_operator_geometry
{
  /// Per triangle t and corner c, the vector n_t x e_c / (2 a_t) (the gradient of the hat
  /// function of corner c): f x 9, row t = (g_0, g_1, g_2).
  Eigen::Matrix<double, Eigen::Dynamic, 9, Eigen::RowMajor> hat_gradients;
  /// Unit triangle normals, f x 3.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> normals;
  /// diag(a_t) times the mean of the basis over the corners of t: f x k.
  Eigen::MatrixXd weighted_face_basis;
  /// The basis itself (n x k), M-orthonormal for the mass used by the caller.
  Eigen::MatrixXd basis;
  /// The lumped vertex masses (n).
  Eigen::VectorXd mass;
};

/// Precomputes the triangle data of `mesh` for the basis `basis` (n x k). `length_scale`
/// multiplies every coordinate (e.g. 1 / sqrt(area) to work at unit area); `face_area_scale`
/// multiplies the triangle areas in the integrals (the same normalisation as `mass`).
inline Reduced_operator_geometry reduced_operator_geometry(const Indexed_mesh& mesh,
                                                           const Eigen::MatrixXd& basis,
                                                           const Eigen::VectorXd& mass,
                                                           double length_scale,
                                                           double face_area_scale)
{
  Reduced_operator_geometry g;
  const int nf = mesh.number_of_triangles();
  const Eigen::Index k = basis.cols();
  g.hat_gradients.resize(nf, 9);
  g.normals.resize(nf, 3);
  g.weighted_face_basis.resize(nf, k);
  g.basis = basis;
  g.mass = mass;
  const std::vector<char> oriented = oriented_triangles(mesh);
  for(int t = 0; t < nf; ++t)
  {
    if(!oriented[std::size_t(t)])
    {
      // No orientation (degenerate, or on a non-manifold edge): no contribution.
      g.normals.row(t).setZero();
      g.hat_gradients.row(t).setZero();
      g.weighted_face_basis.row(t).setZero();
      continue;
    }
    const int v[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    const Eigen::Vector3d p[3] = {mesh.point(v[0]) * length_scale, mesh.point(v[1]) * length_scale,
                                  mesh.point(v[2]) * length_scale};
    const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double twice_area = cross.norm();
    const Eigen::Vector3d n = cross / twice_area;
    g.normals.row(t) = n.transpose();
    for(int c = 0; c < 3; ++c)
    {
      const Eigen::Vector3d e = p[(c + 2) % 3] - p[(c + 1) % 3];  // edge opposite corner c
      const Eigen::Vector3d grad = n.cross(e) / twice_area;
      g.hat_gradients.block<1, 3>(t, 3 * c) = grad.transpose();
    }
    const double weight = mesh.triangle_areas[t] * face_area_scale / 3.0;
    g.weighted_face_basis.row(t) =
        weight * (basis.row(v[0]) + basis.row(v[1]) + basis.row(v[2]));
  }
  return g;
}

/// The orientation operator O_f (k x k) of the vertex function `f` in the basis of `g`.
/// With `normalize_gradient`, grad f is replaced by grad f / |grad f| on every triangle (0 where
/// it vanishes).
inline Eigen::MatrixXd reduced_orientation_operator(const Indexed_mesh& mesh,
                                                    const Reduced_operator_geometry& g,
                                                    const Eigen::Ref<const Eigen::VectorXd>& f,
                                                    bool normalize_gradient)
{
  const int nf = mesh.number_of_triangles();
  const Eigen::Index k = g.basis.cols();
  // values(t, j) = <n_t, grad f x grad phi_j> = <n_t x grad f, grad phi_j>
  //              = sum_c <w_t, hat_gradient_c> phi_j(v_c),  w_t = n_t x grad_t f.
  Eigen::MatrixXd values(nf, k);
  for(int t = 0; t < nf; ++t)
  {
    const int v[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    Eigen::Vector3d grad_f = Eigen::Vector3d::Zero();
    for(int c = 0; c < 3; ++c)
      grad_f += f[v[c]] * g.hat_gradients.block<1, 3>(t, 3 * c).transpose();
    if(normalize_gradient)
    {
      const double length = grad_f.norm();
      grad_f = length > 0 ? Eigen::Vector3d(grad_f / length) : Eigen::Vector3d::Zero();
    }
    const Eigen::Vector3d w = g.normals.row(t).transpose().cross(grad_f);
    double alpha[3];
    for(int c = 0; c < 3; ++c) alpha[c] = w.dot(g.hat_gradients.block<1, 3>(t, 3 * c).transpose());
    values.row(t) = alpha[0] * g.basis.row(v[0]) + alpha[1] * g.basis.row(v[1]) +
                    alpha[2] * g.basis.row(v[2]);
  }
  return g.weighted_face_basis.transpose() * values;
}

/// The multiplication operator X_f = Phi^T M diag(f) Phi (k x k) of the vertex function `f`.
inline Eigen::MatrixXd reduced_multiplication_operator(const Reduced_operator_geometry& g,
                                                       const Eigen::Ref<const Eigen::VectorXd>& f)
{
  const Eigen::VectorXd weights = g.mass.cwiseProduct(f);
  return g.basis.transpose() * (weights.asDiagonal() * g.basis);
}

/// Orientation-sensitive scalar descriptors: for each pair (f, g) of columns of `functions`
/// (n x d), the vertex function <n, grad f x grad g> (the area-weighted mean over the incident
/// triangles that have an orientation, oriented_triangles()), with coordinates multiplied by
/// `length_scale`. The value changes sign under an
/// orientation-reversing isometry, so these descriptors tell a shape from its mirror image, which
/// intrinsic descriptors (WKS, HKS) cannot. Returns n x (number of pairs).
inline Eigen::MatrixXd gradient_cross_products(const Indexed_mesh& mesh, const Eigen::MatrixXd& functions,
                                               const std::vector<std::pair<int, int> >& pairs,
                                               double length_scale)
{
  const int n = mesh.number_of_vertices();
  const Eigen::Index p = static_cast<Eigen::Index>(pairs.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, p);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
  Eigen::Matrix<double, 3, Eigen::Dynamic> gradients(3, functions.cols());
  const std::vector<char> oriented = oriented_triangles(mesh);
  for(int t = 0; t < mesh.number_of_triangles(); ++t)
  {
    if(!oriented[std::size_t(t)]) continue;  // degenerate, or on a non-manifold edge
    const int v[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    const Eigen::Vector3d q[3] = {mesh.point(v[0]) * length_scale, mesh.point(v[1]) * length_scale,
                                  mesh.point(v[2]) * length_scale};
    const Eigen::Vector3d cross = (q[1] - q[0]).cross(q[2] - q[0]);
    const double twice_area = cross.norm();
    const Eigen::Vector3d normal = cross / twice_area;
    gradients.setZero();
    for(int c = 0; c < 3; ++c)
    {
      const Eigen::Vector3d hat = normal.cross(q[(c + 2) % 3] - q[(c + 1) % 3]) / twice_area;
      gradients.noalias() += hat * functions.row(v[c]);
    }
    const double area = mesh.triangle_areas[t];
    for(Eigen::Index k = 0; k < p; ++k)
    {
      const double value = normal.dot(gradients.col(pairs[k].first).cross(gradients.col(pairs[k].second)));
      for(int c = 0; c < 3; ++c) out(v[c], k) += area * value;
    }
    for(int c = 0; c < 3; ++c) weight[v[c]] += area;
  }
  for(int i = 0; i < n; ++i)
    if(weight[i] > 0) out.row(i) /= weight[i];
  return out;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_ORIENTATION_OPERATOR_H
