// SPDX-License-Identifier: GPL-3.0-or-later
// The flat mesh copy every algorithm runs on: structure, and a clear exception for bad meshes.

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <limits>
#include <string>

namespace smc = CGAL::Surface_mesh_correspondence;
using namespace smc_test;

namespace {


smc::internal::Indexed_mesh soup(const std::vector<std::array<double, 3> >& p,
                                 const std::vector<std::array<int, 3> >& t)
{
  smc::internal::Indexed_mesh m;
  m.points.resize(static_cast<Eigen::Index>(p.size()), 3);
  for(std::size_t i = 0; i < p.size(); ++i)
    for(int c = 0; c < 3; ++c) m.points(static_cast<Eigen::Index>(i), c) = p[i][c];
  m.triangles.resize(static_cast<Eigen::Index>(t.size()), 3);
  for(std::size_t i = 0; i < t.size(); ++i)
    for(int c = 0; c < 3; ++c) m.triangles(static_cast<Eigen::Index>(i), c) = t[i][c];
  return m;
}

} // namespace

BOOST_AUTO_TEST_SUITE(indexed_mesh)

BOOST_AUTO_TEST_CASE(sphere_structure)
{
  const Mesh s = icosphere(2);
  const auto m = smc::internal::make_indexed_mesh(s);
  BOOST_TEST(m.number_of_vertices() == 162);
  BOOST_TEST(m.number_of_triangles() == 320);
  BOOST_TEST(m.number_of_edges() == 480);  // Euler: V - E + F = 2
  BOOST_TEST(m.number_of_components == 1);
  BOOST_TEST(!m.has_boundary());
  // Degrees are 5 (the 12 icosahedron vertices) or 6, and neighbour lists are symmetric.
  int fives = 0;
  for(int v = 0; v < m.number_of_vertices(); ++v)
  {
    BOOST_TEST((m.degree(v) == 5 || m.degree(v) == 6));
    fives += m.degree(v) == 5;
    for(const int* w = m.neighbors_begin(v); w != m.neighbors_end(v); ++w)
      BOOST_TEST(std::binary_search(m.neighbors_begin(*w), m.neighbors_end(*w), v));
  }
  BOOST_TEST(fives == 12);
  // The area approaches 4 pi from below.
  BOOST_TEST(m.total_area < 4 * pi);
  BOOST_TEST(m.total_area > 0.97 * 4 * pi);
}

BOOST_AUTO_TEST_CASE(boundary_and_components)
{
  const auto g = smc::internal::make_indexed_mesh(grid(4, 3));
  BOOST_TEST(g.number_of_boundary_edges == 2 * (4 + 3));
  BOOST_TEST(std::abs(g.total_area - 1.0) < 1e-12);

  Mesh two = icosphere(1);
  const Mesh other = transformed(icosphere(1), [](const Point& p) { return p + Vector(5, 0, 0); });
  CGAL::copy_face_graph(other, two);
  const auto m = smc::internal::make_indexed_mesh(two);
  BOOST_TEST(m.number_of_components == 2);
  smc::internal::Mesh_requirements connected;
  connected.allow_several_components = false;
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(two, CGAL::parameters::default_values(), connected, "source"); }),
                      "source has 2 connected components"));
  smc::internal::Mesh_requirements closed;
  closed.allow_boundary = false;
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(grid(2, 2), CGAL::parameters::default_values(), closed); }),
                      "boundary"));
}

BOOST_AUTO_TEST_CASE(polyhedron_and_surface_mesh_agree)
{
  const Mesh s = icosphere(1);
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(s, p);
  const auto a = smc::internal::make_indexed_mesh(s);
  const auto b = smc::internal::make_indexed_mesh(p);
  BOOST_TEST(a.number_of_vertices() == b.number_of_vertices());
  BOOST_TEST(a.number_of_edges() == b.number_of_edges());
  BOOST_TEST(std::abs(a.total_area - b.total_area) < 1e-12);
}

BOOST_AUTO_TEST_CASE(bad_meshes_are_named)
{
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([] { smc::internal::make_indexed_mesh(Mesh()); }), "is empty"));

  Mesh quad;
  auto v0 = quad.add_vertex(Point(0, 0, 0)), v1 = quad.add_vertex(Point(1, 0, 0)),
       v2 = quad.add_vertex(Point(1, 1, 0)), v3 = quad.add_vertex(Point(0, 1, 0));
  quad.add_face(v0, v1, v2, v3);
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(quad); }), "has 4 vertices; only triangle"));

  Mesh nan = icosphere(1);
  nan.point(*nan.vertices().begin()) = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(nan); }), "non-finite coordinate"));

  Mesh flat = grid(2, 2);
  flat.point(Vertex(4)) = Point(0, 0, 0);  // the centre vertex collapses onto a corner
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(flat); }), "degenerate"));

  Mesh isolated = icosphere(1);
  isolated.add_vertex(Point(3, 3, 3));
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::make_indexed_mesh(isolated); }), "is isolated"));

  // Three triangles around one edge (a non-manifold edge), given as a soup.
  auto fin = smc::internal::Indexed_mesh();
  auto fan = soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::finalize_indexed_mesh(fan, {}); }), "not manifold"));
  // Two triangles touching at a single vertex (a pinched vertex).
  auto bow = soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::finalize_indexed_mesh(bow, {}); }),
                      "vertex 0 joins several separate fans"));
  (void)fin;
}

BOOST_AUTO_TEST_SUITE_END()
