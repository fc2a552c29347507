// SPDX-License-Identifier: GPL-3.0-or-later
// Evaluation toolkit: geodesic errors against analytic distances, the symmetry-tolerant variant,
// cycle consistency, coverage and the statistics.

#include <CGAL/Surface_mesh_correspondence/evaluation.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

namespace smc = CGAL::Surface_mesh_correspondence;
using namespace smc_test;

namespace {

// Vertex (i, j) of smc_test::grid(n, n) has index j * (n + 1) + i.
std::size_t grid_vertex(int n, int i, int j) { return static_cast<std::size_t>(j * (n + 1) + i); }

double great_circle(const Point& a, const Point& b)
{
  const double c = (a.x() * b.x() + a.y() * b.y() + a.z() * b.z()) /
                   std::sqrt((a.x() * a.x() + a.y() * a.y() + a.z() * a.z()) * (b.x() * b.x() + b.y() * b.y() + b.z() * b.z()));
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

} // namespace

BOOST_AUTO_TEST_SUITE(evaluation)

BOOST_AUTO_TEST_CASE(statistics_of_a_hand_made_list)
{
  const smc::Error_statistics s = smc::error_statistics({0.0, 0.1, 0.3, 0.05}, 0.25, 6);
  BOOST_TEST(s.mean == 0.1125, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.median == 0.075, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.maximum == 0.3);
  // thresholds 0, 0.05, 0.1, 0.15, 0.2, 0.25
  const std::vector<double> expected = {0.25, 0.5, 0.75, 0.75, 0.75, 0.75};
  BOOST_TEST(s.cumulative == expected, boost::test_tools::per_element());
  BOOST_TEST(s.fraction_below(0.06) == 0.5);
  BOOST_CHECK_THROW(smc::error_statistics({0.1}, 0.25, 1), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(errors_on_a_flat_grid_are_euclidean)
{
  const int n = 20;
  const Mesh g = grid(n, n);  // unit square: area 1, distances are already normalised
  smc::Vertex_index_map_vector shift(num_vertices(g)), gt(num_vertices(g));
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      gt[grid_vertex(n, i, j)] = grid_vertex(n, i, j);
      // Three columns to the right and two rows up, clamped at the border.
      shift[grid_vertex(n, i, j)] = grid_vertex(n, std::min(n, i + 3), std::min(n, j + 2));
    }
  smc::Map_evaluator<> evaluator(g);
  const smc::Error_statistics identity = evaluator.geodesic_errors(gt, gt, gt);
  BOOST_TEST(identity.mean == 0.0);
  BOOST_TEST(identity.cumulative.front() == 1.0);

  const smc::Error_statistics s = evaluator.geodesic_errors(shift, gt, gt);
  double worst = 0;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      const double dx = (std::min(n, i + 3) - i) / double(n), dy = (std::min(n, j + 2) - j) / double(n);
      const double exact = std::sqrt(dx * dx + dy * dy);
      const double got = s.errors[grid_vertex(n, i, j)];
      worst = std::max(worst, exact > 0 ? std::abs(got - exact) / exact : got);
    }
  BOOST_TEST_MESSAGE("largest relative error of fast-marching distances on the grid: " << worst);
  BOOST_TEST(worst < 0.03);
  // The free function agrees with the class.
  BOOST_TEST(smc::map_geodesic_errors(g, shift, gt, gt).mean == s.mean);
}

BOOST_AUTO_TEST_CASE(errors_on_a_sphere_follow_great_circles)
{
  const Mesh s = icosphere(4, 2.0);  // radius 2
  const std::size_t nv = num_vertices(s);
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, nv - 1);
  smc::Vertex_index_map_vector map(nv), gt_source, gt_target;
  for(std::size_t v = 0; v < nv; ++v) map[v] = pick(rng);
  for(std::size_t k = 0; k < 300; ++k)
  {
    gt_source.push_back(pick(rng));
    gt_target.push_back(pick(rng));
  }
  const smc::Error_statistics e = smc::map_geodesic_errors<CGAL::Parallel_if_available_tag>(s, map, gt_source, gt_target);
  const double scale = std::sqrt(CGAL::to_double(4 * pi * 4.0));  // sqrt(area) of the radius-2 sphere
  double worst = 0;
  for(std::size_t k = 0; k < gt_source.size(); ++k)
  {
    const double exact = 2.0 * great_circle(s.point(Vertex(static_cast<Mesh::size_type>(map[gt_source[k]]))),
                                            s.point(Vertex(static_cast<Mesh::size_type>(gt_target[k]))));
    worst = std::max(worst, std::abs(e.errors[k] * scale - exact) / scale);
  }
  BOOST_TEST_MESSAGE("largest error against great circles (fraction of sqrt(area)): " << worst);
  BOOST_TEST(worst < 0.01);
}

BOOST_AUTO_TEST_CASE(symmetry_tolerant_errors)
{
  const int n = 16;
  const Mesh g = grid(n, n);
  smc::Vertex_index_map_vector mirror(num_vertices(g)), gt(num_vertices(g)), gt_mirror(num_vertices(g));
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      gt[grid_vertex(n, i, j)] = grid_vertex(n, i, j);
      gt_mirror[grid_vertex(n, i, j)] = grid_vertex(n, n - i, j);
      mirror[grid_vertex(n, i, j)] = grid_vertex(n, n - i, j);
    }
  smc::Map_evaluator<> evaluator(g);
  const smc::Error_statistics direct = evaluator.geodesic_errors(mirror, gt, gt);
  const smc::Error_statistics tolerant = evaluator.symmetric_geodesic_errors(mirror, gt, gt, gt_mirror);
  BOOST_TEST(direct.mean > 0.3);  // mean |1 - 2x| over the square is 1/2 (up to discretisation)
  BOOST_TEST(tolerant.mean == 0.0);
  // A right map is right under both measures.
  BOOST_TEST(evaluator.symmetric_geodesic_errors(gt, gt, gt, gt_mirror).mean == 0.0);
  // Per sample, the tolerant error is the smaller of the two.
  smc::Vertex_index_map_vector half(gt);
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n / 2; ++i) half[grid_vertex(n, i, j)] = grid_vertex(n, std::min(n, i + 1), j);
  const auto a = evaluator.geodesic_errors(half, gt, gt);
  const auto b = evaluator.geodesic_errors(half, gt, gt_mirror);
  const auto c = evaluator.symmetric_geodesic_errors(half, gt, gt, gt_mirror);
  for(std::size_t k = 0; k < c.errors.size(); ++k)
    BOOST_TEST(c.errors[k] == std::min(a.errors[k], b.errors[k]), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(cycle_consistency_and_coverage)
{
  const int n = 12;
  const Mesh g = grid(n, n);
  const std::size_t nv = num_vertices(g);
  smc::Vertex_index_map_vector identity(nv), shift(nv);
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      identity[grid_vertex(n, i, j)] = grid_vertex(n, i, j);
      shift[grid_vertex(n, i, j)] = grid_vertex(n, std::min(n, i + 2), j);
    }
  const smc::Cycle_consistency same = smc::cycle_consistency(g, identity, identity);
  BOOST_TEST(same.distances.mean == 0.0);
  BOOST_TEST(same.fixed_point_fraction == 1.0);
  // Shift there and come back unchanged: every column but the last moves (by 2/n, or 1/n for
  // column n-1).
  const smc::Cycle_consistency shifted = smc::cycle_consistency(g, shift, identity);
  BOOST_TEST(shifted.fixed_point_fraction == 1.0 / (n + 1), boost::test_tools::tolerance(1e-12));
  double expected_mean = 0;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) expected_mean += (std::min(n, i + 2) - i) / double(n);
  expected_mean /= nv;
  BOOST_TEST(shifted.distances.mean == expected_mean, boost::test_tools::tolerance(0.02));

  BOOST_TEST(smc::map_coverage(identity, nv) == 1.0);
  BOOST_TEST(smc::map_coverage(shift, nv) == double(nv - 2 * (n + 1)) / nv, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(smc::number_of_inconsistent_vertices(identity, identity) == 0u);
  // x -> shift(x) -> x fails on the moved columns; y -> identity(y) -> shift(y) fails on the same.
  BOOST_TEST(smc::number_of_inconsistent_vertices(shift, identity) == 2u * n * (n + 1));
}

BOOST_AUTO_TEST_CASE(polyhedron_gives_the_same_numbers)
{
  const Mesh s = icosphere(3);
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(s, p);  // vertex order may change: compare a statistic that does not depend on it
  const std::size_t nv = num_vertices(s);
  smc::Vertex_index_map_vector constant(nv, 0), all(nv);
  for(std::size_t v = 0; v < nv; ++v) all[v] = v;
  const double a = smc::map_geodesic_errors(s, constant, all, all).mean;
  // On the polyhedron, map everything to the vertex at the same position as vertex 0 of s.
  auto vim = CGAL::get_initialized_vertex_index_map(p);
  std::size_t same = 0;
  for(auto v : vertices(p))
    if(v->point() == s.point(Vertex(0))) same = get(vim, v);
  const double b = smc::map_geodesic_errors(p, smc::Vertex_index_map_vector(nv, same), all, all).mean;
  BOOST_TEST(a == b, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(bad_maps_are_named)
{
  const Mesh g = grid(4, 4);
  const std::size_t nv = num_vertices(g);
  smc::Vertex_index_map_vector ok(nv, 0), gt = {0, 1, 2};
  smc::Map_evaluator<> evaluator(g);
  smc::Vertex_index_map_vector bad = ok;
  bad[3] = nv;
  BOOST_CHECK_THROW(evaluator.geodesic_errors(bad, gt, gt), smc::Invalid_map_error);
  BOOST_CHECK_THROW(evaluator.geodesic_errors(ok, gt, {0, 1}), smc::Invalid_map_error);
  BOOST_CHECK_THROW(evaluator.geodesic_errors(ok, {0, 1, nv}, gt), smc::Invalid_map_error);
  BOOST_CHECK_THROW(evaluator.symmetric_geodesic_errors(ok, gt, gt, {0}), smc::Invalid_map_error);
  BOOST_CHECK_THROW(evaluator.cycle_consistency(ok, smc::Vertex_index_map_vector(nv, nv + 1)), smc::Invalid_map_error);
  BOOST_CHECK_THROW(evaluator.cycle_consistency(smc::Vertex_index_map_vector(nv - 1, 0), ok), smc::Invalid_map_error);
  BOOST_CHECK_THROW(smc::map_coverage(bad, nv), smc::Invalid_map_error);
  try
  {
    evaluator.geodesic_errors(bad, gt, gt);
  }
  catch(const smc::Invalid_map_error& e)
  {
    BOOST_TEST(std::string(e.what()).find("entry 3") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
