// SPDX-License-Identifier: GPL-3.0-or-later
// Geodesic distance fields: fast marching, heat method and exact geodesics against analytic
// distances (sphere, plane), against each other, and their behaviour on components, boundaries,
// other mesh types and bad input.

#include <CGAL/Surface_mesh_correspondence/geodesic_distances.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace smci = CGAL::Surface_mesh_correspondence::internal;
using namespace smc_test;

namespace {

struct Errors
{
  double mean = 0, max = 0;
};

// Mean and max of |d - ref| over the vertices (ref finite).
Errors compare(const std::vector<double>& d, const std::vector<double>& ref)
{
  Errors e;
  int count = 0;
  for(std::size_t v = 0; v < d.size(); ++v)
  {
    if(!std::isfinite(ref[v])) continue;
    const double x = std::abs(d[v] - ref[v]);
    e.mean += x;
    e.max = std::max(e.max, x);
    ++count;
  }
  e.mean /= std::max(1, count);
  return e;
}

std::vector<double> great_circle(const smci::Indexed_mesh& m, int s)
{
  std::vector<double> d(m.number_of_vertices());
  for(int v = 0; v < m.number_of_vertices(); ++v)
  {
    const double c = m.point(s).normalized().dot(m.point(v).normalized());
    d[v] = std::acos(std::max(-1.0, std::min(1.0, c)));
  }
  return d;
}

std::vector<double> fast_marching(const smci::Indexed_mesh& m, int s,
                                  smci::Fast_marching_update rule = smci::Fast_marching_update::circular)
{
  smci::Fast_marching_geometry g(m, rule);
  smci::Fast_marching_workspace ws(g);
  ws.run(s);
  std::vector<double> d;
  ws.copy_distances(d);
  return d;
}

} // namespace

BOOST_AUTO_TEST_SUITE(geodesic_distances)

// On the unit icosphere, all three methods approach the great-circle distance, and their errors
// shrink when the sphere is refined.
BOOST_AUTO_TEST_CASE(sphere_convergence)
{
  double previous[3] = {inf, inf, inf};
  for(int level = 2; level <= 4; ++level)
  {
    const smci::Indexed_mesh m = smci::make_indexed_mesh(icosphere(level));
    smci::Exact_geodesic_solver exact(m);
    smci::Heat_method_solver heat(m);
    double mean[3] = {0, 0, 0}, worst[3] = {0, 0, 0};
    const int sources[2] = {0, m.number_of_vertices() / 2};
    for(int s : sources)
    {
      const std::vector<double> ref = great_circle(m, s);
      std::vector<double> de, dh;
      exact.distances(s, de);
      heat.distances(s, dh);
      const std::vector<double> df = fast_marching(m, s);
      const Errors e[3] = {compare(de, ref), compare(dh, ref), compare(df, ref)};
      for(int k = 0; k < 3; ++k)
      {
        mean[k] += e[k].mean / 2;
        worst[k] = std::max(worst[k], e[k].max);
      }
    }
    BOOST_TEST_MESSAGE("icosphere(" << level << "), n = " << m.number_of_vertices()
                       << ": mean |error| exact " << mean[0] << ", heat " << mean[1]
                       << ", fast marching " << mean[2] << "; max " << worst[0] << ", "
                       << worst[1] << ", " << worst[2]);
    for(int k = 0; k < 3; ++k)
    {
      BOOST_TEST(mean[k] < previous[k]);
      previous[k] = mean[k];
    }
    if(level == 4)
    {
      // Diameter pi: errors in per cent of it.
      BOOST_TEST(mean[0] < 0.003 * 3.1416);
      BOOST_TEST(mean[1] < 0.005 * 3.1416);
      BOOST_TEST(mean[2] < 0.005 * 3.1416);
      BOOST_TEST(worst[2] < 0.02 * 3.1416);
    }
  }
}

// On a flat grid the exact geodesic distance is the Euclidean distance; fast marching with the
// circular front is exact up to rounding for a single source; the planar front of the paper and
// the heat method are close.
BOOST_AUTO_TEST_CASE(flat_grid)
{
  for(int variant = 0; variant < 2; ++variant)
  {
    const Mesh g = variant == 0 ? grid(16, 12, 1.6, 1.2) : regular_grid(16, 12, 1.6, 1.2);
    const smci::Indexed_mesh m = smci::make_indexed_mesh(g);
    smci::Exact_geodesic_solver exact(m);
    smci::Heat_method_solver heat(m);
    for(int s : {0, 5 * 17 + 7, m.number_of_vertices() - 1})
    {
      std::vector<double> euclid(m.number_of_vertices());
      for(int v = 0; v < m.number_of_vertices(); ++v) euclid[v] = (m.point(v) - m.point(s)).norm();
      std::vector<double> de, dh;
      exact.distances(s, de);
      heat.distances(s, dh);
      const Errors ee = compare(de, euclid), ec = compare(fast_marching(m, s), euclid),
                   ep = compare(fast_marching(m, s, smci::Fast_marching_update::planar), euclid),
                   eh = compare(dh, euclid);
      BOOST_TEST_MESSAGE("grid variant " << variant << ", source " << s << ": max |error| exact "
                         << ee.max << ", fast marching circular " << ec.max << ", planar " << ep.max
                         << " (mean " << ep.mean << "), heat " << eh.max << " (mean " << eh.mean << ")");
      BOOST_TEST(ee.max < 1e-9);
      BOOST_TEST(ec.max < 1e-9);
      BOOST_TEST(ep.max < 0.1);   // edge length 0.1
      BOOST_TEST(ep.mean < 0.03);
      BOOST_TEST(eh.max < 0.08);
      BOOST_TEST(eh.mean < 0.03);
    }
  }
}

// Fast marching: the two-point updates against hand-computed cases.
BOOST_AUTO_TEST_CASE(two_point_updates)
{
  // Right isosceles corner C with X = (1, 0), Y = (0, 1); a source far along (1, 1) direction:
  // planar front from direction (-1, -1) / sqrt 2: T(X) = T(Y) = t0, T(C) = t0 + 1 / sqrt 2.
  const double t0 = 5.0;
  const double planar = smci::fast_marching_two_point_update(t0, t0, 1.0, 1.0, 0.0);
  BOOST_TEST(std::abs(planar - (t0 + 1 / std::sqrt(2.0))) < 1e-12);
  // Point source at S = (1, 1) + 3 (1, 1)/sqrt 2, i.e. at distance |S - X| from X.
  const double sx = 1 + 3 / std::sqrt(2.0), sy = 1 + 3 / std::sqrt(2.0);
  const double tx = std::hypot(sx - 1, sy), ty = std::hypot(sx, sy - 1);
  const double circular = smci::fast_marching_circular_update(tx, ty, 1.0, 1.0, 0.0);
  BOOST_TEST(std::abs(circular - std::hypot(sx, sy)) < 1e-12);
  // A front arriving from outside the triangle (source beyond X on the x axis) is rejected.
  BOOST_TEST(std::isinf(smci::fast_marching_two_point_update(2.0, 2.0 + std::sqrt(2.0), 1.0, 1.0, 0.0)));
  BOOST_TEST(std::isinf(smci::fast_marching_circular_update(2.0, std::sqrt(9.0 + 1.0), 1.0, 1.0, 0.0)));
}

// Truncation and early termination accept the same vertices with the same values as a full run;
// multi-source fast marching is the minimum of the single-source runs (up to the interaction
// of the fronts where they meet).
BOOST_AUTO_TEST_CASE(fast_marching_truncation_early_termination_multi_source)
{
  const Mesh irregular = transformed(capsule(24, 6, 12, 1.0, 4.0), [](const Point& p) {
    return Point(p.x() * (1 + 0.2 * std::sin(3 * p.z())), p.y(), p.z() + 0.1 * p.x() * p.y());
  });
  for(const Mesh* mesh : {&irregular})
  {
    const smci::Indexed_mesh m = smci::make_indexed_mesh(*mesh);
    const int n = m.number_of_vertices();
    smci::Fast_marching_geometry g(m);
    smci::Fast_marching_workspace ws(g);
    std::vector<double> full;
    ws.run(3);
    ws.copy_distances(full);
    const double far = *std::max_element(full.begin(), full.end());
    for(double radius : {0.0, 0.3 * far, 0.7 * far})
    {
      ws.run(3, radius);
      int mismatches = 0, count = 0;
      for(int v = 0; v < n; ++v)
      {
        const bool inside = full[v] <= radius;
        if(inside) ++count;
        if(inside ? ws.distance(v) != full[v] : !std::isinf(ws.distance(v))) ++mismatches;
      }
      BOOST_TEST(mismatches == 0);
      BOOST_TEST(static_cast<int>(ws.accepted().size()) == count);
    }
    // Early termination: the targets get exactly their full-run values, and the run stopped
    // before the farthest vertex.
    const int targets[2] = {n / 3, n / 2};
    const int source = 3;
    ws.run(&source, 1, inf, targets, 2);
    BOOST_TEST(ws.distance(targets[0]) == full[targets[0]]);
    BOOST_TEST(ws.distance(targets[1]) == full[targets[1]]);
    BOOST_TEST(static_cast<int>(ws.accepted().size()) < n);
    for(int v : ws.accepted()) BOOST_TEST(ws.distance(v) == full[v]);

    // Multi-source.
    const int sources[3] = {3, n / 2, n - 5};
    std::vector<double> minimum(n, inf), single;
    for(int s : sources)
    {
      ws.run(s);
      ws.copy_distances(single);
      for(int v = 0; v < n; ++v) minimum[v] = std::min(minimum[v], single[v]);
    }
    ws.run(sources, 3);
    std::vector<double> multi;
    ws.copy_distances(multi);
    const Errors e = compare(multi, minimum);
    BOOST_TEST_MESSAGE("multi-source vs min of single sources: max " << e.max << ", mean " << e.mean
                       << " (mean edge length " << g.graph.mean_edge_length << ")");
    BOOST_TEST(e.max < 0.25 * g.graph.mean_edge_length);
    BOOST_TEST(e.mean < 0.005 * g.graph.mean_edge_length);
    for(int s : sources) BOOST_TEST(multi[s] == 0.0);
  }
}

// Obtuse triangles: a strongly sheared grid (all triangles obtuse) keeps fast marching close to
// the exact distances thanks to the unfolding.
BOOST_AUTO_TEST_CASE(obtuse_triangles_unfolded)
{
  const Mesh sheared = transformed(regular_grid(20, 20), [](const Point& p) {
    return Point(p.x() + 0.8 * p.y(), 0.45 * p.y(), 0);
  });
  const smci::Indexed_mesh m = smci::make_indexed_mesh(sheared);
  smci::Fast_marching_geometry g(m);
  BOOST_TEST(g.number_of_obtuse_angles > 0);
  BOOST_TEST_MESSAGE("sheared grid: " << g.number_of_obtuse_angles << " obtuse angles, "
                     << g.number_of_fallbacks << " not unfolded (boundary)");
  smci::Exact_geodesic_solver exact(m);
  std::vector<double> de;
  const int s = 10 * 21 + 10;
  exact.distances(s, de);
  const Errors e = compare(fast_marching(m, s), de);
  const Errors ep = compare(fast_marching(m, s, smci::Fast_marching_update::planar), de);
  BOOST_TEST_MESSAGE("sheared grid: fast marching max |error| " << e.max << ", mean " << e.mean
                     << "; planar front max " << ep.max << ", mean " << ep.mean
                     << "; mean edge " << g.graph.mean_edge_length);
  BOOST_TEST(e.mean < 0.02 * g.graph.mean_edge_length);
  BOOST_TEST(ep.mean < 0.5 * g.graph.mean_edge_length);
}

// Several components: vertices of another component are at infinite distance for every method.
BOOST_AUTO_TEST_CASE(several_components)
{
  const Mesh two = disjoint_union(icosphere(2), transformed(icosphere(2), [](const Point& p) {
                                    return Point(p.x() + 3, p.y(), p.z());
                                  }));
  const smci::Indexed_mesh m = smci::make_indexed_mesh(two);
  BOOST_TEST(m.number_of_components == 2);
  const int n = m.number_of_vertices(), half = n / 2;
  std::vector<double> de, dh;
  smci::Exact_geodesic_solver(m).distances(5, de);
  smci::Heat_method_solver heat(m);
  heat.distances(5, dh);
  const std::vector<double> df = fast_marching(m, 5);
  for(int v = 0; v < n; ++v)
  {
    const bool same = v < half;
    BOOST_TEST(std::isfinite(de[v]) == same);
    BOOST_TEST(std::isfinite(dh[v]) == same);
    BOOST_TEST(std::isfinite(df[v]) == same);
  }
  // The heat method of the second component is independent of the first.
  heat.distances(half + 5, dh);
  const smci::Indexed_mesh one = smci::make_indexed_mesh(icosphere(2));
  std::vector<double> alone;
  smci::Heat_method_solver(one).distances(5, alone);
  double diff = 0;
  for(int v = 0; v < half; ++v) diff = std::max(diff, std::abs(dh[half + v] - alone[v]));
  BOOST_TEST(diff < 1e-9);
}

// A grid with a hole: the exact distance is Euclidean when the segment misses the hole, longer
// otherwise; fast marching and the heat method follow it around the hole.
BOOST_AUTO_TEST_CASE(boundary_with_hole)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(regular_grid(18, 18, 1.0, 1.0, true));
  BOOST_TEST(m.has_boundary());
  auto at = [&](double x, double y) {
    int best = 0;
    for(int v = 1; v < m.number_of_vertices(); ++v)
      if((m.point(v) - Eigen::Vector3d(x, y, 0)).norm() < (m.point(best) - Eigen::Vector3d(x, y, 0)).norm())
        best = v;
    return best;
  };
  const int s = at(2 / 18.0, 0.5);  // left of the hole (x in [1/3, 2/3]), mid height
  std::vector<double> de, dh;
  smci::Exact_geodesic_solver(m).distances(s, de);
  smci::Heat_method_solver(m).distances(s, dh);
  const std::vector<double> df = fast_marching(m, s);
  const int behind = at(16 / 18.0, 0.5);  // right of the hole
  const double straight = (m.point(behind) - m.point(s)).norm();
  BOOST_TEST(de[behind] > straight * 1.05);
  const int next = at(3 / 18.0, 0.5);
  BOOST_TEST(std::abs(de[next] - 1 / 18.0) < 1e-12);
  for(int v = 0; v < m.number_of_vertices(); ++v)
    BOOST_TEST(de[v] >= (m.point(v) - m.point(s)).norm() - 1e-9);
  const Errors ef = compare(df, de), eh = compare(dh, de);
  BOOST_TEST_MESSAGE("grid with hole: fast marching mean |error| " << ef.mean << " max " << ef.max
                     << "; heat mean " << eh.mean << " max " << eh.max);
  BOOST_TEST(ef.mean < 0.005);
  BOOST_TEST(ef.max < 0.03);
  BOOST_TEST(df[behind] > straight * 1.05);
  BOOST_TEST(dh[behind] > straight * 1.05);
  // The heat method is far less accurate on this coarse grid, and its far field (normalised
  // gradients of a heat that has decayed by many orders of magnitude) depends on rounding: the
  // mean error is 0.0306 when Eigen uses FMA (-march=native); SSE2 builds stayed below 0.03.
  BOOST_TEST(eh.mean < 0.035);
}

// The public FaceGraph functions give the same values on a Surface_mesh and on a Polyhedron_3,
// and the fast marching / heat / exact entry points agree with the index-based ones.
BOOST_AUTO_TEST_CASE(surface_mesh_and_polyhedron)
{
  typedef CGAL::Polyhedron_3<Kernel> Polyhedron;
  typedef boost::graph_traits<Polyhedron>::vertex_descriptor Pvertex;
  Mesh sm = icosphere(2);
  Polyhedron poly;
  CGAL::copy_face_graph(sm, poly);
  const smci::Indexed_mesh m = smci::make_indexed_mesh(sm);

  auto sm_distances = sm.add_property_map<Vertex, double>("v:d", 0).first;
  std::map<Pvertex, double> pmap;
  auto poly_distances = boost::make_assoc_property_map(pmap);

  // copy_face_graph reorders the vertices of a Polyhedron_3: match them by position.
  std::map<Point, int> index_of;
  for(Vertex v : sm.vertices()) index_of[sm.point(v)] = static_cast<int>(v);
  std::vector<Pvertex> pvertex(num_vertices(sm));
  for(Pvertex v : vertices(poly)) pvertex[index_of.at(v->point())] = v;
  BOOST_TEST((poly.size_of_vertices() == num_vertices(sm)));
  const Vertex s_sm(7);
  const Pvertex s_poly = pvertex[7];

  for(int method = 0; method < 3; ++method)
  {
    if(method == 0)
    {
      smc::fast_marching_geodesic_distances(sm, s_sm, sm_distances);
      smc::fast_marching_geodesic_distances(poly, s_poly, poly_distances);
    }
    else if(method == 1)
    {
      smc::heat_method_geodesic_distances(sm, s_sm, sm_distances);
      smc::heat_method_geodesic_distances(poly, s_poly, poly_distances);
    }
    else
    {
      smc::exact_geodesic_distances(sm, s_sm, sm_distances);
      smc::exact_geodesic_distances(poly, s_poly, poly_distances);
    }
    std::vector<double> ref;
    smci::geodesic_distances_from(m, 7, method == 0 ? smc::Geodesic_method::fast_marching
                                        : method == 1 ? smc::Geodesic_method::heat_method
                                                      : smc::Geodesic_method::exact, ref);
    double diff_sm = 0, diff_poly = 0;
    for(int i = 0; i < m.number_of_vertices(); ++i)
    {
      diff_sm = std::max(diff_sm, std::abs(sm_distances[Vertex(i)] - ref[i]));
      diff_poly = std::max(diff_poly, std::abs(pmap[pvertex[i]] - ref[i]));
    }
    BOOST_TEST(diff_sm == 0.0);
    // The Polyhedron_3 copy has another vertex order: same values up to rounding.
    BOOST_TEST(diff_poly < (method == 1 ? 1e-6 : 1e-9));
  }

  // Named parameters: truncation and targets; the stateful classes.
  smc::fast_marching_geodesic_distances(sm, std::vector<Vertex>{Vertex(0), Vertex(100)}, sm_distances,
                                        smc::parameters::maximum_distance(0.5));
  for(Vertex v : sm.vertices())
    BOOST_TEST((sm_distances[v] <= 0.5 || std::isinf(sm_distances[v])));
  BOOST_TEST(sm_distances[Vertex(100)] == 0.0);

  smc::Fast_marching_geodesic_distances<Polyhedron> fm(poly);
  smc::fast_marching_geodesic_distances(sm, Vertex(3), sm_distances);
  const Pvertex p3 = pvertex[3], p90 = pvertex[90];
  const double full = sm_distances[Vertex(90)];
  BOOST_TEST(std::abs(fm.distance(p90, p3) - full) < 1e-12);
  smc::fast_marching_geodesic_distances(sm, Vertex(3), sm_distances,
                                        smc::parameters::target_vertices(std::vector<Vertex>{Vertex(90)}));
  BOOST_TEST(sm_distances[Vertex(90)] == full);
  int unreached = 0;
  for(Vertex v : sm.vertices()) unreached += std::isinf(sm_distances[v]) ? 1 : 0;
  BOOST_TEST(unreached > 0);

  smc::Heat_method_geodesic_distances<Mesh> hm(sm);
  hm.compute(Vertex(3), sm_distances);
  std::vector<double> ref;
  smci::geodesic_distances_from(m, 3, smc::Geodesic_method::heat_method, ref);
  BOOST_TEST(std::abs(sm_distances[Vertex(90)] - ref[90]) < 1e-12);
}

// Bad input gets a clear exception.
BOOST_AUTO_TEST_CASE(bad_input)
{
  Mesh sm = icosphere(1);
  auto dist = sm.add_property_map<Vertex, double>("v:d", 0).first;
  BOOST_TEST(contains(error_of([&] { smc::fast_marching_geodesic_distances(sm, Vertex(1000), dist); }),
                      "not a vertex"));
  BOOST_TEST(contains(error_of([&] { smc::exact_geodesic_distances(sm, Vertex(42), dist); }), "not a vertex"));
  BOOST_TEST(contains(error_of([&] { smc::heat_method_geodesic_distances(sm, Vertex(-1), dist); }),
                      "not a vertex"));
  BOOST_TEST(contains(error_of([&] {
                        smc::fast_marching_geodesic_distances(sm, Vertex(0), dist,
                                                              smc::parameters::maximum_distance(-1.0));
                      }),
                      "maximum distance"));
  BOOST_TEST(contains(error_of([&] {
                        smc::fast_marching_geodesic_distances(sm, std::vector<Vertex>(), dist);
                      }),
                      "no source"));
  const Mesh empty;
  BOOST_TEST(contains(error_of([&] { smc::fast_marching_geodesic_distances(empty, Vertex(0), dist); }), "empty"));
  Mesh nan_mesh = icosphere(1);
  nan_mesh.point(Vertex(4)) = Point(std::nan(""), 0, 0);
  BOOST_TEST(contains(error_of([&] { smc::Fast_marching_geodesic_distances<Mesh> fm(nan_mesh); }), "non-finite"));
  BOOST_TEST(contains(error_of([&] { smc::Heat_method_geodesic_distances<Mesh> hm(nan_mesh); }), "non-finite"));
  const smci::Indexed_mesh m = smci::make_indexed_mesh(sm);
  smci::Fast_marching_geometry g(m);
  smci::Fast_marching_workspace ws(g);
  BOOST_TEST(contains(error_of([&] { ws.run(-3); }), "out of range"));
  const int target = 99;
  BOOST_TEST(contains(error_of([&] { const int s = 0; ws.run(&s, 1, inf, &target, 1); }), "out of range"));
  BOOST_TEST(contains(error_of([&] { ws.run(0, std::nan("")); }), "maximum distance"));
  // The workspace is still usable after an exception.
  ws.run(0);
  BOOST_TEST(static_cast<int>(ws.accepted().size()) == m.number_of_vertices());
}

BOOST_AUTO_TEST_SUITE_END()
