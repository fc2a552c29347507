// SPDX-License-Identifier: GPL-3.0-or-later
// Coupled refinement: the parts checked on small hand-made cases (inverse map, candidate sets,
// unary and pairwise terms), and the whole algorithm on a bent, remeshed capsule with ground
// truth from the construction.

#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include "test_pairs.h"

#include <boost/property_map/vector_property_map.hpp>
#include <boost/test/unit_test.hpp>

#include <numeric>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = smc::parameters;
using namespace smc_test;

namespace {

typedef smc::Correspondence_shape<Mesh> Shape;

// Descriptor weights that keep the small test shapes cheap: SHOT and WKS.
auto shape_parameters() { return params::number_of_eigenpairs(40); }

struct Fixture
{
  Shape_pair pair;
  Shape s1, s2;
  smc::Map_evaluator<> on1, on2;
  Fixture()
      : pair(bent_pair(bumpy_capsule(), 4.0, 1.0, true)), s1(pair.m1, shape_parameters()),
        s2(pair.m2, shape_parameters()), on1(pair.m1), on2(pair.m2)
  {}
  double error_12(const smc::Vertex_index_map_vector& m12) const
  {
    return on2.geodesic_errors(m12, all_vertices(m12.size()), pair.gt_12).mean;
  }
  double error_21(const smc::Vertex_index_map_vector& m21) const
  {
    return on1.geodesic_errors(m21, all_vertices(m21.size()), pair.gt_21).mean;
  }
};

const Fixture& fixture()
{
  static const Fixture f;
  return f;
}

} // namespace

BOOST_AUTO_TEST_SUITE(coupled_refinement)

BOOST_AUTO_TEST_CASE(inverse_map_follows_section_6)
{
  // Source: a 2 x 1 grid (6 vertices); target: a 4 x 1 grid (10 vertices), x in [0, 1].
  const Mesh src = grid(2, 1), tgt = grid(4, 1);
  smc::internal::Shape_data S, T;
  S.mesh = smc::internal::make_indexed_mesh(src);
  T.mesh = smc::internal::make_indexed_mesh(tgt);
  T.nearest.reset(new smc::internal::Nearest_vertex_search(T.mesh));
  // opposite map T -> S: target vertices (0,0), (0.25,0) go to source vertex 0, (0.5,0), (0.75,0)
  // and (1,0) go to source vertex 1; the top row all go to source vertex 3.
  std::vector<int> opposite = {0, 0, 1, 1, 1, 3, 3, 3, 3, 3};
  std::vector<int> current = {9, 8, 7, 6, 5, 4};
  const std::vector<int> inv = smc::internal::inverse_map(S, T, opposite, current);
  BOOST_TEST(inv[0] == 0);  // mean of (0,0) and (0.25,0) is (0.125,0): nearest is vertex 0 (tie by index)
  BOOST_TEST(inv[1] == 3);  // mean of x = 0.5, 0.75, 1 is 0.75: vertex 3
  BOOST_TEST(inv[2] == 7);  // no preimage: the current map
  BOOST_TEST(inv[3] == 7);  // mean of the top row (x = 0.5, y = 1): vertex 7
  BOOST_TEST(inv[4] == 5);
  BOOST_TEST(inv[5] == 4);
}

BOOST_AUTO_TEST_CASE(candidate_sets_and_energy_terms)
{
  const Fixture& f = fixture();
  const auto& S = f.s1.data();
  const auto& T = f.s2.data();
  const int n = S.number_of_vertices();
  std::vector<int> x(f.pair.gt_12.begin(), f.pair.gt_12.end());
  std::vector<int> xt = smc::internal::to_int_map(perturbed(f.pair.gt_12, f.pair.m2, 0.5, 5, 3));
  smc::Refinement_settings settings;
  settings.number_of_candidates = 12;
  settings.use_neighbor_matches = false;
  smc::internal::Refinement_workspace<CGAL::Sequential_tag> w;
  smc::internal::select_candidates<CGAL::Sequential_tag>(S, T, x, xt, 3, settings, w.candidates);
  const auto& C = w.candidates;
  BOOST_TEST(C.offsets.size() == static_cast<std::size_t>(n) + 1);
  for(int u = 0; u < n; ++u)
  {
    const int i = S.node_order[u];
    const int* b = C.labels.data() + C.offsets[u];
    const int size = C.offsets[u + 1] - C.offsets[u];
    BOOST_TEST(size == 12);  // the union of two 3-rings always has more than 12 vertices here
    BOOST_TEST(b[0] == x[i]);
    BOOST_TEST(std::find(b, b + size, xt[i]) != b + size);
    std::vector<int> sorted(b, b + size);
    std::sort(sorted.begin(), sorted.end());
    BOOST_TEST((std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()));
  }
  // Non-coupled: candidates around x(i) only, so x~(i) is absent when it is far away.
  settings.use_coupling = false;
  smc::internal::Candidate_sets single;
  smc::internal::select_candidates<CGAL::Sequential_tag>(S, T, x, xt, 1, settings, single);
  int absent = 0;
  for(int u = 0; u < n; ++u)
  {
    const int i = S.node_order[u];
    const int* b = single.labels.data() + single.offsets[u];
    const int* e = single.labels.data() + single.offsets[u + 1];
    BOOST_TEST(e - b <= 12);
    absent += std::find(b, e, xt[i]) == e;
  }
  BOOST_TEST(absent > n / 4);

  // The energy: unary mu |F1 - F2|^2 + lambda d1(i, x21(k)) and pairwise |d1 - d2| recomputed
  // independently.
  settings.use_coupling = true;
  settings.unary_weight = 0.3;
  settings.consistency_weight = 0.7;
  const std::vector<int> x21 = smc::internal::to_int_map(perturbed(f.pair.gt_21, f.pair.m1, 0.5, 5, 4));
  smc::internal::build_energy<CGAL::Sequential_tag>(S, T, x21, settings, w);
  BOOST_TEST(w.energy.number_of_nodes() == static_cast<std::size_t>(n));
  BOOST_TEST(w.energy.number_of_edges() == S.mesh.edges.size());
  const auto& o1 = std::get<smc::Local_distance_oracle>(S.oracle);
  const auto& o2 = std::get<smc::Local_distance_oracle>(T.oracle);
  int cycle_terms = 0;
  for(int u = 0; u < n; u += 37)
  {
    const int i = S.node_order[u];
    for(int a = 0; a < 12; ++a)
    {
      const int k = C.labels[C.offsets[u] + a];
      const double cycle = o1.distance(i, x21[k]) / S.scale;
      cycle_terms += cycle > 0;
      const double expected =
          0.3 * (f.s1.descriptors().row(i) - f.s2.descriptors().row(k)).cast<double>().squaredNorm() + 0.7 * cycle;
      BOOST_TEST(w.energy.unary_cost(u, a) == expected, boost::test_tools::tolerance(1e-4));
    }
  }
  BOOST_TEST(cycle_terms > 0);
  for(std::size_t e = 0; e < w.energy.number_of_edges(); e += 101)
  {
    const int u = static_cast<int>(w.energy.source(e)), v = static_cast<int>(w.energy.target(e));
    const double d1 = o1.distance(S.node_order[u], S.node_order[v]) / S.scale;
    for(int a = 0; a < 12; ++a)
      for(int b = 0; b < 12; ++b)
      {
        const double d2 = o2.distance(C.labels[C.offsets[u] + a], C.labels[C.offsets[v] + b]) / T.scale;
        BOOST_TEST(std::abs(w.energy.pairwise_cost(e, a, b) - std::abs(d1 - d2)) < 1e-6);
      }
  }
}

BOOST_AUTO_TEST_CASE(perturbed_maps_are_improved)
{
  const Fixture& f = fixture();
  double before = 0, after = 0;
  for(unsigned seed : {1u, 2u})
  {
    smc::Vertex_index_map_vector m12 = perturbed(f.pair.gt_12, f.pair.m2, 0.3, 4, seed);
    smc::Vertex_index_map_vector m21 = perturbed(f.pair.gt_21, f.pair.m1, 0.3, 4, seed + 10);
    const double e0 = f.error_12(m12) + f.error_21(m21);
    const std::size_t c0 = smc::number_of_inconsistent_vertices(m12, m21);
    const smc::Coupled_refinement_result r = smc::refine_coupled_maps(f.s1, f.s2, m12, m21);
    const double e1 = f.error_12(m12) + f.error_21(m21);
    BOOST_TEST_MESSAGE("seed " << seed << ": error 1->2 + 2->1 " << e0 << " -> " << e1 << ", inconsistent vertices "
                               << c0 << " -> " << r.inconsistent_vertices_after << " (" << r.outer_iterations
                               << " outer iterations, " << smc::to_string(r.termination) << ")");
    BOOST_TEST(r.inconsistent_vertices_before == c0);
    BOOST_TEST(r.inconsistent_vertices_after == smc::number_of_inconsistent_vertices(m12, m21));
    BOOST_TEST(r.inconsistent_vertices_after < c0);
    BOOST_TEST(e1 < 0.6 * e0);
    before += e0;
    after += e1;
  }
  BOOST_TEST(after < 0.5 * before);
}

BOOST_AUTO_TEST_CASE(the_origin_of_the_maps_sets_five_defaults_and_given_parameters_win)
{
  const smc::Refinement_settings given = smc::Refinement_settings::from(params::default_values(), smc::Map_origin::given);
  BOOST_TEST(given.number_of_candidates == 20);
  BOOST_TEST((given.ring_schedule == std::vector<int>{6, 4, 3, 2, 1}));
  BOOST_TEST(given.consistency_weight == 1.0);
  BOOST_TEST(!given.stop_when_consistency_worsens);
  BOOST_TEST(given.trws_number_of_iterations == 100);

  const smc::Refinement_settings automatic =
      smc::Refinement_settings::from(params::default_values(), smc::Map_origin::automatic);
  BOOST_TEST(automatic.number_of_candidates == 40);
  BOOST_TEST((automatic.ring_schedule == std::vector<int>{4, 3, 2, 1}));
  BOOST_TEST(automatic.consistency_weight == 0.5);
  BOOST_TEST(automatic.stop_when_consistency_worsens);
  BOOST_TEST(automatic.trws_number_of_iterations == 15);
  BOOST_TEST(automatic.unary_weight == given.unary_weight);  // not one of the five
  BOOST_TEST(automatic.use_coupling);
  // The struct's own defaults are the registry's for automatic maps.
  const smc::Refinement_settings plain;
  BOOST_TEST(plain.number_of_candidates == automatic.number_of_candidates);
  BOOST_TEST((plain.ring_schedule == automatic.ring_schedule));

  // A parameter given explicitly overrides the origin's default, directly or in matching_settings.
  smc::Matching_settings m;
  m.set("number_of_candidates", 7.0);
  for(const smc::Refinement_settings& s :
      {smc::Refinement_settings::from(params::number_of_candidates(7), smc::Map_origin::given),
       smc::Refinement_settings::from(params::matching_settings(m), smc::Map_origin::given)})
  {
    BOOST_TEST(s.number_of_candidates == 7);
    BOOST_TEST((s.ring_schedule == std::vector<int>{6, 4, 3, 2, 1}));
    BOOST_TEST(s.trws_number_of_iterations == 100);
  }

  // refine_coupled_maps() uses the defaults for given maps: the same as the five parameters.
  const Fixture& f = fixture();
  smc::Vertex_index_map_vector a12 = perturbed(f.pair.gt_12, f.pair.m2, 0.3, 4, 5u);
  smc::Vertex_index_map_vector a21 = perturbed(f.pair.gt_21, f.pair.m1, 0.3, 4, 15u);
  smc::Vertex_index_map_vector b12 = a12, b21 = a21;
  const smc::Coupled_refinement_result ra = smc::refine_coupled_maps(f.s1, f.s2, a12, a21);
  const smc::Coupled_refinement_result rb = smc::refine_coupled_maps(
      f.s1, f.s2, b12, b21,
      params::consistency_weight(
          1.0, params::stop_when_consistency_worsens(
                   false, params::ring_schedule(std::vector<int>{6, 4, 3, 2, 1},
                                                params::number_of_candidates(20, params::trws_number_of_iterations(100))))));
  BOOST_TEST(ra.steps.size() == rb.steps.size());
  BOOST_TEST(!ra.steps.empty());
  BOOST_TEST(ra.steps.front().rings == 6);
  BOOST_TEST((a12 == b12));
  BOOST_TEST((a21 == b21));
  // With the five automatic values the solves are shorter.
  smc::Vertex_index_map_vector c12 = perturbed(f.pair.gt_12, f.pair.m2, 0.3, 4, 5u);
  smc::Vertex_index_map_vector c21 = perturbed(f.pair.gt_21, f.pair.m1, 0.3, 4, 15u);
  const smc::Coupled_refinement_result rc =
      smc::refine_coupled_maps(f.s1, f.s2, c12, c21, params::trws_number_of_iterations(15, params::ring_schedule(std::vector<int>{4, 3, 2, 1})));
  BOOST_TEST(!rc.steps.empty());
  for(const smc::Refinement_step& step : rc.steps) BOOST_TEST(step.trws_iterations <= 15u);
  BOOST_TEST(rc.steps.front().rings == 4);
}

BOOST_AUTO_TEST_CASE(exact_maps_stay_exact)
{
  // Same connectivity, isometric bend of a strip-like tube: the identity is the ground truth.
  const Mesh m1 = bumpy_capsule(20, 5, 12);
  const Shape_pair p = bent_pair(m1, 4.0, 0.8, false);
  const Shape s1(p.m1, shape_parameters()), s2(p.m2, shape_parameters());
  smc::Vertex_index_map_vector m12 = all_vertices(num_vertices(m1)), m21 = m12;
  smc::refine_coupled_maps(s1, s2, m12, m21);
  std::size_t moved = 0;
  for(std::size_t i = 0; i < m12.size(); ++i) moved += (m12[i] != i) + (m21[i] != i);
  BOOST_TEST_MESSAGE("identity maps: " << moved << " of " << 2 * m12.size() << " matches moved");
  BOOST_TEST(moved <= m12.size() / 50);
  smc::Map_evaluator<> on2(p.m2);
  BOOST_TEST(on2.geodesic_errors(m12, all_vertices(m12.size()), all_vertices(m12.size())).mean < 0.003);
}

BOOST_AUTO_TEST_CASE(coupling_helps)
{
  // Regions of one map slid by a few rings while the other map is right there: the inverse of
  // the other map brings the right candidates (the paper's Fig. 14 ablation).
  const Fixture& f = fixture();
  double coupled = 0, single = 0;
  for(unsigned seed : {5u, 6u, 7u})
  {
    const smc::Vertex_index_map_vector m12 = patch_shifted(f.pair.gt_12, f.pair.m1, 4, 4, 8, seed);
    const smc::Vertex_index_map_vector m21 = patch_shifted(f.pair.gt_21, f.pair.m2, 4, 4, 8, seed + 20);
    for(bool coupling : {true, false})
    {
      smc::Vertex_index_map_vector a = m12, b = m21;
      smc::refine_coupled_maps(f.s1, f.s2, a, b, params::use_coupling(coupling));
      (coupling ? coupled : single) += f.error_12(a) + f.error_21(b);
    }
  }
  BOOST_TEST_MESSAGE("mean error, coupled " << coupled / 6 << ", non-coupled " << single / 6);
  BOOST_TEST(coupled < single);
}

BOOST_AUTO_TEST_CASE(cycle_term_makes_the_maps_more_consistent_and_accurate)
{
  // The unary term lambda d_S(i, x_ba(k)) prefers the candidates that the opposite map sends back
  // near i: against the paper's energy (lambda = 0), the refined maps are more consistent, by
  // Eq. (4) and by the cycle distance, and not less accurate.
  const Fixture& f = fixture();
  std::size_t inconsistent[2] = {0, 0};
  double cycle[2] = {0, 0}, error[2] = {0, 0};
  for(unsigned seed : {3u, 4u})
  {
    const smc::Vertex_index_map_vector m12 = perturbed(f.pair.gt_12, f.pair.m2, 0.3, 4, seed);
    const smc::Vertex_index_map_vector m21 = perturbed(f.pair.gt_21, f.pair.m1, 0.3, 4, seed + 10);
    for(int with : {0, 1})
    {
      smc::Vertex_index_map_vector a = m12, b = m21;
      smc::refine_coupled_maps(f.s1, f.s2, a, b, params::consistency_weight(with ? 1.0 : 0.0));
      inconsistent[with] += smc::number_of_inconsistent_vertices(a, b);
      cycle[with] += f.on1.cycle_consistency(a, b).distances.mean;
      error[with] += f.error_12(a) + f.error_21(b);
    }
  }
  BOOST_TEST_MESSAGE("without / with the cycle term: inconsistent vertices " << inconsistent[0] << " / "
                     << inconsistent[1] << ", cycle error " << cycle[0] << " / " << cycle[1] << ", error "
                     << error[0] << " / " << error[1]);
  BOOST_TEST(inconsistent[1] < inconsistent[0]);
  BOOST_TEST(cycle[1] < cycle[0]);
  BOOST_TEST(error[1] <= error[0]);
}

BOOST_AUTO_TEST_CASE(units_do_not_matter)
{
  const Fixture& f = fixture();
  const smc::Vertex_index_map_vector m12 = perturbed(f.pair.gt_12, f.pair.m2, 0.3, 4, 11);
  const smc::Vertex_index_map_vector m21 = perturbed(f.pair.gt_21, f.pair.m1, 0.3, 4, 12);
  smc::Vertex_index_map_vector a12 = m12, a21 = m21;
  smc::refine_coupled_maps(f.s1, f.s2, a12, a21);
  const double ea = f.error_12(a12) + f.error_21(a21);
  for(double scale : {1024.0, 1000.0})
  {
    const Mesh big = transformed(f.pair.m2, [scale](const Point& p) { return Point(scale * p.x(), scale * p.y(), scale * p.z()); });
    const Shape s2big(big, shape_parameters());
    smc::Vertex_index_map_vector b12 = m12, b21 = m21;
    smc::refine_coupled_maps(f.s1, s2big, b12, b21);
    std::size_t same = 0;
    for(std::size_t i = 0; i < a12.size(); ++i) same += a12[i] == b12[i];
    for(std::size_t i = 0; i < a21.size(); ++i) same += a21[i] == b21[i];
    const double eb = f.error_12(b12) + f.error_21(b21);
    BOOST_TEST_MESSAGE("target scaled by " << scale << ": " << same << " of " << a12.size() + a21.size()
                       << " matches identical, errors " << ea << " and " << eb);
    if(scale == 1024.0)
    {
      // A power of two scales every length, area and eigenvalue exactly: once normalised by the
      // square root of the area, every number is the same, so must be the maps (no absolute
      // tolerance anywhere).
      BOOST_TEST(same == a12.size() + a21.size());
    }
    else
    {
      // Other factors change the last bits, which breaks some near-ties of the MRFs differently
      // (about 10% of the matches with FMA): the maps are equally good, not identical (0.0018
      // apart with FMA; a scale-dependent weight would move them by far more).
      BOOST_TEST(std::abs(eb - ea) < 0.003);
    }
  }
}

BOOST_AUTO_TEST_CASE(generic_entry_point_with_property_maps)
{
  // Polyhedron-free but generic: vertex -> vertex property maps on Surface_mesh.
  const Mesh m1 = bumpy_capsule(16, 4, 10);
  Shape_pair p = bent_pair(m1, 4.0, 0.7, true);
  auto map12 = p.m1.add_property_map<Vertex, Vertex>("v:map12").first;
  auto map21 = p.m2.add_property_map<Vertex, Vertex>("v:map21").first;
  const smc::Vertex_index_map_vector init12 = perturbed(p.gt_12, p.m2, 0.3, 3, 4);
  const smc::Vertex_index_map_vector init21 = perturbed(p.gt_21, p.m1, 0.3, 3, 5);
  for(Vertex v : p.m1.vertices()) map12[v] = Vertex(static_cast<Mesh::size_type>(init12[v.idx()]));
  for(Vertex v : p.m2.vertices()) map21[v] = Vertex(static_cast<Mesh::size_type>(init21[v.idx()]));
  struct Counting_visitor : smc::Default_refinement_visitor
  {
    int steps = 0, trws = 0;
    bool trws_iteration(int, std::size_t, double, double) { ++trws; return true; }
    bool step(const smc::Refinement_step&) { ++steps; return true; }
  } visitor;
  const smc::Coupled_refinement_result r = smc::refine_coupled_maps(
      p.m1, p.m2, map12, map21, params::number_of_eigenpairs(30, params::number_of_candidates(10)).visitor(std::ref(visitor)));
  BOOST_TEST(visitor.steps == static_cast<int>(r.steps.size()));
  BOOST_TEST(visitor.trws > visitor.steps);
  BOOST_TEST(r.preprocessing_seconds > 0);
  smc::Vertex_index_map_vector out12(num_vertices(p.m1));
  for(Vertex v : p.m1.vertices()) out12[v.idx()] = map12[v].idx();
  smc::Map_evaluator<> on2(p.m2);
  const auto all = all_vertices(out12.size());
  BOOST_TEST(on2.geodesic_errors(out12, all, p.gt_12).mean < on2.geodesic_errors(init12, all, p.gt_12).mean);
  // A visitor that stops at once: one solve, the input maps are kept if not more consistent.
  struct Stop : smc::Default_refinement_visitor
  {
    bool step(const smc::Refinement_step&) { return false; }
  };
  smc::Vertex_index_map_vector a = init12, b = init21;
  const Shape s1(p.m1, params::number_of_eigenpairs(30)), s2(p.m2, params::number_of_eigenpairs(30));
  const auto stopped = smc::refine_coupled_maps(s1, s2, a, b, params::visitor(Stop()));
  BOOST_TEST(stopped.steps.size() == 1u);
  BOOST_TEST((stopped.termination == smc::Refinement_termination::visitor_stop));
}

BOOST_AUTO_TEST_CASE(shape_takes_the_leading_eigenpairs_of_a_precomputed_spectrum)
{
  // A shape given a spectrum of more eigenpairs (as the automatic initialisation computes) uses
  // its leading ones: the same spectrum and, up to the eigensolver's tolerance, the same
  // descriptor stack as a shape that solves for its own.
  const Mesh& m = fixture().pair.m1;
  const Shape& own = fixture().s1;
  const smc::Laplace_beltrami_spectrum large(m, params::number_of_eigenpairs(80));
  const Shape shared(m, params::precomputed_spectrum(std::cref(large), shape_parameters()));
  BOOST_TEST(shared.spectrum().number_of_eigenpairs() == 40);
  BOOST_TEST((shared.spectrum().eigenvalues() - large.eigenvalues().head(40)).norm() == 0);
  BOOST_TEST((shared.spectrum().eigenvalues() - own.spectrum().eigenvalues()).cwiseAbs().maxCoeff() <
             1e-9 * own.spectrum().eigenvalues()[39]);
  const double stack_difference = (shared.descriptors() - own.descriptors()).cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("largest descriptor difference " << stack_difference);
  BOOST_TEST(stack_difference < 1e-4);
  BOOST_TEST(shared.preprocessing_times().spectrum < own.preprocessing_times().spectrum);

  // A spectrum that does not fit is refused with the reason.
  const smc::Laplace_beltrami_spectrum few(m, params::number_of_eigenpairs(30));
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] {
                        Shape s(m, params::precomputed_spectrum(std::cref(few), shape_parameters()));
                      }),
                      "30 eigenpairs, fewer than the 40 needed"));
  const smc::Laplace_beltrami_spectrum of_other(fixture().pair.m2, params::number_of_eigenpairs(40));
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] {
                        Shape s(m, params::precomputed_spectrum(std::cref(of_other), shape_parameters()));
                      }),
                      "precomputed_spectrum"));
  // Same connectivity, other geometry: the vertex areas tell.
  const Mesh bigger = transformed(m, [](const Point& p) { return Point(1.5 * p.x(), p.y(), p.z()); });
  const smc::Laplace_beltrami_spectrum of_bigger(bigger, params::number_of_eigenpairs(40));
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] {
                        Shape s(m, params::precomputed_spectrum(std::cref(of_bigger), shape_parameters()));
                      }),
                      "not a spectrum of this mesh"));
  const smc::Laplace_beltrami_spectrum plain(m,
                                             params::number_of_eigenpairs(40, params::use_intrinsic_delaunay(false)));
  BOOST_TEST(contains(error_of<smc::Invalid_parameter_error>([&] {
                        Shape s(m, params::precomputed_spectrum(std::cref(plain), shape_parameters()));
                      }),
                      "intrinsic Delaunay"));
}

BOOST_AUTO_TEST_CASE(bad_input_is_named)
{
  const Fixture& f = fixture();
  smc::Vertex_index_map_vector m12 = f.pair.gt_12, m21 = f.pair.gt_21;
  smc::Vertex_index_map_vector short12(m12.begin(), m12.end() - 1);
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, f.s2, short12, m21), smc::Invalid_map_error);
  smc::Vertex_index_map_vector bad21 = m21;
  bad21[7] = num_vertices(f.pair.m1) + 3;
  try
  {
    smc::refine_coupled_maps(f.s1, f.s2, m12, bad21);
    BOOST_ERROR("no exception for an out-of-range map entry");
  }
  catch(const smc::Invalid_map_error& e)
  {
    BOOST_TEST(std::string(e.what()).find("map 2->1: entry 7") != std::string::npos);
  }
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, f.s2, m12, m21, params::number_of_candidates(0)),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, f.s2, m12, m21, params::ring_schedule(std::vector<int>())),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, f.s2, m12, m21, params::unary_weight(-1.0)),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, f.s2, m12, m21, params::consistency_weight(-0.5)),
                    smc::Invalid_parameter_error);
  // Meshes: two components, and a descriptor mismatch between shapes prepared differently.
  Mesh two = icosphere(2);
  const Mesh other = transformed(icosphere(2), [](const Point& p) { return p + Vector(4, 0, 0); });
  CGAL::copy_face_graph(other, two);
  try
  {
    const Shape s(two);
    BOOST_ERROR("no exception for a mesh with two components");
  }
  catch(const smc::Invalid_mesh_error& e)
  {
    BOOST_TEST(std::string(e.what()).find("2 connected components") != std::string::npos);
  }
  const Shape no_hks(f.pair.m2, params::number_of_eigenpairs(40, params::hks_weight(0.0)));
  BOOST_CHECK_THROW(smc::refine_coupled_maps(f.s1, no_hks, m12, m21), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_SUITE_END()
