// SPDX-License-Identifier: GPL-3.0-or-later
// Distance oracles: the dense matrix and the local rows equal the (symmetrised) fast marching
// values they are made of, the far estimate of the local oracle stays within its documented
// bound, both are close to exact geodesics, and parallel builds equal sequential ones.

#include <CGAL/Surface_mesh_correspondence/distance_oracle.h>
#include <CGAL/Surface_mesh_correspondence/internal/neighborhood_search.h>

#include "test_meshes.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace smci = CGAL::Surface_mesh_correspondence::internal;
using namespace smc_test;

namespace {

// All fast marching fields of a mesh: fields[k][l] = d_k(l).
std::vector<std::vector<double> > fast_marching_fields(const smci::Indexed_mesh& m)
{
  smci::Fast_marching_geometry g(m);
  smci::Fast_marching_workspace ws(g);
  std::vector<std::vector<double> > f(m.number_of_vertices());
  for(int k = 0; k < m.number_of_vertices(); ++k)
  {
    ws.run(k);
    ws.copy_distances(f[k]);
  }
  return f;
}

Mesh bumpy_capsule()
{
  return transformed(capsule(28, 7, 14, 1.0, 4.0), [](const Point& p) {
    return Point(p.x() * (1 + 0.25 * std::sin(2.5 * p.z())), p.y() * (1 + 0.1 * p.x()), p.z());
  });
}

} // namespace

BOOST_AUTO_TEST_SUITE(distance_oracles)

// The dense oracle is the symmetrised fast marching matrix, close to exact geodesics; parallel
// and sequential builds are identical; the row batch equals single queries.
BOOST_AUTO_TEST_CASE(dense_oracle)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(bumpy_capsule());
  const int n = m.number_of_vertices();
  const auto f = fast_marching_fields(m);
  const smc::Dense_distance_oracle dense = smc::Dense_distance_oracle::build<CGAL::Sequential_tag>(m);
  BOOST_TEST(dense.number_of_vertices() == n);
  int wrong = 0;
  for(int k = 0; k < n; ++k)
    for(int l = 0; l < n; ++l)
    {
      const float expected = k == l ? 0.f : 0.5f * (static_cast<float>(f[k][l]) + static_cast<float>(f[l][k]));
      if(dense.distance(k, l) != expected || dense.distance(k, l) != dense.distance(l, k)) ++wrong;
    }
  BOOST_TEST(wrong == 0);

#ifdef CGAL_LINKED_WITH_TBB
  const smc::Dense_distance_oracle parallel = smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m);
  BOOST_TEST(std::equal(dense.row(0), dense.row(0) + std::size_t(n) * n, parallel.row(0)));
#endif

  const std::vector<int> ls = {3, 0, n - 1, 17, 3};
  std::vector<float> out(ls.size());
  dense.distances(11, ls.data(), ls.size(), out.data());
  for(std::size_t i = 0; i < ls.size(); ++i) BOOST_TEST(out[i] == dense.distance(11, ls[i]));
  std::vector<float> shifted(ls.size() + 1, -1.f);
  dense.distances_to_set(11, nullptr, ls.data(), ls.size(), shifted.data());
  for(std::size_t i = 0; i < ls.size(); ++i) BOOST_TEST(shifted[i + 1] == dense.distance(11, ls[i]));

  // Against exact geodesics from a few sources.
  smci::Exact_geodesic_solver exact(m);
  double error = 0, scale = 0;
  int count = 0;
  for(int s : {0, n / 3, n - 1})
  {
    std::vector<double> de;
    exact.distances(s, de);
    for(int v = 0; v < n; ++v)
    {
      error += std::abs(dense.distance(s, v) - de[v]);
      scale = std::max(scale, de[v]);
      ++count;
    }
  }
  error /= count;
  BOOST_TEST_MESSAGE("dense oracle: mean |error| " << error << " (diameter " << scale << ")");
  BOOST_TEST(error < 0.005 * scale);
}

// Heat method and exact rows: the dense oracle built with them matches the solvers.
BOOST_AUTO_TEST_CASE(dense_oracle_other_methods)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(icosphere(1));
  const int n = m.number_of_vertices();
  smci::Exact_geodesic_solver exact(m);
  smci::Heat_method_solver heat(m);
  std::vector<std::vector<double> > de(n), dh(n);
  for(int k = 0; k < n; ++k)
  {
    exact.distances(k, de[k]);
    heat.distances(k, dh[k]);
  }
  const auto oe = smc::Dense_distance_oracle::build(m, smc::Geodesic_method::exact);
  const auto oh = smc::Dense_distance_oracle::build(m, smc::Geodesic_method::heat_method);
  double worst_e = 0, worst_h = 0;
  for(int k = 0; k < n; ++k)
    for(int l = 0; l < n; ++l)
    {
      const double e = k == l ? 0 : 0.5f * (static_cast<float>(de[k][l]) + static_cast<float>(de[l][k]));
      const double h = k == l ? 0 : 0.5f * (static_cast<float>(dh[k][l]) + static_cast<float>(dh[l][k]));
      worst_e = std::max(worst_e, std::abs(oe.distance(k, l) - e));
      worst_h = std::max(worst_h, std::abs(oh.distance(k, l) - h));
    }
  BOOST_TEST(worst_e == 0.0);
  BOOST_TEST(worst_h == 0.0);
}

// Local rows hold exactly the pairs within the radius, with the symmetrised fast marching
// values; beyond it the landmark estimate lies between the distance and the distance plus twice
// the covering radius (up to the fast marching's own triangle-inequality defects).
BOOST_AUTO_TEST_CASE(local_oracle)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(bumpy_capsule());
  const int n = m.number_of_vertices();
  const auto f = fast_marching_fields(m);
  smci::Edge_length_graph graph(m);
  const double radius = 4 * graph.mean_edge_length;
  const smc::Local_distance_oracle local = smc::Local_distance_oracle::build(m, radius, 24);
  BOOST_TEST(local.number_of_vertices() == n);
  BOOST_TEST(local.number_of_landmarks() == 24);
  BOOST_TEST(local.covering_radius() > 0.f);
  const float R = static_cast<float>(radius);
  int wrong_rows = 0, wrong_values = 0, outside_bound = 0, far_pairs = 0;
  double far_error = 0, worst_undershoot = 0;
  for(int k = 0; k < n; ++k)
  {
    int expected_size = 0;
    for(int l = 0; l < n; ++l)
    {
      const bool in_k = f[k][l] <= radius, in_l = f[l][k] <= radius;
      if(in_k) ++expected_size;
      if(in_k != local.is_local(k, l)) ++wrong_rows;
      if(k == l) continue;
      if(in_k)
      {
        const float expected = in_l ? 0.5f * (static_cast<float>(f[k][l]) + static_cast<float>(f[l][k]))
                                    : static_cast<float>(f[k][l]);
        if(local.distance(k, l) != expected) ++wrong_values;
      }
      else
      {
        const double d = 0.5 * (f[k][l] + f[l][k]);
        const double estimate = local.distance(k, l);
        ++far_pairs;
        far_error += estimate - d;
        worst_undershoot = std::max(worst_undershoot, (d - estimate) / d);
        if(estimate < R || estimate < d * (1 - 0.01) || estimate > d + 2 * local.covering_radius() + 0.01 * d)
          ++outside_bound;
      }
    }
    if(static_cast<int>(local.row_size(k)) != expected_size) ++wrong_rows;
    for(std::size_t i = 1; i < local.row_size(k); ++i)
      if(local.row_vertices(k)[i - 1] >= local.row_vertices(k)[i]) ++wrong_rows;
  }
  BOOST_TEST_MESSAGE("local oracle on " << n << " vertices: " << local.number_of_local_entries() / double(n)
                     << " entries per row, covering radius " << local.covering_radius()
                     << ", mean far overestimate " << far_error / far_pairs << " (R = " << R
                     << "), worst relative underestimate " << worst_undershoot);
  BOOST_TEST(wrong_rows == 0);
  BOOST_TEST(wrong_values == 0);
  BOOST_TEST(outside_bound == 0);

  // Against exact geodesics (rows and far estimates together).
  {
    smci::Exact_geodesic_solver exact(m);
    double error = 0, diameter = 0;
    int count = 0;
    for(int s : {1, n / 2, n - 2})
    {
      std::vector<double> de;
      exact.distances(s, de);
      for(int v = 0; v < n; ++v)
      {
        error += std::abs(local.distance(s, v) - de[v]);
        diameter = std::max(diameter, de[v]);
        ++count;
      }
    }
    BOOST_TEST_MESSAGE("local oracle: mean |error| against exact " << error / count << " (diameter " << diameter << ")");
    BOOST_TEST(error / count < 0.01 * diameter);
  }

  // Batch queries equal single ones; the diagonal is 0.
  std::vector<int> ls(local.row_vertices(7), local.row_vertices(7) + local.row_size(7));
  ls.push_back(n - 1);
  ls.push_back(7);
  std::vector<float> out(ls.size());
  local.distances(7, ls.data(), ls.size(), out.data());
  for(std::size_t i = 0; i < ls.size(); ++i) BOOST_TEST(out[i] == local.distance(7, ls[i]));
  BOOST_TEST(local.distance(7, 7) == 0.f);

  // Set queries (one row walk per source) equal single ones, for sources whose rows hold all, a
  // part or none of the set, and with the source itself in the set; the slots stay untouched.
  {
    std::vector<int> set;
    for(int l = 0; l < n; l += 5) set.push_back(l);
    set.push_back(7);
    std::vector<int> slot(static_cast<std::size_t>(n), 0);
    for(std::size_t p = 0; p < set.size(); ++p) slot[set[p]] = static_cast<int>(p) + 1;
    const std::vector<int> slot_before = slot;
    std::vector<float> row(set.size() + 1);
    int mismatches = 0, local_hits = 0, far_hits = 0;
    for(int k = 0; k < n; ++k)
    {
      local.distances_to_set(k, slot.data(), set.data(), set.size(), row.data());
      for(std::size_t p = 0; p < set.size(); ++p)
      {
        mismatches += row[p + 1] != local.distance(k, set[p]);
        (local.is_local(k, set[p]) ? local_hits : far_hits) += 1;
      }
    }
    BOOST_TEST(mismatches == 0);
    BOOST_TEST(local_hits > 0);
    BOOST_TEST(far_hits > 0);
    BOOST_TEST((slot == slot_before));
  }

#ifdef CGAL_LINKED_WITH_TBB
  const smc::Local_distance_oracle parallel = smc::Local_distance_oracle::build<CGAL::Parallel_tag>(m, radius, 24);
  int differences = 0;
  for(int k = 0; k < n; ++k)
    for(int l = 0; l < n; l += 3) differences += parallel.distance(k, l) != local.distance(k, l);
  BOOST_TEST(differences == 0);
#endif
}

// Several components: +infinity between them, finite inside each (every component gets a
// landmark even when fewer are asked for).
BOOST_AUTO_TEST_CASE(oracles_on_several_components)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(
      disjoint_union(icosphere(2), transformed(icosphere(2), [](const Point& p) {
                       return Point(p.x() + 5, p.y(), p.z());
                     })));
  const int n = m.number_of_vertices(), half = n / 2;
  const auto dense = smc::Dense_distance_oracle::build(m);
  const auto local = smc::Local_distance_oracle::build(m, 0.3, 1);
  BOOST_TEST(local.number_of_landmarks() == 2);
  for(int k = 0; k < n; k += 7)
    for(int l = 0; l < n; l += 5)
    {
      const bool same = (k < half) == (l < half);
      BOOST_TEST(std::isfinite(dense.distance(k, l)) == same);
      BOOST_TEST(std::isfinite(local.distance(k, l)) == same);
    }
}

// The FaceGraph builders read their named parameters; bad parameters throw.
BOOST_AUTO_TEST_CASE(builders_and_parameters)
{
  const Mesh sm = icosphere(2);
  const auto dense = smc::make_dense_distance_oracle(sm);
  const auto heat = smc::make_dense_distance_oracle(sm, smc::parameters::geodesic_method(smc::Geodesic_method::heat_method));
  BOOST_TEST(dense.number_of_vertices() == 162);
  BOOST_TEST(dense.distance(0, 100) != heat.distance(0, 100));
  BOOST_TEST(std::abs(dense.distance(0, 100) - heat.distance(0, 100)) < 0.05);

  const auto local = smc::make_local_distance_oracle(sm, smc::parameters::oracle_landmarks(10, smc::parameters::local_radius(0.5)));
  BOOST_TEST(local.local_radius() == 0.5f);
  BOOST_TEST(local.number_of_landmarks() == 10);
  const auto by_rings = smc::make_local_distance_oracle(sm, smc::parameters::oracle_radius(3.0));
  const smci::Indexed_mesh m = smci::make_indexed_mesh(sm);
  BOOST_TEST(by_rings.local_radius() == static_cast<float>(3 * smci::Edge_length_graph(m).mean_edge_length),
             boost::test_tools::tolerance(1e-6f));
  BOOST_TEST(by_rings.number_of_landmarks() == std::min(162, smc::Matching_settings().oracle_landmarks));
  for(int l = 0; l < 162; ++l)
    if(local.is_local(0, l)) BOOST_TEST(std::abs(local.distance(0, l) - dense.distance(0, l)) < 1e-3f);

  BOOST_TEST(contains(error_of([&] { smc::make_local_distance_oracle(sm, smc::parameters::local_radius(-1.0)); }),
                      "local radius"));
  BOOST_TEST(contains(error_of([&] { smc::make_local_distance_oracle(sm, smc::parameters::oracle_landmarks(0)); }),
                      "landmarks"));
  const Mesh empty;
  BOOST_TEST(contains(error_of([&] { smc::make_dense_distance_oracle(empty); }), "empty"));
}

// Non-manifold meshes: the distances of the tufted cover are those of the surface, and on an open
// book they are known: within a page the Euclidean distance, between two pages the distance in
// the plane where both are unfolded about the spine, sqrt((r_a + r_b)^2 + (z_a - z_b)^2); across
// the pinched vertex of a bow-tie, the sum of the distances to it.
BOOST_AUTO_TEST_CASE(dense_distances_on_non_manifold_meshes_match_the_unfolded_pages)
{
  const int n = 8;
  for(const std::vector<double>& angles : {std::vector<double>{0.0, 0.35, 2.5}, std::vector<double>{0.0, 1.2, 3.14159, 4.3}})
  {
    std::vector<Eigen::Vector3d> points;
    std::vector<std::array<int, 3> > triangles;
    smc_test::add_book(int(angles.size()), n, points, triangles, 0, angles);
    const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
    const smc::Dense_distance_oracle oracle = smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m);
    auto page = [&](int v) { return v <= n ? -1 : (v - (n + 1)) / (n * (n + 1)); };
    double worst = 0;
    for(int a = 0; a < m.number_of_vertices(); ++a)
      for(int b = a + 1; b < m.number_of_vertices(); ++b)
      {
        const Eigen::Vector3d& pa = points[std::size_t(a)];
        const Eigen::Vector3d& pb = points[std::size_t(b)];
        const double ra = std::hypot(pa.x(), pa.y()), rb = std::hypot(pb.x(), pb.y());
        const bool same_page = page(a) < 0 || page(b) < 0 || page(a) == page(b);
        const double exact = same_page ? (pa - pb).norm() : std::hypot(ra + rb, pa.z() - pb.z());
        worst = std::max(worst, std::abs(double(oracle.distance(a, b)) - exact) / exact);
      }
    BOOST_TEST_MESSAGE(angles.size() << " pages: largest relative error " << worst);
    BOOST_TEST(worst < 1e-6);  // exact: the wave crosses the spine as a plane or circular front
  }
  // A bow-tie: two unit squares (n x n grids) in different planes sharing one corner.
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3> > triangles;
  for(int square = 0; square < 2; ++square)
  {
    const int base = int(points.size());
    auto vertex = [&](int i, int j) { return i == 0 && j == 0 ? 0 : base + i * (n + 1) + j - (square == 0 ? 0 : 1); };
    for(int i = 0; i <= n; ++i)
      for(int j = 0; j <= n; ++j)
      {
        if(square == 1 && i == 0 && j == 0) continue;
        const double x = double(i) / n, y = double(j) / n;
        points.push_back(square == 0 ? Eigen::Vector3d(x, y, 0) : Eigen::Vector3d(-x, 0.3 * y, -y));
      }
    for(int i = 0; i < n; ++i)
      for(int j = 0; j < n; ++j)
      {
        triangles.push_back({{vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)}});
        triangles.push_back({{vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)}});
      }
  }
  const smc::internal::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
  BOOST_TEST(m.number_of_components == 1);
  const smc::Dense_distance_oracle oracle = smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m);
  const int first = (n + 1) * (n + 1);  // the first vertex of the second square
  double worst = 0;
  for(int a = 1; a < first; ++a)
    for(int b = first; b < m.number_of_vertices(); ++b)
    {
      const double exact = points[std::size_t(a)].norm() + points[std::size_t(b)].norm();
      worst = std::max(worst, std::abs(double(oracle.distance(a, b)) - exact) / exact);
    }
  // Beyond the pinch the wave restarts from one vertex with an offset, which the circular update
  // (exact for one source on a flat mesh) only approximates: first-order accuracy, 1.3% at worst.
  BOOST_TEST_MESSAGE("bow-tie: largest relative error " << worst);
  BOOST_TEST(worst < 0.02);
}

// The local oracle, k-rings and farthest point sampling on a non-manifold mesh (an open book of
// three pages at uneven angles): local rows hold the pairs within the radius at the analytic
// distances, far pairs get estimates within the landmark bound; k-rings and samples equal a
// breadth-first search and a farthest point sampling written here over the triangles.
BOOST_AUTO_TEST_CASE(local_oracle_rings_and_sampling_on_non_manifold_meshes)
{
  const int n = 8;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3> > triangles;
  smc_test::add_book(3, n, points, triangles, 0, {0.0, 0.35, 2.5});
  const smci::Indexed_mesh m = smc_test::soup_mesh(points, triangles);
  const int nv = m.number_of_vertices();
  auto page = [&](int v) { return v <= n ? -1 : (v - (n + 1)) / (n * (n + 1)); };
  auto exact = [&](int a, int b) {
    const Eigen::Vector3d& pa = points[std::size_t(a)];
    const Eigen::Vector3d& pb = points[std::size_t(b)];
    if(page(a) < 0 || page(b) < 0 || page(a) == page(b)) return (pa - pb).norm();
    return std::hypot(std::hypot(pa.x(), pa.y()) + std::hypot(pb.x(), pb.y()), pa.z() - pb.z());
  };
  const double radius = 0.3;
  const smc::Local_distance_oracle local = smc::Local_distance_oracle::build(m, radius, 12);
  int wrong_rows = 0, wrong_values = 0, outside_bound = 0;
  for(int k = 0; k < nv; ++k)
    for(int l = 0; l < nv; ++l)
    {
      const double d = exact(k, l);
      if(std::abs(d - radius) < 1e-5) continue;  // on the radius: either way within float rounding
      if((d <= radius) != local.is_local(k, l)) ++wrong_rows;
      if(k == l) continue;
      const double e = local.distance(k, l);
      if(d <= radius)
      {
        if(std::abs(e - d) > 1e-5 * d) ++wrong_values;
      }
      else if(e < d * (1 - 1e-5) || e > d + 2 * local.covering_radius() + 1e-5)
        ++outside_bound;
    }
  BOOST_TEST(wrong_rows == 0);
  BOOST_TEST(wrong_values == 0);
  BOOST_TEST(outside_bound == 0);

  // Neighbours: the vertices sharing a triangle, whatever the number of triangles per edge.
  std::vector<std::set<int> > adjacent(static_cast<std::size_t>(nv));
  for(const auto& t : triangles)
    for(int a = 0; a < 3; ++a)
      for(int b = 0; b < 3; ++b)
        if(a != b) adjacent[std::size_t(t[std::size_t(a)])].insert(t[std::size_t(b)]);
  smci::K_ring_workspace rings(m);
  for(int seed : {0, n / 2, n + 3, nv - 1})
    for(int k : {1, 2, 3})
    {
      std::vector<int> ring;
      rings.k_ring(&seed, 1, k, ring);
      std::vector<int> level(std::size_t(nv), -1), queue = {seed};
      level[std::size_t(seed)] = 0;
      for(std::size_t q = 0; q < queue.size(); ++q)
        for(int w : adjacent[std::size_t(queue[q])])
          if(level[std::size_t(w)] < 0 && level[std::size_t(queue[q])] < k)
          {
            level[std::size_t(w)] = level[std::size_t(queue[q])] + 1;
            queue.push_back(w);
          }
      std::sort(ring.begin(), ring.end());
      std::sort(queue.begin(), queue.end());
      BOOST_TEST((ring == queue));
    }

  // Farthest point sampling along the edges: each sample is (up to rounding: the grids have ties)
  // the farthest vertex from the samples before it, by shortest paths along the triangles'
  // edges computed here by repeated relaxation.
  std::vector<int> samples;
  smci::Edge_length_graph graph(m);
  smci::Farthest_point_sampler sampler(graph);
  std::vector<int> all(static_cast<std::size_t>(nv));
  for(int v = 0; v < nv; ++v) all[std::size_t(v)] = v;
  sampler.sample(all.data(), all.size(), nullptr, 0, 20, samples);
  BOOST_TEST_REQUIRE(samples.size() == 20u);
  BOOST_TEST(samples[0] == 0);
  std::vector<double> nearest(std::size_t(nv), std::numeric_limits<double>::infinity());
  int not_farthest = 0;
  for(std::size_t s = 0; s < samples.size(); ++s)
  {
    if(s > 0)
    {
      const double farthest = *std::max_element(nearest.begin(), nearest.end());
      if(nearest[std::size_t(samples[s])] < farthest * (1 - 1e-9)) ++not_farthest;
    }
    std::vector<double> d(std::size_t(nv), std::numeric_limits<double>::infinity());
    d[std::size_t(samples[s])] = 0;
    for(bool changed = true; changed;)
    {
      changed = false;
      for(int v = 0; v < nv; ++v)
        for(int w : adjacent[std::size_t(v)])
        {
          const double through = d[std::size_t(v)] + (points[std::size_t(v)] - points[std::size_t(w)]).norm();
          if(through < d[std::size_t(w)] * (1 - 1e-12))
          {
            d[std::size_t(w)] = through;
            changed = true;
          }
        }
    }
    for(int v = 0; v < nv; ++v) nearest[std::size_t(v)] = std::min(nearest[std::size_t(v)], d[std::size_t(v)]);
  }
  BOOST_TEST(not_farthest == 0);
}

BOOST_AUTO_TEST_SUITE_END()
