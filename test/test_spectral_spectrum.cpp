// SPDX-License-Identifier: GPL-3.0-or-later
// The Laplace-Beltrami spectrum: analytic eigenvalues (sphere, flat square), M-orthonormality,
// components, boundaries, the sign convention, the dense and sparse solvers against each other,
// and the errors users get.

#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using namespace smc_test;

namespace {

// Largest relative error of lambda_j * area / (4 pi) against l (l + 1) for l = 1..lmax, the
// eigenvalues being taken in order (multiplicity 2 l + 1).
double sphere_error(const smc::Laplace_beltrami_spectrum& s, int lmax)
{
  double e = 0;
  int j = 1;
  for(int l = 1; l <= lmax; ++l)
    for(int m = 0; m < 2 * l + 1; ++m, ++j)
      e = std::max(e, std::abs(s.eigenvalues()[j] * s.total_area() / (4 * pi) - l * (l + 1)) /
                          (l * (l + 1)));
  return e;
}

double orthonormality_error(const smc::Laplace_beltrami_spectrum& s)
{
  const Eigen::MatrixXd& phi = s.eigenvectors();
  const Eigen::MatrixXd gram = phi.transpose() * s.mass().asDiagonal() * phi;
  return (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
}

// max_j |L phi_j - lambda_j M phi_j| / (|lambda_j| + 1) in the M^{-1} norm, area normalised.
double residual(const smc::Laplace_beltrami_spectrum& s)
{
  double r = 0;
  const double A = s.total_area();
  for(int j = 0; j < s.number_of_eigenpairs(); ++j)
  {
    const Eigen::VectorXd phi = s.eigenvectors().col(j);
    const Eigen::VectorXd res =
        s.stiffness_matrix() * phi - s.eigenvalues()[j] * s.mass().cwiseProduct(phi);
    const double norm = std::sqrt(res.cwiseAbs2().cwiseQuotient(s.mass()).sum());
    r = std::max(r, norm * A / (s.eigenvalues()[j] * A + 1));
  }
  return r;
}

// An asymmetric closed surface: a jittered ellipsoid (distinct eigenvalues, non-zero moments).
Mesh lumpy_ellipsoid(int levels)
{
  return transformed(jittered_sphere(levels, 0.3),
                     [](const Point& p) { return Point(1.3 * p.x(), p.y() + 0.2 * p.x() * p.x(), 0.8 * p.z()); });
}

// For every vertex index of `a`, the index of the vertex of `b` at the same position.
template <typename MeshB>
std::vector<int> same_vertices(const Mesh& a, const MeshB& b)
{
  const auto ia = smc::internal::make_indexed_mesh(a), ib = smc::internal::make_indexed_mesh(b);
  std::map<std::array<double, 3>, int> index_in_b;
  for(int v = 0; v < ib.number_of_vertices(); ++v)
    index_in_b[{ib.points(v, 0), ib.points(v, 1), ib.points(v, 2)}] = v;
  std::vector<int> out(ia.number_of_vertices());
  for(int v = 0; v < ia.number_of_vertices(); ++v)
    out[v] = index_in_b.at({ia.points(v, 0), ia.points(v, 1), ia.points(v, 2)});
  return out;
}


} // namespace

BOOST_AUTO_TEST_SUITE(spectrum)

BOOST_AUTO_TEST_CASE(sphere_eigenvalues_converge_to_l_times_l_plus_1)
{
  // The vertices are jittered by 2% of the edge length: on the exact icosphere the eigenvalues
  // have exact multiplicities 2l + 1, whose copies a Krylov solver finds only through rounding
  // errors (it may miss one, depending on the compiler's rounding; see doc/spectral.md).
  double previous = 1;
  for(int level : {2, 3, 4})
  {
    const smc::Laplace_beltrami_spectrum s(jittered_sphere(level, 0.02), params::number_of_eigenpairs(30));
    BOOST_TEST(s.number_of_eigenpairs() == 30);
    BOOST_TEST(s.eigenvalues()[0] == 0);
    for(int j = 1; j < 30; ++j) BOOST_TEST(s.eigenvalues()[j] >= s.eigenvalues()[j - 1]);
    const double e = sphere_error(s, 4);  // l = 0..4: the first 25 eigenvalues
    BOOST_TEST_MESSAGE("jittered icosphere level " << level << ": max relative error (l <= 4) " << e);
    BOOST_TEST(e < (level == 2 ? 0.15 : level == 3 ? 0.04 : 0.01));
    BOOST_TEST(e < 0.3 * previous);  // O(h^2): about 4 times smaller per level
    previous = e;
    // Gaps between the groups of 2l+1 are much larger than the spread inside a group.
    BOOST_TEST(s.eigenvalues()[4] / s.eigenvalues()[3] > 2.5);   // l = 2 vs l = 1
    BOOST_TEST(s.eigenvalues()[3] / s.eigenvalues()[1] < 1.01);  // inside l = 1
    BOOST_TEST(orthonormality_error(s) < 1e-10);
    BOOST_TEST(residual(s) < 1e-7);
  }
}

BOOST_AUTO_TEST_CASE(flat_square_neumann_eigenvalues)
{
  // Unit square with free boundary: lambda = pi^2 (a^2 + b^2), a, b >= 0.
  std::vector<double> exact;
  for(int a = 0; a < 8; ++a)
    for(int b = 0; b < 8; ++b) exact.push_back(pi * pi * (a * a + b * b));
  std::sort(exact.begin(), exact.end());
  double previous = 1;
  for(int n : {12, 24})
  {
    const smc::Laplace_beltrami_spectrum s(grid(n, n), params::number_of_eigenpairs(12));
    BOOST_TEST(std::abs(s.total_area() - 1) < 1e-12);
    double e = 0;
    for(int j = 1; j < 12; ++j) e = std::max(e, std::abs(s.eigenvalues()[j] - exact[j]) / exact[j]);
    BOOST_TEST_MESSAGE("grid " << n << ": max relative error of the first 12 eigenvalues " << e);
    BOOST_TEST(e < (n == 12 ? 0.08 : 0.02));
    BOOST_TEST(e < 0.35 * previous);
    previous = e;
    BOOST_TEST(orthonormality_error(s) < 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(intrinsic_delaunay_improves_sheared_spheres)
{
  // The twisted sphere is the unit sphere meshed with long obtuse triangles.
  for(int level : {3, 4})
  {
    const Mesh m = twisted_sphere(level, 3.0);
    const smc::Laplace_beltrami_spectrum plain(
        m, params::use_intrinsic_delaunay(false, params::number_of_eigenpairs(25)));
    const smc::Laplace_beltrami_spectrum idt(m, params::number_of_eigenpairs(25));
    BOOST_TEST(idt.uses_intrinsic_delaunay());
    BOOST_TEST(idt.number_of_flips() > 0);
    const double e_plain = sphere_error(plain, 4), e_idt = sphere_error(idt, 4);
    BOOST_TEST_MESSAGE("twisted sphere level " << level << ": error " << e_plain << " without, "
                                               << e_idt << " with intrinsic Delaunay");
    BOOST_TEST(e_idt < 0.2 * e_plain);
    BOOST_TEST(e_idt < 0.06);
  }
}

BOOST_AUTO_TEST_CASE(dense_and_sparse_solvers_agree)
{
  // The same problem through Spectra (shift-invert) and through the dense solver.
  const auto im = smc::internal::make_indexed_mesh(lumpy_ellipsoid(3));
  const auto lb = smc::internal::laplace_beltrami_matrices(im, true);
  smc::internal::Eigensolver_settings sparse, dense;
  sparse.dense_threshold = 0;
  dense.dense_threshold = 1000000;
  Eigen::VectorXd va, vb;
  Eigen::MatrixXd pa, pb;
  smc::internal::Eigensolver_statistics sa, sb;
  smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component, 1, 40, sparse,
                                             va, pa, &sa);
  smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component, 1, 40, dense,
                                             vb, pb, &sb);
  BOOST_TEST(sa.dense_components == 0);
  BOOST_TEST(sa.operations > 0);
  BOOST_TEST(sb.dense_components == 1);
  BOOST_TEST((va - vb).cwiseAbs().maxCoeff() < 1e-9 * vb[39]);
  // Distinct eigenvalues and the intrinsic sign rule: the same vectors, signs included.
  for(int j = 0; j < 40; ++j) BOOST_TEST((pa.col(j) - pb.col(j)).cwiseAbs().maxCoeff() < 1e-6);
}

BOOST_AUTO_TEST_CASE(two_components_of_different_size)
{
  // A unit sphere and a sphere of radius 2: eigenvalues l(l+1) and l(l+1)/4 merged; zero twice.
  // Jittered (by 2% of the edge length): no exact multiplicities, whose copies the separate and
  // the joint solves would find only through rounding errors.
  const Mesh a = jittered_sphere(3, 0.02),
             b = transformed(a, [](const Point& p) { return Point(2 * p.x(), 2 * p.y(), 2 * p.z()); });
  Mesh both = a;
  {
    Mesh shifted = transformed(b, [](const Point& p) { return Point(p.x() + 5, p.y(), p.z()); });
    both.join(shifted);
  }
  const int k = 30;
  const smc::Laplace_beltrami_spectrum s(both, params::number_of_eigenpairs(k));
  const smc::Laplace_beltrami_spectrum sa(a, params::number_of_eigenpairs(k));
  const smc::Laplace_beltrami_spectrum sb(b, params::number_of_eigenpairs(k));
  BOOST_TEST(s.number_of_components() == 2);
  BOOST_TEST(s.number_of_zero_eigenvalues() == 2);
  BOOST_TEST(s.eigenvalues()[0] == 0);
  BOOST_TEST(s.eigenvalues()[1] == 0);
  BOOST_TEST(s.eigenvalues()[2] > 0.1);
  std::vector<double> merged;
  for(int j = 0; j < k; ++j)
  {
    merged.push_back(sa.eigenvalues()[j]);
    merged.push_back(sb.eigenvalues()[j]);
  }
  std::sort(merged.begin(), merged.end());
  for(int j = 0; j < k; ++j)
    BOOST_TEST(std::abs(s.eigenvalues()[j] - merged[j]) <= 1e-9 * (1 + merged[j]));
  BOOST_TEST(std::abs(s.total_area() - sa.total_area() - sb.total_area()) < 1e-12);
  BOOST_TEST(orthonormality_error(s) < 1e-10);
  BOOST_TEST(residual(s) < 1e-7);
  // Each eigenvector lives on one component.
  const int na = static_cast<int>(num_vertices(a));
  for(int j = 0; j < k; ++j)
  {
    const double on_a = s.eigenvectors().col(j).head(na).norm(), on_b = s.eigenvectors().col(j).tail(na).norm();
    BOOST_TEST(std::min(on_a, on_b) == 0);
  }
  // The zero modes are the normalised indicator functions of the two spheres.
  BOOST_TEST(std::abs(s.eigenvectors()(0, 0) * std::sqrt(sa.total_area()) - 1) < 1e-12);
  BOOST_TEST(std::abs(s.eigenvectors()(na, 1) * std::sqrt(sb.total_area()) - 1) < 1e-12);
}

BOOST_AUTO_TEST_CASE(open_surfaces)
{
  // An open tube of radius 1 and length 4 with free ends: lambda = (pi a / 4)^2 + b^2 (b is the
  // angular frequency, twice for b > 0); the first ones are 0, (pi/4)^2, 1, 1, 1 + (pi/4)^2 (twice).
  const smc::Laplace_beltrami_spectrum s(tube(48, 48), params::number_of_eigenpairs(6));
  const double q = std::pow(pi / 4, 2);
  const double exact[] = {0, q, 1, 1, 1 + q, 1 + q};
  for(int j = 1; j < 6; ++j) BOOST_TEST(std::abs(s.eigenvalues()[j] - exact[j]) / exact[j] < 0.02);
  BOOST_TEST(orthonormality_error(s) < 1e-10);
}

BOOST_AUTO_TEST_CASE(surface_mesh_and_polyhedron_agree)
{
  const Mesh m = lumpy_ellipsoid(2);
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(m, p);
  const smc::Laplace_beltrami_spectrum a(m, params::number_of_eigenpairs(20));
  const smc::Laplace_beltrami_spectrum b(p, params::number_of_eigenpairs(20));
  BOOST_TEST((a.eigenvalues() - b.eigenvalues()).cwiseAbs().maxCoeff() < 1e-10 * a.eigenvalues()[19]);
  // Same eigenvectors (signs included) once the vertices are matched by position.
  const std::vector<int> to_b = same_vertices(m, p);
  double worst = 0;
  for(int i = 0; i < a.number_of_vertices(); ++i)
    worst = std::max(worst, (a.eigenvectors().row(i) - b.eigenvectors().row(to_b[i])).cwiseAbs().maxCoeff());
  BOOST_TEST(worst < 1e-7);
}

BOOST_AUTO_TEST_CASE(signs_are_deterministic_and_intrinsic)
{
  const Mesh m = lumpy_ellipsoid(3);
  const int k = 30;
  const smc::Laplace_beltrami_spectrum a(m, params::number_of_eigenpairs(k));
  const smc::Laplace_beltrami_spectrum again(m, params::number_of_eigenpairs(k));
  BOOST_TEST((a.eigenvalues() - again.eigenvalues()).norm() == 0);
  BOOST_TEST((a.eigenvectors() - again.eigenvectors()).norm() == 0);

  // The convention itself: positive third moment (all are significant on this asymmetric shape).
  const double sqrt_area = std::sqrt(a.total_area());
  for(int j = 0; j < k; ++j)
  {
    const double moment = (a.mass().array() * a.eigenvectors().col(j).array().cube()).sum();
    BOOST_TEST(moment * sqrt_area > smc::internal::sign_moment_threshold);
  }

  // Renumbering the vertices (another vertex index map) renumbers the eigenvectors and keeps
  // their signs: the rule does not depend on the vertex order.
  const int n = static_cast<int>(num_vertices(m));
  std::vector<int> permutation(n);
  for(int i = 0; i < n; ++i) permutation[i] = (7 * i + 3) % n;  // n = 642 is coprime with 7
  Mesh copy = m;
  auto index = copy.add_property_map<Vertex, std::size_t>("v:renumbered", 0).first;
  for(Vertex v : copy.vertices()) index[v] = static_cast<std::size_t>(permutation[v.idx()]);
  const smc::Laplace_beltrami_spectrum b(copy, params::number_of_eigenpairs(k).vertex_index_map(index));
  BOOST_TEST((a.eigenvalues() - b.eigenvalues()).cwiseAbs().maxCoeff() < 1e-10 * a.eigenvalues()[k - 1]);
  double worst = 0;
  for(int j = 0; j < k; ++j)
    for(int i = 0; i < n; ++i) worst = std::max(worst, std::abs(a.eigenvectors()(i, j) - b.eigenvectors()(permutation[i], j)));
  BOOST_TEST(worst < 1e-6);

  // The fall-back rule on functions with no third moment: odd functions on a symmetric shape.
  Eigen::MatrixXd odd(4, 2);
  odd << 0.5, -0.2, -0.5, 0.2, 0.1, -0.3, -0.1, 0.3;
  const Eigen::VectorXd mass = Eigen::VectorXd::Ones(4);
  smc::internal::fix_eigenvector_signs(odd, mass, 4.0);
  BOOST_TEST(odd(0, 0) == 0.5);   // largest magnitude first found at vertex 0: kept positive
  BOOST_TEST(odd(2, 1) == 0.3);   // largest magnitude first at vertex 2: flipped to positive
  BOOST_TEST(odd(3, 1) == -0.3);
}

BOOST_AUTO_TEST_CASE(uniform_scaling)
{
  const Mesh m = lumpy_ellipsoid(2);
  const double s = 3.0;
  const Mesh big = transformed(m, [s](const Point& p) { return Point(s * p.x(), s * p.y(), s * p.z()); });
  const smc::Laplace_beltrami_spectrum a(m, params::number_of_eigenpairs(20));
  const smc::Laplace_beltrami_spectrum b(big, params::number_of_eigenpairs(20));
  BOOST_TEST(std::abs(b.total_area() - s * s * a.total_area()) < 1e-10 * b.total_area());
  BOOST_TEST((b.eigenvalues() * s * s - a.eigenvalues()).cwiseAbs().maxCoeff() < 1e-9 * a.eigenvalues()[19]);
  BOOST_TEST((b.eigenvectors() * s - a.eigenvectors()).cwiseAbs().maxCoeff() < 1e-6);
}

BOOST_AUTO_TEST_CASE(bad_input_is_reported)
{
  const Mesh sphere = icosphere(1);  // 42 vertices
  // Number of eigenpairs.
  for(int k : {0, -3, 42, 100})
  {
    const std::string e = error_of<smc::Invalid_parameter_error>(
        [&] { smc::Laplace_beltrami_spectrum s(sphere, params::number_of_eigenpairs(k)); });
    BOOST_TEST(contains(e, "number_of_eigenpairs"), e);
  }
  // The default (100) is reduced on small meshes.
  BOOST_TEST(smc::Laplace_beltrami_spectrum(sphere).number_of_eigenpairs() == 41);
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] {
                        smc::Laplace_beltrami_spectrum s(sphere, params::eigen_shift(0.5));
                      }),
                      "eigen_shift"));
  // Meshes.
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([] { smc::Laplace_beltrami_spectrum s{Mesh()}; }),
                      "empty"));
  Mesh quad;
  {
    const Vertex a = quad.add_vertex(Point(0, 0, 0)), b = quad.add_vertex(Point(1, 0, 0)),
                 c = quad.add_vertex(Point(1, 1, 0)), d = quad.add_vertex(Point(0, 1, 0));
    quad.add_face(a, b, c, d);
  }
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::Laplace_beltrami_spectrum s(quad); }),
                      "triangle"));
  Mesh isolated = sphere;
  isolated.add_vertex(Point(3, 3, 3));
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::Laplace_beltrami_spectrum s(isolated); }),
                      "isolated"));
  Mesh degenerate = sphere;
  {
    const Vertex a = degenerate.add_vertex(Point(5, 0, 0)), b = degenerate.add_vertex(Point(6, 0, 0)),
                 c = degenerate.add_vertex(Point(7, 0, 0));
    degenerate.add_face(a, b, c);
  }
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::Laplace_beltrami_spectrum s(degenerate); }),
                      "degenerate"));
  Mesh nan_mesh = sphere;
  nan_mesh.point(*nan_mesh.vertices().begin()) = Point(0, std::nan(""), 0);
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::Laplace_beltrami_spectrum s(nan_mesh); }),
                      "non-finite"));
}

BOOST_AUTO_TEST_CASE(indexed_mesh_constructor)
{
  const Mesh m = lumpy_ellipsoid(2);
  const auto im = smc::internal::make_indexed_mesh(m);
  const smc::Laplace_beltrami_spectrum a(m, params::number_of_eigenpairs(15));
  const smc::Laplace_beltrami_spectrum b(im, params::number_of_eigenpairs(15));
  BOOST_TEST((a.eigenvalues() - b.eigenvalues()).norm() == 0);
  BOOST_TEST((a.eigenvectors() - b.eigenvectors()).norm() == 0);
  BOOST_TEST(b.number_of_vertices() == im.number_of_vertices());
  BOOST_TEST(std::abs(b.total_area() - im.total_area) < 1e-12 * im.total_area);
  // A flat copy that was allowed to keep an isolated vertex is refused.
  Mesh isolated = m;
  isolated.add_vertex(Point(4, 4, 4));
  smc::internal::Mesh_requirements lenient;
  lenient.allow_isolated_vertices = true;
  const auto loose = smc::internal::make_indexed_mesh(isolated, params::default_values(), lenient);
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::Laplace_beltrami_spectrum s(loose); }),
                      "isolated"));
}

BOOST_AUTO_TEST_CASE(leading_eigenpairs_of_a_larger_spectrum)
{
  // Taking the first k eigenpairs of a spectrum of 2k gives the spectrum computed with k, up to
  // the solver's tolerance (signs included: the convention does not depend on k).
  const Mesh m = lumpy_ellipsoid(3);
  const smc::Laplace_beltrami_spectrum large(m, params::number_of_eigenpairs(60));
  const smc::Laplace_beltrami_spectrum direct(m, params::number_of_eigenpairs(30));
  const smc::Laplace_beltrami_spectrum taken(large, 30);
  BOOST_TEST(taken.number_of_eigenpairs() == 30);
  BOOST_TEST((taken.eigenvalues() - large.eigenvalues().head(30)).norm() == 0);
  BOOST_TEST((taken.eigenvalues() - direct.eigenvalues()).cwiseAbs().maxCoeff() < 1e-9 * direct.eigenvalues()[29]);
  BOOST_TEST((taken.eigenvectors() - direct.eigenvectors()).cwiseAbs().maxCoeff() < 1e-6);
  BOOST_TEST((taken.mass() - direct.mass()).norm() == 0);
  BOOST_TEST((taken.stiffness_matrix() - direct.stiffness_matrix()).norm() == 0);
  BOOST_TEST(taken.total_area() == direct.total_area());
  BOOST_TEST(taken.uses_intrinsic_delaunay() == direct.uses_intrinsic_delaunay());
  BOOST_TEST(taken.number_of_flips() == direct.number_of_flips());
  BOOST_TEST(orthonormality_error(taken) < 1e-8);
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] { smc::Laplace_beltrami_spectrum s(large, 61); }),
                      "cannot take 61 eigenpairs from a spectrum of 60"));
  BOOST_CHECK_THROW(smc::Laplace_beltrami_spectrum(large, 0), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(non_convergence_is_a_numerical_error)
{
  // Two restarts with a Krylov space barely larger than k cannot converge to 1e-14.
  const auto im = smc::internal::make_indexed_mesh(icosphere(3));
  const auto lb = smc::internal::laplace_beltrami_matrices(im, true);
  smc::internal::Eigensolver_settings settings;
  settings.dense_threshold = 0;
  settings.krylov_dimension = 42;
  settings.max_restarts = 2;
  settings.tolerance = 1e-15;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  const std::string e = error_of<smc::Numerical_error>([&] {
    smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component, 1, 40,
                                               settings, values, vectors);
  });
  BOOST_TEST(contains(e, "of the 40 requested eigenpairs converged"), e);
}

BOOST_AUTO_TEST_SUITE_END()
