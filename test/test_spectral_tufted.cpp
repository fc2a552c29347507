// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The tufted Laplacian (Sharp and Crane 2020) on non-manifold meshes: equal to the intrinsic
// Delaunay Laplacian on closed manifold meshes, symmetric, positive semi-definite with one zero
// eigenvalue per component on fins, touching sheets and pinched vertices, and converging to the
// analytic spectrum of an open book of three pages; the wedges around an edge follow the angles
// even past a triangle of zero area, and meshes that need the cover get this Laplacian.

#include <CGAL/Surface_mesh_correspondence/laplacian.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/internal/tufted_cover.h>

#include "test_meshes.h"

#include <Eigen/Eigenvalues>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using namespace smc_test;

namespace {

typedef Eigen::SparseMatrix<double> Sparse;

/// The sorted generalised eigenvalues of L x = lambda M x (dense).
Eigen::VectorXd spectrum_of(const smc::Laplace_beltrami_matrices& lb)
{
  const Eigen::MatrixXd L(lb.stiffness_matrix), M(lb.mass_matrix);
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(L, M, Eigen::EigenvaluesOnly).eigenvalues();
}

/// The properties of a Laplacian on a mesh with `components` components and area `area`.
void check_laplacian(const smc::Laplace_beltrami_matrices& lb, double area, int components)
{
  const Sparse& L = lb.stiffness_matrix;
  const Eigen::Index n = L.rows();
  BOOST_TEST((Sparse(L.transpose()) - L).norm() <= 1e-12 * L.norm());
  BOOST_TEST((L * Eigen::VectorXd::Ones(n)).cwiseAbs().maxCoeff() <= 1e-12 * L.diagonal().cwiseAbs().maxCoeff());
  double max_off = -1e300;
  for(Eigen::Index j = 0; j < L.outerSize(); ++j)
    for(Sparse::InnerIterator it(L, j); it; ++it)
      if(it.row() != it.col()) max_off = std::max(max_off, it.value());
  BOOST_TEST(max_off <= 1e-12);  // intrinsic Delaunay on the cover: every weight non-negative
  BOOST_TEST(std::abs(lb.mass.sum() - area) <= 1e-12 * area);
  BOOST_TEST(lb.mass.minCoeff() > 0);
  const Eigen::VectorXd ev = spectrum_of(lb);
  const double top = ev[ev.size() - 1];
  BOOST_TEST(ev[0] >= -1e-10 * top);
  for(int k = 0; k < components; ++k) BOOST_TEST(std::abs(ev[k]) <= 1e-10 * top);
  BOOST_TEST(ev[components] > 1e-6 * top);
}

} // namespace

BOOST_AUTO_TEST_SUITE(tufted_laplacian)

BOOST_AUTO_TEST_CASE(the_cover_doubles_every_triangle_and_glues_every_edge_twice)
{
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3> > triangles;
  smc_test::add_book(3, 2, points, triangles);
  const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
  const smc::internal::Intrinsic_triangulation t = smc::internal::tufted_cover(m);
  BOOST_TEST(t.number_of_triangles() == 2 * m.number_of_triangles());
  for(int h = 0; h < t.number_of_halfedges(); ++h)
  {
    const int o = t.twin[std::size_t(h)];
    BOOST_TEST_REQUIRE(o >= 0);  // closed
    BOOST_TEST(t.twin[std::size_t(o)] == h);
    BOOST_TEST(t.origin[std::size_t(o)] == t.target(h));  // consistently oriented
    BOOST_TEST(t.length[std::size_t(o)] == t.length[std::size_t(h)]);
  }
}

// Around an edge, the wedges pair the triangles in the order of their angles about it, also when
// the first triangle has zero area (its third vertex on the edge's line, so no direction): four
// pages at 0, 200, 90 and 300 degrees are glued 0-90, 90-200, 200-300, 300-0, not in index order.
BOOST_AUTO_TEST_CASE(the_wedges_follow_the_angles_when_a_triangle_has_zero_area)
{
  std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}};
  std::vector<std::array<int, 3> > triangles = {{{0, 1, 2}}};  // zero area, first around (0, 1)
  const double degrees[] = {0, 200, 90, 300};
  for(int p = 0; p < 4; ++p)
  {
    const double a = degrees[p] * CGAL_PI / 180;
    points.emplace_back(std::cos(a), std::sin(a), 0.5);
    if(p % 2 == 0)
      triangles.push_back({{0, 1, 3 + p}});
    else
      triangles.push_back({{1, 0, 3 + p}});
  }
  const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles, true);
  BOOST_TEST((m.degenerate_faces == std::vector<int>{0}));
  const smc::internal::Intrinsic_triangulation t = smc::internal::tufted_cover(m);
  // The faces glued across the edge (0, 1), each wedge once; the zero-area face 0 lies in one
  // wedge, between two pages: that wedge counts as glueing those two.
  std::vector<std::array<int, 2> > glued, through_zero;
  for(int h = 0; h < t.number_of_halfedges(); ++h)
  {
    const int o = t.twin[std::size_t(h)];
    if(std::min(t.origin[std::size_t(h)], t.target(h)) != 0 || std::max(t.origin[std::size_t(h)], t.target(h)) != 1 ||
       h > o)
      continue;
    const int a = h / 6, b = o / 6;
    if(a == 0 || b == 0)
      through_zero.push_back({{std::max(a, b), 0}});
    else
      glued.push_back({{std::min(a, b), std::max(a, b)}});
  }
  BOOST_TEST_REQUIRE(through_zero.size() == 2u);
  glued.push_back({{std::min(through_zero[0][0], through_zero[1][0]), std::max(through_zero[0][0], through_zero[1][0])}});
  std::sort(glued.begin(), glued.end());
  // Faces 1-4 are the pages at 0, 200, 90, 300 degrees: 0-90 (1, 3), 90-200 (2, 3), 200-300
  // (2, 4), 300-0 (1, 4).
  const std::vector<std::array<int, 2> > expected = {{{1, 3}}, {{1, 4}}, {{2, 3}}, {{2, 4}}};
  BOOST_TEST((glued == expected));
}

// The Laplacian of a mesh that needs the tufted cover (non-manifold, or faces of zero area) is the
// tufted one, whatever asks for it (laplace_beltrami_matrices(), the spectrum).
BOOST_AUTO_TEST_CASE(non_manifold_meshes_get_the_tufted_laplacian)
{
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3> > triangles;
  smc_test::add_book(3, 4, points, triangles);
  const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
  BOOST_TEST(m.needs_tufted_cover());
  const smc::Laplace_beltrami_matrices a = smc::internal::laplace_beltrami_matrices(m, true);
  const smc::Laplace_beltrami_matrices b = smc::internal::tufted_laplace_beltrami_matrices(m);
  BOOST_TEST((Sparse(a.stiffness_matrix - b.stiffness_matrix).norm() == 0.0));
  BOOST_TEST((a.mass == b.mass));
  check_laplacian(a, 3.0, 1);
  // Without intrinsic flips: the cover's own cotangent weights, the same mass.
  const smc::Laplace_beltrami_matrices c = smc::internal::laplace_beltrami_matrices(m, false);
  BOOST_TEST(c.number_of_flips == 0);
  BOOST_TEST((c.mass == b.mass));
  BOOST_TEST((Sparse(c.stiffness_matrix.transpose()) - c.stiffness_matrix).norm() <= 1e-12 * c.stiffness_matrix.norm());
  BOOST_TEST((c.stiffness_matrix * Eigen::VectorXd::Ones(m.number_of_vertices())).cwiseAbs().maxCoeff() <= 1e-12);
  const smc::Laplace_beltrami_spectrum spectrum(m, params::number_of_eigenpairs(6));
  const Eigen::VectorXd ev = spectrum_of(a);
  for(int k = 0; k < 6; ++k) BOOST_TEST(std::abs(spectrum.eigenvalues()[k] - ev[k]) <= 1e-8 * (1 + ev[k]));
}

BOOST_AUTO_TEST_CASE(on_closed_manifold_meshes_it_is_the_intrinsic_delaunay_laplacian)
{
  // Twisted and jittered spheres need flips; a flat grid with right triangles has a boundary
  // whose triangles are not obtuse, so its pillow edges stay Delaunay.
  for(const Mesh& mesh : {icosphere(2), twisted_sphere(2, 3.0), jittered_sphere(2, 0.45), grid(6, 5)})
  {
    const smc::internal::Indexed_mesh m = smc::internal::make_indexed_mesh(mesh);
    const smc::Laplace_beltrami_matrices idt = smc::laplace_beltrami_matrices(mesh, params::use_intrinsic_delaunay(true));
    const smc::Laplace_beltrami_matrices tufted = smc::internal::tufted_laplace_beltrami_matrices(m);
    BOOST_TEST((Sparse(tufted.stiffness_matrix - idt.stiffness_matrix)).norm() <= 1e-12 * idt.stiffness_matrix.norm());
    BOOST_TEST((tufted.mass - idt.mass).norm() == 0);
  }
}

BOOST_AUTO_TEST_CASE(on_fins_touching_sheets_and_pinched_vertices_it_is_a_laplacian)
{
  auto area_of = [](const smc::internal::Indexed_mesh& m) { return m.total_area; };
  {
    // A fin: three pages on one spine (3 triangles per spine edge), and one at 20 degrees from
    // another, so that the wedges differ.
    std::vector<Eigen::Vector3d> points;
    std::vector<std::array<int, 3> > triangles;
    smc_test::add_book(3, 4, points, triangles, 0, {0.0, 0.35, 2.5});
    const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
    BOOST_TEST_CHECKPOINT("fin");
    check_laplacian(smc::internal::tufted_laplace_beltrami_matrices(m), area_of(m), 1);
  }
  {
    // Two sheets touching along an edge: 4 triangles per spine edge; and beside it, a second
    // component.
    std::vector<Eigen::Vector3d> points;
    std::vector<std::array<int, 3> > triangles;
    smc_test::add_book(4, 4, points, triangles);
    smc_test::add_book(2, 3, points, triangles, 5.0);
    const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
    BOOST_TEST(m.number_of_components == 2);
    BOOST_TEST_CHECKPOINT("touching sheets");
    check_laplacian(smc::internal::tufted_laplace_beltrami_matrices(m), area_of(m), 2);
  }
  {
    // A bow-tie: two squares that share one corner vertex and nothing else.
    std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0, 0.3}, {-1, -1, 0.3},
                                           {0, -1, 0.3}};
    std::vector<std::array<int, 3> > triangles = {{{0, 1, 2}}, {{0, 2, 3}}, {{0, 4, 5}}, {{0, 5, 6}}};
    const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
    BOOST_TEST_CHECKPOINT("bow-tie");
    check_laplacian(smc::internal::tufted_laplace_beltrami_matrices(m), area_of(m), 1);
  }
}

BOOST_AUTO_TEST_CASE(the_spectrum_of_an_open_book_converges_to_the_analytic_one)
{
  // Three unit pages on one spine, free (Neumann) outer edges. An eigenfunction is either the
  // same on every page (even about the spine: pi^2 (a^2 + b^2)) or sums to zero over the pages
  // (zero on the spine: pi^2 ((a + 1/2)^2 + b^2), twice).
  const double pi2 = CGAL_PI * CGAL_PI;
  std::vector<double> exact = {0.25 * pi2, 0.25 * pi2, pi2, pi2, 1.25 * pi2, 1.25 * pi2, 2 * pi2};
  std::vector<double> previous_error;
  for(int n : {4, 8, 16})
  {
    std::vector<Eigen::Vector3d> points;
    std::vector<std::array<int, 3> > triangles;
    smc_test::add_book(3, n, points, triangles);
    const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
    const Eigen::VectorXd ev = spectrum_of(smc::internal::tufted_laplace_beltrami_matrices(m));
    BOOST_TEST(std::abs(ev[0]) < 1e-9);
    std::vector<double> error;
    for(std::size_t k = 0; k < exact.size(); ++k) error.push_back(std::abs(ev[Eigen::Index(k + 1)] - exact[k]) / exact[k]);
    BOOST_TEST_MESSAGE("open book, n = " << n << ": lambda_1 = " << ev[1] << " (exact " << exact[0]
                                         << "), largest relative error of the first 7: "
                                         << *std::max_element(error.begin(), error.end()));
    if(!previous_error.empty())
      for(std::size_t k = 0; k < exact.size(); ++k) BOOST_TEST(error[k] < 0.5 * previous_error[k] + 1e-9);
    previous_error = error;
  }
  for(double e : previous_error) BOOST_TEST(e < 0.01);
}

BOOST_AUTO_TEST_CASE(faces_of_zero_area_are_mollified)
{
  // A flat unit square (a book of one page, 16 x 16 cells) in which 9 interior vertices are
  // moved onto the far edge of one of their triangles: 9 of 512 triangles get zero area (their
  // vertices are collinear) while the surface stays the same square.
  const int n = 16;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3> > triangles;
  smc_test::add_book(1, n, points, triangles);
  smc::internal::Mesh_requirements req;
  req.allow_non_manifold = true;
  req.allow_degenerate_faces = true;
  auto flat_mesh = [&](const std::vector<Eigen::Vector3d>& p) {
    smc::internal::Indexed_mesh m;
    m.points.resize(Eigen::Index(p.size()), 3);
    for(std::size_t i = 0; i < p.size(); ++i) m.points.row(Eigen::Index(i)) = p[i].transpose();
    m.triangles.resize(Eigen::Index(triangles.size()), 3);
    for(std::size_t f = 0; f < triangles.size(); ++f)
      for(int c = 0; c < 3; ++c) m.triangles(Eigen::Index(f), c) = triangles[f][std::size_t(c)];
    smc::internal::finalize_indexed_mesh(m, req, "square");
    return m;
  };
  const smc::internal::Indexed_mesh clean = flat_mesh(points);
  std::vector<Eigen::Vector3d> moved = points;
  int degenerate = 0;
  for(int r : {3, 7, 11})
    for(int k : {3, 7, 11})
    {
      const int v = (n + 1) + (r - 1) * (n + 1) + k;  // vertex (r, k) of the page
      // Its first triangle (v, (r + 1, k), (r + 1, k + 1)): v goes to the middle of the far edge.
      for(const auto& t : triangles)
        if(t[0] == v)
        {
          moved[std::size_t(v)] = 0.5 * (points[std::size_t(t[1])] + points[std::size_t(t[2])]);
          break;
        }
    }
  const smc::internal::Indexed_mesh m = flat_mesh(moved);
  for(int f = 0; f < m.number_of_triangles(); ++f)
    if(m.triangle_areas[std::size_t(f)] < 1e-12) ++degenerate;
  BOOST_TEST(degenerate == 9);
  double epsilon = 0;
  const smc::Laplace_beltrami_matrices lb = smc::internal::tufted_laplace_beltrami_matrices(m, 1e-5, &epsilon);
  BOOST_TEST(epsilon > 0);
  BOOST_TEST(epsilon < 1e-5);  // 1e-5 of the mean edge length (1/16 or so), at most
  BOOST_TEST(lb.stiffness_matrix.coeffs().allFinite());
  check_laplacian(lb, lb.mass.sum(), 1);
  BOOST_TEST(std::abs(lb.mass.sum() - 1.0) < 1e-3);
  // The same square: the spectrum is that of the clean grid, and both approach the analytic
  // Neumann eigenvalues pi^2 (a^2 + b^2).
  const Eigen::VectorXd mollified = spectrum_of(lb), reference = spectrum_of(smc::internal::tufted_laplace_beltrami_matrices(clean));
  double worst = 0;
  for(int k = 1; k <= 8; ++k) worst = std::max(worst, std::abs(mollified[k] - reference[k]) / reference[k]);
  BOOST_TEST_MESSAGE("9 zero-area triangles of 512: epsilon " << epsilon << ", largest relative change of the first 8 eigenvalues " << worst);
  BOOST_TEST(worst < 0.02);
  BOOST_TEST(std::abs(reference[1] - CGAL_PI * CGAL_PI) < 0.02 * CGAL_PI * CGAL_PI);
}

BOOST_AUTO_TEST_SUITE_END()
