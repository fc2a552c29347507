// SPDX-License-Identifier: GPL-3.0-or-later
// The flat mesh copy every algorithm runs on: structure, and a clear exception for bad meshes.

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/orientation_operator.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace tt = boost::test_tools;
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
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::finalize_indexed_mesh(fan, {}); }),
                      "not manifold: the edge (0, 1) is shared by 3 faces"));
  // Two triangles touching at a single vertex (a pinched vertex).
  auto bow = soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::finalize_indexed_mesh(bow, {}); }),
                      "vertex 0 joins several separate fans"));
  (void)fin;
}

// With the requirements that allow them (those of the matching's shapes), non-manifold edges and
// vertices and faces of zero area are recorded instead of refused; the triangles that have no
// orientation (on a non-manifold edge, or of zero area) are told apart; the orientation check of
// a soup skips the edges in more than two faces, and still catches a flipped face elsewhere.
BOOST_AUTO_TEST_CASE(irregular_meshes_are_recorded_when_allowed)
{
  smc::internal::Mesh_requirements req;
  req.allow_non_manifold = true;
  req.allow_degenerate_faces = true;
  // A tetrahedron (0, 1, 2, 3) with a fin (1, 2, 4) and a bow-tie at vertex 3: the triangle
  // (3, 5, 6), and a triangle (1, 7, 0) of zero area outside the tetrahedron's edge (0, 1).
  const std::vector<std::array<double, 3> > p = {{0, 0, 1}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {2, -1, 0},
                                                 {0, 2, 0}, {1, 2, 0}, {2, 0, -1}};
  const std::vector<std::array<int, 3> > tet = {{2, 3, 1}, {2, 1, 0}, {2, 0, 3}, {1, 3, 0}};
  std::vector<std::array<int, 3> > t = tet;
  t.push_back({2, 1, 4});
  t.push_back({3, 5, 6});
  t.push_back({1, 7, 0});  // vertex 7 = 2 p1 - p0, on the line of (0, 1)
  smc::internal::Indexed_mesh m = soup(p, t);
  smc::internal::finalize_indexed_mesh(m, req);
  BOOST_TEST((m.non_manifold_edges == std::vector<std::array<int, 2> >{{{0, 1}}, {{1, 2}}}));
  BOOST_TEST((m.non_manifold_vertices == std::vector<int>{3}));
  BOOST_TEST((m.degenerate_faces == std::vector<int>{6}));
  BOOST_TEST(!m.is_manifold());
  BOOST_TEST(m.needs_tufted_cover());
  // Oriented: the faces on neither (0, 1) nor (1, 2), and not of zero area.
  BOOST_TEST((smc::internal::oriented_triangles(m) == std::vector<char>{0, 0, 1, 0, 0, 1, 0}));
  // The default requirements refuse each problem, as before.
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::internal::finalize_indexed_mesh(m, {}); }),
                      "is degenerate (zero area)"));
  // A clean tetrahedron has none of this.
  smc::internal::Indexed_mesh clean = soup(p, tet);
  clean.points.conservativeResize(4, 3);
  smc::internal::finalize_indexed_mesh(clean, req);
  BOOST_TEST(clean.is_manifold());
  BOOST_TEST(!clean.needs_tufted_cover());
  BOOST_TEST(clean.non_manifold_edges.empty());
  BOOST_TEST(clean.degenerate_faces.empty());
  // Soups: the fin's orientation is not checked, a flipped face on a manifold edge still is.
  std::vector<std::array<double, 3> > fin_points(p.begin(), p.begin() + 5);
  std::vector<std::array<int, 3> > fin_faces = tet;
  fin_faces.push_back({1, 2, 4});  // traverses (1, 2) in the direction of face 0
  const smc::internal::Indexed_mesh fin =
      smc::internal::make_soup_indexed_mesh(smc::Triangle_soup(fin_points, fin_faces), req);
  BOOST_TEST((fin.non_manifold_edges == std::vector<std::array<int, 2> >{{{1, 2}}}));
  std::vector<std::array<int, 3> > flipped = fin_faces;
  flipped[2] = {{2, 3, 0}};
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] {
                        smc::internal::make_soup_indexed_mesh(smc::Triangle_soup(fin_points, flipped), req);
                      }),
                      "inconsistently oriented faces"));
}

// Orientation on a flat grid with a vertical fin on an interior edge and a zero-area triangle (a
// T-junction closed by a sliver: the midpoint m of an edge (a, b) and the triangle (a, b, m)): the
// vertex normals are the grid's (0, 0, 1), also at the fin's edge, the fin's tip gets the fin's
// normal; n . (grad x cross grad y), the signed descriptor of the functional maps, is 1 at every
// vertex but the tip (which has no oriented face: 0), with no NaN from the sliver.
BOOST_AUTO_TEST_CASE(orientation_leaves_out_fins_and_faces_of_zero_area)
{
  const int n = 6;
  std::vector<std::array<double, 3> > p;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) p.push_back({{double(i), double(j), 0.0}});
  auto v = [&](int i, int j) { return j * (n + 1) + i; };
  std::vector<std::array<int, 3> > t;
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      t.push_back({{v(i, j), v(i + 1, j), v(i + 1, j + 1)}});
      t.push_back({{v(i, j), v(i + 1, j + 1), v(i, j + 1)}});
    }
  // The sliver: triangle (a, b, c) = the first one of cell (1, 1) split at the middle m of (a, b).
  const std::size_t split = std::size_t(2 * (1 * n + 1));
  const int a = t[split][0], b = t[split][1], c = t[split][2], m = int(p.size());
  p.push_back({{1.5, 1.0, 0.0}});
  t[split] = {{a, m, c}};
  t.push_back({{m, b, c}});
  t.push_back({{a, b, m}});
  // The fin: a vertical triangle on the diagonal of cell (4, 3).
  const int f0 = v(4, 3), f1 = v(5, 4), tip = int(p.size());
  p.push_back({{4.5, 3.5, 1.0}});
  t.push_back({{f0, f1, tip}});
  smc::internal::Mesh_requirements req;
  req.allow_non_manifold = true;
  req.allow_degenerate_faces = true;
  smc::internal::Indexed_mesh mesh = soup(p, t);
  smc::internal::finalize_indexed_mesh(mesh, req);
  BOOST_TEST(mesh.degenerate_faces.size() == 1u);
  BOOST_TEST(mesh.non_manifold_edges.size() == 1u);
  const smc::internal::Indexed_mesh::Points normals = smc::internal::vertex_normals(mesh);
  const Eigen::RowVector3d up(0, 0, 1), fin_normal = Eigen::RowVector3d(1, -1, 0).normalized();
  for(int x = 0; x < mesh.number_of_vertices(); ++x)
    if(x != tip) BOOST_TEST((normals.row(x) - up).norm() <= 1e-12, "vertex " << x);
  BOOST_TEST((normals.row(f0) - up).norm() <= 1e-12);
  BOOST_TEST((normals.row(tip) - fin_normal).norm() <= 1e-12);
  Eigen::MatrixXd xy(mesh.number_of_vertices(), 2);
  xy.col(0) = mesh.points.col(0);
  xy.col(1) = mesh.points.col(1);
  const Eigen::MatrixXd turn = smc::internal::gradient_cross_products(mesh, xy, {{0, 1}}, 1.0);
  for(int x = 0; x < mesh.number_of_vertices(); ++x)
    BOOST_TEST(turn(x, 0) == (x == tip ? 0.0 : 1.0), tt::tolerance(1e-12));
}

// Triangle soups (points and index triples): every problem is named with its vertex or face and,
// when the lines of the file are known, with its line; a valid soup becomes a mesh whose vertex i
// is point i.
BOOST_AUTO_TEST_CASE(triangle_soup_checks_and_conversion)
{
  typedef std::array<double, 3> P;
  typedef std::vector<std::size_t> F;
  // A tetrahedron with its points in a shuffled order.
  const std::vector<P> points = {{0, 0, 1}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  const std::vector<F> faces = {{2, 3, 1}, {2, 1, 0}, {2, 0, 3}, {1, 3, 0}};
  Mesh tet;
  std::vector<Point> cgal_points;
  for(const P& p : points) cgal_points.emplace_back(p[0], p[1], p[2]);
  smc::triangle_soup_to_mesh(cgal_points, faces, tet);
  BOOST_TEST(num_vertices(tet) == 4u);
  BOOST_TEST(num_faces(tet) == 4u);
  for(std::size_t i = 0; i < 4; ++i) BOOST_TEST(tet.point(Vertex(i)) == cgal_points[i]);
  BOOST_TEST(CGAL::is_closed(tet));
  // The mesh is emptied first.
  smc::triangle_soup_to_mesh(cgal_points, faces, tet);
  BOOST_TEST(num_vertices(tet) == 4u);

  smc::Triangle_soup_origin origin("tet.off");
  origin.vertex_lines = {3, 4, 5, 6};
  origin.face_lines = {7, 8, 9, 10};
  auto problem = [&](std::vector<P> p, std::vector<F> f) {
    return error_of<smc::Invalid_mesh_error>([&] { smc::check_triangle_soup(p, f, origin); });
  };
  BOOST_TEST(contains(problem(points, faces), "no exception"));  // error_of's answer when nothing is thrown
  BOOST_TEST(contains(problem({}, faces), "tet.off: the mesh has no vertices"));
  BOOST_TEST(contains(problem(points, {}), "tet.off: the mesh has no faces"));
  std::vector<P> nan = points;
  nan[1][2] = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(contains(problem(nan, faces), "tet.off:4: vertex 1 has a non-finite coordinate"));
  std::vector<P> inf = points;
  inf[3][0] = std::numeric_limits<double>::infinity();
  BOOST_TEST(contains(problem(inf, faces), "tet.off:6: vertex 3 has a non-finite coordinate (inf 1 0)"));
  BOOST_TEST(contains(problem(points, {{2, 3, 1}, {2, 1, 0}, {2, 0, 4}, {1, 3, 0}}),
                      "tet.off:9: face 2 refers to vertex 4 but the mesh has 4 vertices"));
  BOOST_TEST(contains(problem(points, {{2, 3, 1}, {2, 1, 0, 3}, {2, 0, 3}}),
                      "tet.off:8: 1 of 3 faces are not triangles (face 1 has 4 vertices)"));
  BOOST_TEST(contains(problem(points, {{2, 3, 1}, {2, 1, 1}, {2, 0, 3}, {1, 3, 0}}),
                      "tet.off:8: face 1 is degenerate: it repeats vertex 1"));
  BOOST_TEST(contains(problem(points, {{2, 3, 1}, {1, 2, 0}, {2, 0, 3}, {1, 3, 0}}),
                      "tet.off has inconsistently oriented faces: faces 0 and 1"));
  std::vector<P> isolated = points;
  isolated.push_back({5, 5, 5});
  BOOST_TEST(contains(problem(isolated, faces), "tet.off: vertex 4 is isolated"));
  std::vector<P> two = points;
  for(const P& p : points) two.push_back({p[0] + 3, p[1], p[2]});
  std::vector<F> two_faces = faces;
  for(const F& f : faces) two_faces.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  BOOST_TEST(contains(problem(two, two_faces), "tet.off has 2 connected components"));
  // A fin: a third face on the edge (1, 2).
  std::vector<P> fin = points;
  fin.push_back({2, -1, 0});
  std::vector<F> fin_faces = faces;
  fin_faces.push_back({2, 1, 4});
  BOOST_TEST(contains(problem(fin, fin_faces), "tet.off is not manifold: the edge (1, 2) is shared by 3 faces"));
  // Negative indices (numpy arrays of signed integers).
  const std::vector<std::array<int, 3> > negative = {{2, 3, 1}, {2, 1, 0}, {2, 0, -1}, {1, 3, 0}};
  BOOST_TEST(contains(error_of<smc::Invalid_mesh_error>([&] { smc::check_triangle_soup(points, negative); }),
                      "mesh: face 2 refers to vertex -1"));
}

// Mesh files: OFF and OBJ text (comments, counts on the header line, "i/t/n" and negative OBJ
// indices) give the file's points in order; problems name the file and the line.
BOOST_AUTO_TEST_CASE(mesh_files_name_file_and_line)
{
  char name[] = "/tmp/smc_mesh_io_XXXXXX";
  const std::string dir = ::mkdtemp(name);
  auto write = [&](const std::string& file, const std::string& text) {
    std::ofstream(dir + "/" + file) << text;
    return dir + "/" + file;
  };
  const std::string tet_off = "OFF 4 4 0\n# points\n0 0 1\n1 0 0\n0 0 0\n0 1 0\n3 2 3 1\n3 2 1 0\n3 2 0 3\n3 1 3 0\n";
  Mesh off, obj;
  smc::read_triangle_mesh(write("tet.off", tet_off), off);
  smc::read_triangle_mesh(write("tet.obj", "v 0 0 1\nv 1 0 0\nvt 0 0\nv 0 0 0\nv 0 1 0\nf 3/1 4/1 2/1\n"
                                           "f 3//1 2//1 1//1\nf -2 -4 -1\nf 2 4 1\n"),
                          obj);
  const Point expected[] = {Point(0, 0, 1), Point(1, 0, 0), Point(0, 0, 0), Point(0, 1, 0)};
  BOOST_TEST(num_faces(off) == 4u);
  BOOST_TEST(num_faces(obj) == 4u);
  for(std::size_t i = 0; i < 4; ++i)
  {
    BOOST_TEST(off.point(Vertex(i)) == expected[i]);
    BOOST_TEST(obj.point(Vertex(i)) == expected[i]);
  }
  auto problem = [&](const std::string& file, const std::string& text) {
    Mesh m;
    return error_of([&] { smc::read_triangle_mesh(write(file, text), m); });
  };
  BOOST_TEST(contains(problem("nan.off", "OFF\n4 4 0\n0 0 1\n1 0 nan\n0 0 0\n0 1 0\n3 2 3 1\n3 2 1 0\n3 2 0 3\n3 1 3 0\n"),
                      "nan.off:4: vertex 1 has a non-finite coordinate"));
  BOOST_TEST(contains(problem("range.off", "OFF\n4 4 0\n0 0 1\n1 0 0\n0 0 0\n0 1 0\n3 2 3 1\n3 2 1 9\n3 2 0 3\n3 1 3 0\n"),
                      "range.off:8: face 1 refers to vertex 9 but the file has 4 vertices"));
  BOOST_TEST(contains(problem("short.off", "OFF\n4 4 0\n0 0 1\n1 0 0\n0 0 0\n0 1 0\n3 2 3 1\n"),
                      "short.off: truncated: the header declares 4 faces, the file ends after 1"));
  BOOST_TEST(contains(problem("x.off", "OFF\n4 4 0\n0 0 1\n1 zero 0\n"), "x.off:4: vertex 1: \"zero\" is not a number"));
  BOOST_TEST(contains(problem("fin.off", "OFF\n5 5 0\n0 0 1\n1 0 0\n0 0 0\n0 1 0\n2 -1 0\n3 2 3 1\n3 2 1 0\n3 2 0 3\n"
                                         "3 1 3 0\n3 2 1 4\n"),
                      "fin.off is not manifold: the edge (1, 2) is shared by 3 faces"));
  BOOST_TEST(contains(problem("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
                      "quad.obj:5: 1 of 1 faces are not triangles (face 0 has 4 vertices)"));
  BOOST_TEST(contains(problem("range.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n"), "range.obj:3: face 0 refers to vertex 3"));
  BOOST_TEST(contains(problem("points.xyz", "0 0 0\n"), "unknown mesh format"));
  BOOST_TEST(contains(error_of([&] { smc::read_triangle_mesh(dir + "/missing.off", off); }), "cannot open"));
  BOOST_TEST(contains(error_of([&] { smc::read_triangle_mesh(dir, off); }), "it is a directory"));
  // The same files as triangle soups: the file's points and faces as they are, the problems of
  // the soup itself named with the line, those of the surface left to the shape.
  const smc::Triangle_soup soup = smc::read_triangle_soup(write("tet.off", tet_off));
  BOOST_TEST(soup.number_of_vertices() == 4u);
  BOOST_TEST(soup.number_of_triangles() == 4u);
  for(std::size_t i = 0; i < 4; ++i)
  {
    BOOST_TEST(soup.points()[i][0] == expected[i].x());
    BOOST_TEST(soup.points()[i][2] == expected[i].z());
  }
  BOOST_TEST((soup.triangles()[1] == std::array<int, 3>{{2, 1, 0}}));
  BOOST_TEST(soup.origin().name == dir + "/tet.off");
  BOOST_TEST(soup.origin().face_lines.size() == 4u);
  BOOST_TEST(contains(error_of([&] { smc::read_triangle_soup(write("nan.off", "OFF\n4 4 0\n0 0 1\n1 0 nan\n0 0 0\n0 1 0\n"
                                                                             "3 2 3 1\n3 2 1 0\n3 2 0 3\n3 1 3 0\n")); }),
                      "nan.off:4: vertex 1 has a non-finite coordinate"));
  BOOST_TEST(contains(error_of([&] { smc::read_triangle_soup(write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")); }),
                      "quad.obj:5: 1 of 1 faces are not triangles"));
  const smc::Triangle_soup fin = smc::read_triangle_soup(write("fin.off", "OFF\n5 5 0\n0 0 1\n1 0 0\n0 0 0\n0 1 0\n2 -1 0\n"
                                                                         "3 2 3 1\n3 2 1 0\n3 2 0 3\n3 1 3 0\n3 2 1 4\n"));
  BOOST_TEST(fin.number_of_triangles() == 5u);
  BOOST_TEST(contains(error_of([&] { smc::check_triangle_soup(fin.points(), fin.triangles(), fin.origin()); }),
                      "fin.off is not manifold: the edge (1, 2) is shared by 3 faces"));
  BOOST_TEST(contains(error_of([&] { smc::read_triangle_soup(dir + "/missing.off"); }), "cannot open"));
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
