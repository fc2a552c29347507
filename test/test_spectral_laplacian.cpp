// SPDX-License-Identifier: GPL-3.0-or-later
// The cotangent Laplace-Beltrami matrices and the intrinsic Delaunay flips: algebraic
// properties, exactness on linear functions, agreement with CGAL's planar Delaunay triangulation.

#include <CGAL/Surface_mesh_correspondence/laplacian.h>

#include "test_meshes.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <Eigen/Eigenvalues>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <array>
#include <map>
#include <set>
#include <utility>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using namespace smc_test;

namespace {

typedef Eigen::SparseMatrix<double> Sparse;

double max_off_diagonal(const Sparse& L)
{
  double m = -1e300;
  for(Eigen::Index j = 0; j < L.outerSize(); ++j)
    for(Sparse::InnerIterator it(L, j); it; ++it)
      if(it.row() != it.col()) m = std::max(m, it.value());
  return m;
}

std::set<std::pair<int, int> > off_diagonal_pattern(const Sparse& L, double threshold = 0)
{
  std::set<std::pair<int, int> > s;
  for(Eigen::Index j = 0; j < L.outerSize(); ++j)
    for(Sparse::InnerIterator it(L, j); it; ++it)
      if(it.row() < it.col() && std::abs(it.value()) > threshold)
        s.insert(std::make_pair(static_cast<int>(it.row()), static_cast<int>(it.col())));
  return s;
}

// Unit-square grid whose interior vertices are moved by up to `amount` grid steps (boundary
// vertices stay on the square); deterministic.
Mesh jittered_grid(int n, double amount)
{
  Mesh g = grid(n, n);
  unsigned state = 777u;
  auto next = [&state]() {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (2.0 / 16777216.0) - 1.0;
  };
  const double h = 1.0 / n;
  return transformed(g, [&](const Point& p) {
    const double dx = amount * h * next(), dy = amount * h * next();
    const bool boundary = p.x() < 1e-9 || p.x() > 1 - 1e-9 || p.y() < 1e-9 || p.y() > 1 - 1e-9;
    return boundary ? p : Point(p.x() + dx, p.y() + dy, 0);
  });
}

// Checks the properties every cotangent Laplacian has.
void check_basic_properties(const smc::Laplace_beltrami_matrices& lb, double area)
{
  const Sparse& L = lb.stiffness_matrix;
  const Eigen::Index n = L.rows();
  BOOST_TEST(L.cols() == n);
  BOOST_TEST((Sparse(L.transpose()) - L).norm() <= 1e-12 * L.norm());
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  BOOST_TEST((L * ones).cwiseAbs().maxCoeff() <= 1e-12 * L.diagonal().cwiseAbs().maxCoeff());
  BOOST_TEST(std::abs(lb.mass.sum() - area) <= 1e-12 * area);
  BOOST_TEST(lb.mass.minCoeff() > 0);
  BOOST_TEST((Eigen::VectorXd(lb.mass_matrix.diagonal()) - lb.mass).norm() == 0);
  BOOST_TEST(lb.mass_matrix.nonZeros() == n);
}

} // namespace

BOOST_AUTO_TEST_SUITE(laplacian)

BOOST_AUTO_TEST_CASE(symmetric_zero_row_sums_positive_semidefinite)
{
  for(const Mesh& m : {icosphere(2), twisted_sphere(2, 3.0), grid(6, 5), tube(12, 6)})
    for(bool idt : {false, true})
    {
      const auto im = smc::internal::make_indexed_mesh(m);
      const auto lb = smc::laplace_beltrami_matrices(m, params::use_intrinsic_delaunay(idt));
      check_basic_properties(lb, im.total_area);
      // Positive semi-definite with a one-dimensional kernel (connected meshes).
      const Eigen::MatrixXd dense = Eigen::MatrixXd(lb.stiffness_matrix);
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
      BOOST_TEST(ev[0] >= -1e-10 * ev[ev.size() - 1]);
      BOOST_TEST(ev[1] > 1e-6 * ev[ev.size() - 1]);
    }
}

BOOST_AUTO_TEST_CASE(linear_functions_are_reproduced_on_flat_meshes)
{
  // For a linear f on a flat mesh, (L f)_i = 0 at interior vertices and f^T L f is the Dirichlet
  // energy |grad f|^2 * area, with or without flips (the intrinsic triangulation of a flat
  // domain is a planar triangulation, on which f is still linear).
  const Mesh g = jittered_grid(8, 0.35);
  const auto im = smc::internal::make_indexed_mesh(g);
  for(bool idt : {false, true})
  {
    const auto lb = smc::laplace_beltrami_matrices(g, params::use_intrinsic_delaunay(idt));
    check_basic_properties(lb, 1.0);
    Eigen::VectorXd f(im.number_of_vertices());
    for(int v = 0; v < im.number_of_vertices(); ++v) f[v] = 2.0 * im.points(v, 0) - 0.5 * im.points(v, 1);
    const Eigen::VectorXd Lf = lb.stiffness_matrix * f;
    for(int v = 0; v < im.number_of_vertices(); ++v)
    {
      const double x = im.points(v, 0), y = im.points(v, 1);
      if(x > 1e-9 && x < 1 - 1e-9 && y > 1e-9 && y < 1 - 1e-9) BOOST_TEST(std::abs(Lf[v]) < 1e-12);
    }
    BOOST_TEST(f.dot(Lf) == 4.25, boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(flip_of_a_kite_matches_the_other_diagonal)
{
  // A flat kite i=(0,0), j=(2,0), k=(1,0.3), l=(1,-0.3) triangulated along the long diagonal ij
  // (both opposite angles obtuse) must become the kite triangulated along kl; folding the kite
  // along ij changes nothing intrinsically.
  for(double fold : {0.0, 1.0})
  {
    const double c = std::cos(fold), s = std::sin(fold);
    const std::vector<Point> pts = {Point(0, 0, 0), Point(2, 0, 0), Point(1, 0.3 * c, 0.3 * s),
                                    Point(1, -0.3, 0)};
    const Mesh long_diagonal = mesh_from_soup(pts, {{0, 1, 2}, {1, 0, 3}});
    const Mesh short_diagonal = mesh_from_soup(
        {Point(0, 0, 0), Point(2, 0, 0), Point(1, 0.3, 0), Point(1, -0.3, 0)}, {{0, 3, 2}, {3, 1, 2}});
    const auto a = smc::laplace_beltrami_matrices(long_diagonal, params::use_intrinsic_delaunay(true));
    const auto b = smc::laplace_beltrami_matrices(short_diagonal, params::use_intrinsic_delaunay(false));
    const auto plain =
        smc::laplace_beltrami_matrices(long_diagonal, params::use_intrinsic_delaunay(false));
    BOOST_TEST(a.number_of_flips == 1);
    BOOST_TEST(max_off_diagonal(plain.stiffness_matrix) > 0);  // the long diagonal's weight < 0
    BOOST_TEST((Eigen::MatrixXd(a.stiffness_matrix) - Eigen::MatrixXd(b.stiffness_matrix)).norm() < 1e-12);
    BOOST_TEST(a.stiffness_matrix.coeff(0, 1) == 0);
    BOOST_TEST(a.stiffness_matrix.coeff(2, 3) < 0);
  }
}

BOOST_AUTO_TEST_CASE(intrinsic_delaunay_of_a_planar_domain_is_the_delaunay_triangulation)
{
  // On a flat convex domain the intrinsic Delaunay triangulation is the Delaunay triangulation
  // of the vertices: compare the edges (non-zero pattern of L) with CGAL's Delaunay_triangulation_2.
  typedef CGAL::Delaunay_triangulation_2<Kernel> DT;
  typedef Kernel::Point_2 Point_2;
  const Mesh g = jittered_grid(12, 0.4);
  const auto im = smc::internal::make_indexed_mesh(g);
  std::vector<std::pair<Point_2, int> > pts;
  for(int v = 0; v < im.number_of_vertices(); ++v) pts.emplace_back(Point_2(im.points(v, 0), im.points(v, 1)), v);
  DT dt;
  std::map<Point_2, int> index;
  for(const auto& p : pts)
  {
    dt.insert(p.first);
    index[p.first] = p.second;
  }
  std::set<std::pair<int, int> > reference;
  for(auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e)
  {
    const int a = index[e->first->vertex(DT::cw(e->second))->point()];
    const int b = index[e->first->vertex(DT::ccw(e->second))->point()];
    reference.insert(std::make_pair(std::min(a, b), std::max(a, b)));
  }
  const auto plain = smc::laplace_beltrami_matrices(g, params::use_intrinsic_delaunay(false));
  const auto idt = smc::laplace_beltrami_matrices(g, params::use_intrinsic_delaunay(true));
  BOOST_TEST(idt.number_of_flips > 10);
  BOOST_TEST(max_off_diagonal(plain.stiffness_matrix) > 1e-3);
  BOOST_TEST(max_off_diagonal(idt.stiffness_matrix) <= 1e-12);
  // Edges of zero weight (co-circular pairs) may be absent from either side: none here.
  const auto pattern = off_diagonal_pattern(idt.stiffness_matrix, 1e-12);
  BOOST_TEST(pattern.size() == reference.size());
  BOOST_TEST((pattern == reference));
}

BOOST_AUTO_TEST_CASE(flips_make_every_weight_non_negative)
{
  for(const Mesh& m : {twisted_sphere(3, 3.0), twisted_sphere(3, 6.0), jittered_sphere(3, 0.45)})
  {
    const auto plain = smc::laplace_beltrami_matrices(m, params::use_intrinsic_delaunay(false));
    const auto idt = smc::laplace_beltrami_matrices(m);  // the default
    BOOST_TEST(max_off_diagonal(plain.stiffness_matrix) > 1e-3);
    BOOST_TEST(idt.number_of_flips > 0);
    // cot alpha + cot beta >= -1e-12 is guaranteed; weights are half of that.
    BOOST_TEST(max_off_diagonal(idt.stiffness_matrix) <= 1e-12);
    // The mass does not depend on the triangulation.
    BOOST_TEST((idt.mass - plain.mass).norm() == 0);
    check_basic_properties(idt, plain.mass.sum());
  }
}

BOOST_AUTO_TEST_CASE(delaunay_meshes_are_unchanged)
{
  // Icospheres and staggered tubes are Delaunay already: no flip, the same matrix.
  for(const Mesh& m : {icosphere(3), tube(16, 8)})
  {
    const auto plain = smc::laplace_beltrami_matrices(m, params::use_intrinsic_delaunay(false));
    const auto idt = smc::laplace_beltrami_matrices(m, params::use_intrinsic_delaunay(true));
    BOOST_TEST(idt.number_of_flips == 0);
    BOOST_TEST((Sparse(idt.stiffness_matrix - plain.stiffness_matrix)).norm() == 0);
  }
}

BOOST_AUTO_TEST_CASE(surface_mesh_and_polyhedron_agree)
{
  const Mesh s = twisted_sphere(2, 3.0);
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(s, p);
  const auto a = smc::laplace_beltrami_matrices(s);
  const auto b = smc::laplace_beltrami_matrices(p);
  // The vertex orders differ: match the vertices by position, then compare entry by entry. The
  // flips happen in another order, but the intrinsic Delaunay Laplacian is unique.
  const auto ia = smc::internal::make_indexed_mesh(s), ib = smc::internal::make_indexed_mesh(p);
  std::map<std::array<double, 3>, int> index_in_b;
  for(int v = 0; v < ib.number_of_vertices(); ++v)
    index_in_b[{ib.points(v, 0), ib.points(v, 1), ib.points(v, 2)}] = v;
  const int n = ia.number_of_vertices();
  Eigen::VectorXi to_b(n);
  for(int v = 0; v < n; ++v) to_b[v] = index_in_b.at({ia.points(v, 0), ia.points(v, 1), ia.points(v, 2)});
  const Eigen::MatrixXd la = Eigen::MatrixXd(a.stiffness_matrix), lb = Eigen::MatrixXd(b.stiffness_matrix);
  double worst = 0;
  for(int i = 0; i < n; ++i)
  {
    BOOST_TEST(std::abs(a.mass[i] - b.mass[to_b[i]]) < 1e-15);
    for(int j = 0; j < n; ++j) worst = std::max(worst, std::abs(la(i, j) - lb(to_b[i], to_b[j])));
  }
  BOOST_TEST(worst < 1e-12 * la.cwiseAbs().maxCoeff());
}

BOOST_AUTO_TEST_CASE(bad_meshes_throw)
{
  auto throws_mesh_error = [](const Mesh& m) {
    try
    {
      smc::laplace_beltrami_matrices(m);
    }
    catch(const smc::Invalid_mesh_error&)
    {
      return true;
    }
    return false;
  };
  BOOST_TEST(throws_mesh_error(Mesh()));
  Mesh nan_mesh = icosphere(1);
  nan_mesh.point(*nan_mesh.vertices().begin()) = Point(std::nan(""), 0, 0);
  BOOST_TEST(throws_mesh_error(nan_mesh));
  Mesh isolated = icosphere(1);
  isolated.add_vertex(Point(5, 5, 5));
  BOOST_TEST(throws_mesh_error(isolated));
  BOOST_TEST(throws_mesh_error(mesh_from_soup({Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0)}, {{0, 1, 2}})));
}

BOOST_AUTO_TEST_SUITE_END()
