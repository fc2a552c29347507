// SPDX-License-Identifier: GPL-3.0-or-later
// k-ring neighbourhoods, geodesic balls and farthest point sampling, against brute-force
// references (breadth-first search written here, thresholded exact distances, an O(m |S|^2)
// farthest point sampling on Floyd-Warshall distances).

#include <CGAL/Surface_mesh_correspondence/neighborhoods.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace smci = CGAL::Surface_mesh_correspondence::internal;
using namespace smc_test;

namespace {

// Brute-force hop distance from a set of seeds: Bellman-Ford style relaxation over the edge list.
std::vector<int> hop_distance(const smci::Indexed_mesh& m, const std::vector<int>& seeds)
{
  std::vector<int> d(m.number_of_vertices(), 1 << 29);
  for(int s : seeds) d[s] = 0;
  for(bool changed = true; changed;)
  {
    changed = false;
    for(const auto& e : m.edges)
    {
      if(d[e[0]] + 1 < d[e[1]]) d[e[1]] = d[e[0]] + 1, changed = true;
      if(d[e[1]] + 1 < d[e[0]]) d[e[0]] = d[e[1]] + 1, changed = true;
    }
  }
  return d;
}

// All-pairs shortest paths inside the set S along edges with both ends in S (Floyd-Warshall).
std::vector<std::vector<double> > set_distances(const smci::Indexed_mesh& m, const std::vector<int>& set)
{
  const std::size_t k = set.size();
  std::map<int, std::size_t> local;
  for(std::size_t i = 0; i < k; ++i) local[set[i]] = i;
  std::vector<std::vector<double> > d(k, std::vector<double>(k, inf));
  for(std::size_t i = 0; i < k; ++i) d[i][i] = 0;
  for(const auto& e : m.edges)
  {
    auto a = local.find(e[0]), b = local.find(e[1]);
    if(a == local.end() || b == local.end()) continue;
    const double l = (m.point(e[0]) - m.point(e[1])).norm();
    d[a->second][b->second] = d[b->second][a->second] = l;
  }
  for(std::size_t c = 0; c < k; ++c)
    for(std::size_t i = 0; i < k; ++i)
      for(std::size_t j = 0; j < k; ++j)
        if(d[i][c] + d[c][j] < d[i][j]) d[i][j] = d[i][c] + d[c][j];
  return d;
}

// Reference farthest point sampling, O(m |S|^2) from the all-pairs distances.
std::vector<int> reference_fps(const smci::Indexed_mesh& m, const std::vector<int>& set,
                               const std::vector<int>& seeds, int count)
{
  std::vector<int> members;
  for(int v : set)
    if(std::find(members.begin(), members.end(), v) == members.end()) members.push_back(v);
  const auto d = set_distances(m, members);
  auto local = [&](int v) {
    return static_cast<std::size_t>(std::find(members.begin(), members.end(), v) - members.begin());
  };
  std::vector<int> out;
  for(int s : seeds)
    if(std::find(out.begin(), out.end(), s) == out.end() && static_cast<int>(out.size()) < count)
      out.push_back(s);
  while(static_cast<int>(out.size()) < std::min<int>(count, static_cast<int>(members.size())))
  {
    int best = -1;
    double best_d = -1;
    for(int v : members)
    {
      if(std::find(out.begin(), out.end(), v) != out.end()) continue;
      double dv = inf;
      for(int p : out) dv = std::min(dv, d[local(v)][local(p)]);
      if(out.empty()) dv = inf;
      if(dv > best_d || (dv == best_d && v < best))
      {
        best_d = dv;
        best = v;
      }
    }
    out.push_back(best);
  }
  return out;
}

} // namespace

BOOST_AUTO_TEST_SUITE(neighborhoods)

// Interior vertices of a valence-6 grid: the k-ring has 1 + 3k(k+1) vertices; on every mesh the
// k-ring of a set equals the brute-force hop-distance threshold, in breadth-first order.
BOOST_AUTO_TEST_CASE(k_rings)
{
  {
    const smci::Indexed_mesh m = smci::make_indexed_mesh(regular_grid(20, 20));
    smci::K_ring_workspace ws(m);
    std::vector<int> ring;
    const int center = 10 * 21 + 10;
    BOOST_TEST(m.degree(center) == 6);
    for(int k = 0; k <= 8; ++k)
    {
      ws.k_ring(&center, 1, k, ring);
      BOOST_TEST(static_cast<int>(ring.size()) == 1 + 3 * k * (k + 1));
    }
  }
  const Mesh meshes[3] = {icosphere(3), regular_grid(15, 9, 1, 1, true),
                          disjoint_union(icosphere(1), capsule(10, 3, 5))};
  for(const Mesh& mesh : meshes)
  {
    const smci::Indexed_mesh m = smci::make_indexed_mesh(mesh);
    smci::K_ring_workspace ws(m);
    std::vector<int> ring;
    const std::vector<std::vector<int> > seed_sets = {{0}, {5, 17}, {3, 3, m.number_of_vertices() - 1}};
    for(const auto& seeds : seed_sets)
    {
      const std::vector<int> hops = hop_distance(m, seeds);
      for(int k : {0, 1, 2, 4, 6})
      {
        ws.k_ring(seeds.data(), seeds.size(), k, ring);
        std::set<int> expected;
        for(int v = 0; v < m.number_of_vertices(); ++v)
          if(hops[v] <= k) expected.insert(v);
        BOOST_TEST((std::set<int>(ring.begin(), ring.end()) == expected));
        BOOST_TEST(ring.size() == expected.size());  // no duplicates
        BOOST_TEST(ring[0] == seeds[0]);
        for(std::size_t i = 1; i < ring.size(); ++i) BOOST_TEST(hops[ring[i - 1]] <= hops[ring[i]]);
        for(int v : ring) BOOST_TEST(ws.level(v) == hops[v]);
      }
    }
  }
}

// Geodesic balls contain every vertex whose exact distance is clearly inside the radius and no
// vertex clearly outside it (fast marching errors are within 2% here), and match thresholded
// fast marching exactly.
BOOST_AUTO_TEST_CASE(geodesic_balls)
{
  const smci::Indexed_mesh m = smci::make_indexed_mesh(icosphere(3));
  smci::Exact_geodesic_solver exact(m);
  smci::Fast_marching_geometry g(m);
  smci::Fast_marching_workspace ws(g), full(g);
  std::vector<int> ball;
  for(int s : {0, 100, 400})
  {
    std::vector<double> de;
    exact.distances(s, de);
    full.run(s);
    for(double r : {0.0, 0.2, 0.5, 1.3})
    {
      smci::geodesic_ball(ws, &s, 1, r, ball);
      const std::set<int> in(ball.begin(), ball.end());
      BOOST_TEST(in.size() == ball.size());
      BOOST_TEST(ball[0] == s);
      for(int v = 0; v < m.number_of_vertices(); ++v)
      {
        if(de[v] < 0.98 * r) BOOST_TEST(in.count(v) == 1u);
        if(de[v] > 1.02 * r + 1e-12) BOOST_TEST(in.count(v) == 0u);
        BOOST_TEST((in.count(v) == 1u) == (full.distance(v) <= r));
      }
    }
  }
  // A ball around a set is the union of the single balls (up to fast marching interaction at
  // the meeting points, none of which lies at the radius here).
  const int seeds[2] = {0, 300};
  smci::geodesic_ball(ws, seeds, 2, 0.3, ball);
  std::set<int> expected;
  for(int s : seeds)
  {
    std::vector<int> b;
    smci::geodesic_ball(ws, &s, 1, 0.3, b);
    expected.insert(b.begin(), b.end());
  }
  BOOST_TEST((std::set<int>(ball.begin(), ball.end()) == expected));
}

// Farthest point sampling: seeds first, no duplicates, each new sample the farthest from the
// previous ones by the restricted edge distance (brute-force reference), deterministic, and all
// of a set smaller than the sample count.
BOOST_AUTO_TEST_CASE(farthest_point_sampling_internal)
{
  // An irregular closed mesh (no ties: the sequences must be identical to the reference) and a
  // grid with a hole (many equal-length paths, summed in different orders by the two
  // algorithms: the farthest property is checked up to rounding).
  const Mesh meshes[2] = {transformed(icosphere(3), [](const Point& p) {
                            return Point(p.x() * 1.3, p.y() * (1 + 0.2 * p.z()), p.z());
                          }),
                          regular_grid(24, 24, 24, 24, true)};
  for(int mesh_index = 0; mesh_index < 2; ++mesh_index)
  {
    const Mesh& mesh = meshes[mesh_index];
    const smci::Indexed_mesh m = smci::make_indexed_mesh(mesh);
    smci::Edge_length_graph graph(m);
    smci::Farthest_point_sampler sampler(graph), other(graph);
    smci::K_ring_workspace rings(m);
    std::vector<int> set, samples, again;
    for(int trial = 0; trial < 6; ++trial)
    {
      const int x = (trial * 131 + 7) % m.number_of_vertices();
      const int y = (trial * 57 + 300) % m.number_of_vertices();
      const int seeds[2] = {x, y};
      rings.k_ring(seeds, 2, 3, set);  // union of the 3-rings of x and y (maybe disconnected)
      for(int count : {1, 2, 10, 25})
      {
        sampler.sample(set.data(), set.size(), seeds, 2, count, samples);
        if(mesh_index == 0)
          BOOST_TEST(samples == reference_fps(m, set, {x, y}, count));
        else
        {
          std::vector<int> members = set;
          std::sort(members.begin(), members.end());
          members.erase(std::unique(members.begin(), members.end()), members.end());
          const auto d = set_distances(m, members);
          auto local = [&](int v) {
            return static_cast<std::size_t>(std::lower_bound(members.begin(), members.end(), v) -
                                            members.begin());
          };
          for(std::size_t j = 2; j < samples.size(); ++j)
          {
            auto nearest = [&](int v) {
              double dv = inf;
              for(std::size_t i = 0; i < j; ++i) dv = std::min(dv, d[local(v)][local(samples[i])]);
              return dv;
            };
            double farthest = 0;
            for(int v : members) farthest = std::max(farthest, nearest(v));
            const double chosen = nearest(samples[j]);
            BOOST_TEST((chosen >= farthest - 1e-9 || (std::isinf(chosen) && std::isinf(farthest))));
          }
        }
        BOOST_TEST(samples.size() == std::min<std::size_t>(count, set.size()));
        BOOST_TEST(samples[0] == x);
        if(count >= 2 && x != y) BOOST_TEST(samples[1] == y);
        BOOST_TEST(std::set<int>(samples.begin(), samples.end()).size() == samples.size());
        other.sample(set.data(), set.size(), seeds, 2, count, again);
        BOOST_TEST(samples == again);
      }
    }
    // Sets smaller than the count: everything, seeds first; duplicated seeds and set entries.
    const int seeds[3] = {4, 4, 2};
    const std::vector<int> small = {2, 9, 4, 5, 9, 4};
    sampler.sample(small.data(), small.size(), seeds, 3, 30, samples);
    const std::vector<int> first = samples;
    BOOST_TEST(samples.size() == 4u);
    BOOST_TEST(samples[0] == 4);
    BOOST_TEST(samples[1] == 2);
    BOOST_TEST((std::set<int>(samples.begin(), samples.end()) == std::set<int>{2, 4, 5, 9}));
    // No seeds: the smallest index first.
    sampler.sample(small.data(), small.size(), nullptr, 0, 2, samples);
    BOOST_TEST(samples[0] == 2);
    // Bad input.
    BOOST_TEST(contains(error_of([&] { sampler.sample(small.data(), small.size(), seeds, 3, 0, samples); }),
                        "must be positive"));
    const int outside = 3;
    BOOST_TEST(contains(error_of([&] { sampler.sample(small.data(), small.size(), &outside, 1, 5, samples); }),
                        "not in the vertex set"));
    const std::vector<int> bad = {1, -4};
    BOOST_TEST(contains(error_of([&] { sampler.sample(bad.data(), bad.size(), nullptr, 0, 5, samples); }),
                        "out of range"));
    // Still usable after the exceptions.
    sampler.sample(small.data(), small.size(), seeds, 3, 30, again);
    BOOST_TEST(again == first);
  }

  // Ties are broken by the smallest index: the 1-ring of an interior vertex of an integer grid
  // (its two diagonal neighbours are exactly sqrt(2) away, the others 1).
  const smci::Indexed_mesh m = smci::make_indexed_mesh(regular_grid(6, 6, 6, 6));
  smci::Edge_length_graph graph(m);
  smci::Farthest_point_sampler sampler(graph);
  smci::K_ring_workspace rings(m);
  std::vector<int> set, samples;
  const int center = 3 * 7 + 3;
  rings.k_ring(&center, 1, 1, set);
  sampler.sample(set.data(), set.size(), &center, 1, 2, samples);
  BOOST_TEST(samples[1] == 2 * 7 + 2);  // (2, 2) before (4, 4)
  std::reverse(set.begin(), set.end());
  sampler.sample(set.data(), set.size(), &center, 1, 2, samples);
  BOOST_TEST(samples[1] == 2 * 7 + 2);
}

// The FaceGraph functions, on Surface_mesh and Polyhedron_3, and their bad input.
BOOST_AUTO_TEST_CASE(public_functions)
{
  typedef CGAL::Polyhedron_3<Kernel> Polyhedron;
  typedef boost::graph_traits<Polyhedron>::vertex_descriptor Pvertex;
  Mesh sm = icosphere(3);
  Polyhedron poly;
  CGAL::copy_face_graph(sm, poly);
  std::map<Point, Vertex> sm_of;
  for(Vertex v : sm.vertices()) sm_of[sm.point(v)] = v;
  std::map<Vertex, Pvertex> poly_of;
  for(Pvertex v : vertices(poly)) poly_of[sm_of.at(v->point())] = v;
  auto to_sm = [&](const std::vector<Pvertex>& vs) {
    std::vector<Vertex> out;
    for(Pvertex v : vs) out.push_back(sm_of.at(v->point()));
    return out;
  };

  std::vector<Vertex> a;
  std::vector<Pvertex> b;
  smc::k_ring_neighborhood(sm, Vertex(5), 3, std::back_inserter(a));
  smc::k_ring_neighborhood(poly, poly_of[Vertex(5)], 3, std::back_inserter(b));
  {
    const std::vector<Vertex> bs = to_sm(b);
    BOOST_TEST((std::set<Vertex>(a.begin(), a.end()) == std::set<Vertex>(bs.begin(), bs.end())));
  }
  BOOST_TEST(a.size() == 31u);  // vertex 5 is an icosahedron vertex (valence 5): 1 + 5 + 10 + 15

  a.clear();
  b.clear();
  smc::geodesic_ball(sm, std::vector<Vertex>{Vertex(5), Vertex(50)}, 0.25, std::back_inserter(a));
  smc::geodesic_ball(poly, std::vector<Pvertex>{poly_of[Vertex(5)], poly_of[Vertex(50)]}, 0.25,
                     std::back_inserter(b));
  BOOST_TEST(a.size() == b.size());
  {
    const std::vector<Vertex> bs = to_sm(b);
    BOOST_TEST((std::set<Vertex>(a.begin(), a.end()) == std::set<Vertex>(bs.begin(), bs.end())));
  }

  std::vector<Vertex> set;
  smc::k_ring_neighborhood(sm, std::vector<Vertex>{Vertex(5), Vertex(50)}, 4, std::back_inserter(set));
  std::vector<Pvertex> pset;
  for(Vertex v : set) pset.push_back(poly_of[v]);
  a.clear();
  b.clear();
  smc::farthest_point_sampling(sm, set, 12, std::back_inserter(a),
                               smc::parameters::seed_vertices(std::vector<Vertex>{Vertex(50), Vertex(5)}));
  smc::farthest_point_sampling(poly, pset, 12, std::back_inserter(b),
                               smc::parameters::seed_vertices(std::vector<Pvertex>{poly_of[Vertex(50)], poly_of[Vertex(5)]}));
  BOOST_TEST(a.size() == 12u);
  BOOST_TEST(a[0] == Vertex(50));
  BOOST_TEST(a[1] == Vertex(5));
  BOOST_TEST((a == to_sm(b)));

  BOOST_TEST(contains(error_of([&] { smc::k_ring_neighborhood(sm, Vertex(5), -1, std::back_inserter(a)); }),
                      "must be >= 0"));
  BOOST_TEST(contains(error_of([&] { smc::k_ring_neighborhood(sm, Vertex(5000), 1, std::back_inserter(a)); }),
                      "out of range"));
  BOOST_TEST(contains(error_of([&] { smc::geodesic_ball(sm, Vertex(5), -0.5, std::back_inserter(a)); }),
                      "radius"));
  BOOST_TEST(contains(error_of([&] { smc::farthest_point_sampling(sm, set, 0, std::back_inserter(a)); }),
                      "must be positive"));
  BOOST_TEST(contains(error_of([&] {
                        smc::farthest_point_sampling(sm, set, 5, std::back_inserter(a),
                                                     smc::parameters::seed_vertices(std::vector<Vertex>{Vertex(600)}));
                      }),
                      "not in the vertex set"));
}

BOOST_AUTO_TEST_SUITE_END()
