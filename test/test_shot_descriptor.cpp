// SPDX-License-Identifier: GPL-3.0-or-later
// SHOT descriptors: invariances, analytic cases (plane, sphere), robustness on tiny supports and
// boundaries, distinctiveness under a near-isometric bend, mesh types, concurrency, bad input.

#include <CGAL/Surface_mesh_correspondence/shot.h>

#include "test_meshes.h"

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using namespace smc_test;

namespace {

constexpr int kSize = smc::shot_descriptor_size;

/// Height field z = f(x, y) over a 40 x 40 grid of the unit square, without symmetries.
Mesh bumpy_grid(int cells = 40)
{
  return transformed(grid(cells, cells), [](const Point& p) {
    const double x = p.x(), y = p.y();
    return Point(x, y, 0.08 * std::sin(5 * x + 1) * std::cos(3 * y + 0.3) + 0.05 * x * x * y +
                           0.03 * std::sin(7 * y));
  });
}

/// A unit sphere with radial bumps, without symmetries.
Mesh bumpy_sphere(int levels = 3)
{
  return transformed(icosphere(levels), [](const Point& p) {
    const double s = 1 + 0.12 * std::sin(3 * p.x() + 1) * std::cos(2 * p.y()) + 0.06 * p.z() * p.x() +
                     0.04 * std::sin(4 * p.z()) + 0.05 * std::sin(2.3 * p.y() + 0.4 * p.x());
    return Point(s * p.x(), s * p.y(), s * p.z());
  });
}

/// Rotation about a generic axis, then translation.
Point rigid(const Point& p)
{
  Eigen::Vector3d axis(0.3, -0.7, 0.5);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.234, axis.normalized()).toRotationMatrix();
  const Eigen::Vector3d q = r * Eigen::Vector3d(p.x(), p.y(), p.z()) + Eigen::Vector3d(3.5, -120, 0.25);
  return Point(q.x(), q.y(), q.z());
}

bool all_finite_unit(const Eigen::MatrixXd& d)
{
  if(!d.allFinite()) return false;
  for(Eigen::Index i = 0; i < d.rows(); ++i)
    if(std::abs(d.row(i).norm() - 1) > 1e-12) return false;
  return true;
}

/// Indices of the vertices of a grid(nx, ny) at least `margin` cells away from its border.
std::vector<int> interior_grid_vertices(int nx, int ny, int margin)
{
  std::vector<int> out;
  for(int j = margin; j <= ny - margin; ++j)
    for(int i = margin; i <= nx - margin; ++i) out.push_back(j * (nx + 1) + i);
  return out;
}

template <typename F>
std::string error_message(F&& f)
{
  try
  {
    f();
  }
  catch(const smc::Error& e)
  {
    return e.what();
  }
  return "no exception";
}


/// Sum of the descriptor over all sectors, per cosine bin.
std::vector<double> cosine_marginal(const Eigen::RowVectorXd& d)
{
  std::vector<double> m(smc::internal::shot_cosine_bins, 0.0);
  for(int s = 0; s < smc::internal::shot_number_of_sectors; ++s)
    for(int c = 0; c < smc::internal::shot_cosine_bins; ++c)
      m[c] += d[s * smc::internal::shot_cosine_bins + c];
  return m;
}

/// Readable property maps backed by vectors indexed by the Surface_mesh vertex index.
struct Position_map
{
  typedef Vertex key_type;
  typedef Point value_type;
  typedef const Point& reference;
  typedef boost::readable_property_map_tag category;
  const std::vector<Point>* p;
  friend const Point& get(const Position_map& m, Vertex v) { return (*m.p)[static_cast<std::size_t>(v)]; }
};

struct Index_map
{
  typedef Vertex key_type;
  typedef std::size_t value_type;
  typedef std::size_t reference;
  typedef boost::readable_property_map_tag category;
  const std::vector<std::size_t>* p;
  friend std::size_t get(const Index_map& m, Vertex v) { return (*m.p)[static_cast<std::size_t>(v)]; }
};

} // namespace

BOOST_AUTO_TEST_SUITE(shot)

BOOST_AUTO_TEST_CASE(size_norm_and_finiteness)
{
  const Mesh s = bumpy_sphere();
  const Eigen::MatrixXd d = smc::compute_shot_descriptors(s);
  BOOST_TEST(d.rows() == static_cast<Eigen::Index>(num_vertices(s)));
  BOOST_TEST(d.cols() == 352);
  BOOST_TEST(all_finite_unit(d));
  BOOST_TEST(d.minCoeff() >= 0.0);
  // A generic vertex fills many bins (interpolation spreads every point over 16 of them).
  BOOST_TEST((d.row(0).array() > 0).count() > 30);
}

BOOST_AUTO_TEST_CASE(rigid_motion_invariance)
{
  for(const Mesh& m : {bumpy_grid(), bumpy_sphere()})
  {
    const Mesh moved = transformed(m, rigid);
    const Eigen::MatrixXd a = smc::compute_shot_descriptors(m);
    const Eigen::MatrixXd b = smc::compute_shot_descriptors(moved);
    const double difference = (a - b).cwiseAbs().maxCoeff();
    BOOST_TEST_MESSAGE("SHOT rigid motion: max |difference| = " << difference);
    BOOST_TEST(difference < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(uniform_scaling_invariance)
{
  const Mesh m = bumpy_sphere();
  const Mesh big = transformed(m, [](const Point& p) { return Point(37 * p.x(), 37 * p.y(), 37 * p.z()); });
  const Eigen::MatrixXd a = smc::compute_shot_descriptors(m, params::shot_radius(0.08));
  const Eigen::MatrixXd b = smc::compute_shot_descriptors(big, params::shot_radius(0.08));
  const double difference = (a - b).cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("SHOT scaling: max |difference| = " << difference);
  BOOST_TEST(difference < 1e-9);
  // The radius matters: another radius gives other descriptors.
  const Eigen::MatrixXd c = smc::compute_shot_descriptors(m, params::shot_radius(0.12));
  BOOST_TEST((a - c).cwiseAbs().maxCoeff() > 0.05);
}

BOOST_AUTO_TEST_CASE(plane_puts_all_mass_in_the_last_cosine_bin)
{
  const int cells = 30;
  const double radius = 0.12;  // R = 0.12 (unit square)
  const Mesh flat = grid(cells, cells);
  const Eigen::MatrixXd d = smc::compute_shot_descriptors(flat, params::shot_radius(radius));
  BOOST_TEST(all_finite_unit(d));
  const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(flat);
  const int bins = smc::internal::shot_cosine_bins;
  const std::vector<int> inner = interior_grid_vertices(cells, cells, 5);
  double worst_other_bins = 0, worst_hemisphere_gap = 0, worst_shell_ratio_error = 0;
  for(int v : inner)
  {
    // All normals equal the frame's z axis: cosine 1, the last bin of every sector.
    double other_bins = 0, lower = 0, upper = 0, inner_shell = 0, outer_shell = 0;
    for(int b = 0; b < kSize; ++b)
    {
      const int sector = b / bins;
      if(b % bins != bins - 1) other_bins += d(v, b);
      ((sector / 8) % 2 == 0 ? lower : upper) += d(v, b);
      (sector / 16 == 0 ? inner_shell : outer_shell) += d(v, b);
    }
    worst_other_bins = std::max(worst_other_bins, other_bins);
    // Every point lies on the equator of the support: half of its weight in each hemisphere.
    worst_hemisphere_gap = std::max(worst_hemisphere_gap, std::abs(lower - upper));
    // Radial interpolation from brute-force distances: weight 1 in the inner shell up to R/4,
    // 0 from 3R/4 on, linear in between.
    double expected_inner = 0, expected_outer = 0;
    for(int w = 0; w < im.number_of_vertices(); ++w)
    {
      const double dist = (im.point(w) - im.point(v)).norm();
      if(w == v || dist >= radius) continue;
      const double t = std::min(1.0, std::max(0.0, (dist - radius / 4) / (radius / 2)));
      expected_inner += 1 - t;
      expected_outer += t;
    }
    worst_shell_ratio_error = std::max(worst_shell_ratio_error,
                                       std::abs(inner_shell / outer_shell - expected_inner / expected_outer));
  }
  BOOST_TEST(worst_other_bins == 0.0);
  BOOST_TEST(worst_hemisphere_gap < 1e-12);
  BOOST_TEST(worst_shell_ratio_error < 1e-9);
  // Reversed orientation: no support point decides the side of z (all lie in the tangent plane),
  // so z follows the (reversed) vertex normal and the cosines are 1 again.
  Mesh flipped = flat;
  CGAL::Polygon_mesh_processing::reverse_face_orientations(flipped);
  const Eigen::MatrixXd f = smc::compute_shot_descriptors(flipped, params::shot_radius(radius));
  double flipped_off_bins = 0;
  for(int v : inner)
    for(int b = 0; b < kSize; ++b)
      if(b % bins != bins - 1) flipped_off_bins = std::max(flipped_off_bins, f(v, b));
  BOOST_TEST(flipped_off_bins == 0.0);
  // A tilted plane: the same up to rounding.
  const Mesh tilted = transformed(flat, rigid);
  const Eigen::MatrixXd t = smc::compute_shot_descriptors(tilted, params::shot_radius(radius));
  double off_bins = 0;
  for(int v : inner)
    for(int b = 0; b < kSize; ++b)
      if(b % bins != bins - 1) off_bins = std::max(off_bins, t(v, b));
  BOOST_TEST(off_bins < 1e-9);
}

BOOST_AUTO_TEST_CASE(sphere_cosine_distribution_follows_the_geometry)
{
  // Unit sphere, outward normals. A cap is convex: the majority of the support lies below the
  // tangent plane, so z points inwards, z = -p, and a neighbour at chord distance d has
  // cos(theta) = n_i . z = -p_i . p = -(1 - d^2 / 2).
  const Mesh s = icosphere(4);
  const double relative = 0.3;
  const double radius = relative * std::sqrt(4 * pi);  // R = 1.06: cosines in [-1, -0.43]
  const Eigen::MatrixXd d = smc::compute_shot_descriptors(s, params::shot_radius(relative));
  const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(s);
  const int bins = smc::internal::shot_cosine_bins;
  double worst = 0, positive_mass = 0;
  for(int v = 0; v < im.number_of_vertices(); v += 97)
  {
    std::vector<double> expected(bins, 0.0);
    for(int w = 0; w < im.number_of_vertices(); ++w)
    {
      const double dist = (im.point(w) - im.point(v)).norm();
      if(w == v || dist >= radius) continue;
      const double cosine = -(1 - dist * dist / 2);
      const double u = (cosine + 1) * bins / 2.0 - 0.5;
      const int b0 = static_cast<int>(std::floor(u));
      if(b0 < 0) expected[0] += 1;
      else if(b0 >= bins - 1) expected[bins - 1] += 1;
      else
      {
        expected[b0] += 1 - (u - b0);
        expected[b0 + 1] += u - b0;
      }
    }
    std::vector<double> got = cosine_marginal(d.row(v));
    const double se = std::accumulate(expected.begin(), expected.end(), 0.0);
    const double sg = std::accumulate(got.begin(), got.end(), 0.0);
    double l1 = 0;
    for(int c = 0; c < bins; ++c) l1 += std::abs(expected[c] / se - got[c] / sg);
    worst = std::max(worst, l1);
    // Nothing with a positive cosine.
    for(int c = bins / 2 + 1; c < bins; ++c) positive_mass += got[c];
  }
  BOOST_TEST(positive_mass == 0.0);
  BOOST_TEST_MESSAGE("SHOT sphere: worst L1 distance of the cosine marginals = " << worst);
  // Vertex normals and the frame are approximations on the polyhedron: a loose bound.
  BOOST_TEST(worst < 0.05);
}

BOOST_AUTO_TEST_CASE(tiny_supports_boundaries_and_coarse_meshes)
{
  // Boundary vertices of a grid, and a radius so small that no vertex has a neighbour within it.
  for(double r : {1e-6, 0.01, 0.06, 0.5, 5.0})
  {
    const Eigen::MatrixXd d = smc::compute_shot_descriptors(bumpy_grid(12), params::shot_radius(r));
    BOOST_TEST(all_finite_unit(d));
  }
  // Coarse closed meshes: the icosahedron and a capsule.
  BOOST_TEST(all_finite_unit(smc::compute_shot_descriptors(icosphere(0))));
  BOOST_TEST(all_finite_unit(smc::compute_shot_descriptors(capsule(6, 2, 3), params::shot_radius(0.02))));
  // A single triangle and a square made of two (fewer vertices than the minimum support).
  const Mesh triangle = mesh_from_soup({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}, {{0, 1, 2}});
  BOOST_TEST(all_finite_unit(smc::compute_shot_descriptors(triangle)));
  BOOST_TEST(all_finite_unit(smc::compute_shot_descriptors(grid(1, 1))));

  // The enlarged support has at least 10 vertices: on the 12-vertex icosahedron with a tiny
  // radius, a vertex sees its 5 ring neighbours and beyond; the statistics say so.
  smc::internal::Shot_options options;
  options.relative_radius = 1e-3;
  smc::internal::Shot_statistics stats;
  const smc::internal::Indexed_mesh ico = smc::internal::make_indexed_mesh(icosphere(0));
  smc::internal::shot_descriptors<CGAL::Sequential_tag>(ico, options, &stats);
  BOOST_TEST(stats.enlarged_supports == 12u);
  BOOST_TEST(stats.average_neighbors >= 10.0);
  // With the default radius on a fine mesh no support is enlarged.
  const smc::internal::Indexed_mesh fine = smc::internal::make_indexed_mesh(icosphere(4));
  smc::internal::shot_descriptors<CGAL::Sequential_tag>(fine, smc::internal::Shot_options(), &stats);
  BOOST_TEST(stats.enlarged_supports == 0u);
  BOOST_TEST(stats.average_neighbors > 20.0);
}

BOOST_AUTO_TEST_CASE(uniform_grid_matches_brute_force)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  smc::internal::Indexed_mesh::Points points(500, 3);
  for(Eigen::Index i = 0; i < points.rows(); ++i)
    points.row(i) = Eigen::RowVector3d(uniform(rng), 0.3 * uniform(rng), 2 * uniform(rng));
  for(double cell : {1e-9, 0.05, 0.3, 10.0})
  {
    const smc::internal::Uniform_point_grid g(points, cell);
    for(double r : {0.01, 0.2, 0.7, 5.0})
      for(int q = 0; q < 500; q += 37)
      {
        std::vector<int> found, expected;
        const Eigen::Vector3d centre = points.row(q).transpose();
        g.for_each_in_ball(centre.data(), r, [&](int j, double, std::size_t) { found.push_back(j); });
        for(int j = 0; j < 500; ++j)
          if((points.row(j) - points.row(q)).squaredNorm() < r * r) expected.push_back(j);
        std::sort(found.begin(), found.end());
        BOOST_TEST(found == expected);
      }
  }
}

BOOST_AUTO_TEST_CASE(fast_atan2_matches_std)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  double worst = 0;
  for(int k = 0; k < 200000; ++k)
  {
    double y = uniform(rng), x = uniform(rng);
    if(k % 5 == 0) x *= 1e-9;
    if(k % 7 == 0) y = std::abs(y) * 1e-12;
    worst = std::max(worst, std::abs(smc::internal::shot_atan2(y, x) - std::atan2(y, x)));
  }
  BOOST_TEST(worst < 1e-14);
  BOOST_TEST(smc::internal::shot_atan2(0.0, -1.0) == pi);
  BOOST_TEST(smc::internal::shot_atan2(0.0, 0.0) == 0.0);
  BOOST_TEST(std::abs(smc::internal::shot_atan2(1.0, 1.0) - pi / 4) < 1e-16);
}

BOOST_AUTO_TEST_CASE(poisson_disk_support_sample)
{
  const Mesh s = bumpy_sphere(4);  // 2562 vertices
  const smc::internal::Indexed_mesh m = smc::internal::make_indexed_mesh(s);
  const double spacing = 0.1;
  const std::vector<int> sample = smc::internal::poisson_disk_subsample(m.points, spacing);
  BOOST_TEST(sample.size() > 100u);
  BOOST_TEST(sample.size() < 2562u);
  std::vector<char> kept(m.number_of_vertices(), 0);
  for(int v : sample) kept[v] = 1;
  double closest_pair = 1e30, farthest_vertex = 0;
  for(int v = 0; v < m.number_of_vertices(); ++v)
  {
    double nearest_kept = 1e30;
    for(int w : sample)
    {
      const double d = (m.point(v) - m.point(w)).norm();
      if(kept[v] && w != v) closest_pair = std::min(closest_pair, d);
      nearest_kept = std::min(nearest_kept, d);
    }
    farthest_vertex = std::max(farthest_vertex, nearest_kept);
  }
  BOOST_TEST(closest_pair >= spacing);    // a packing ...
  BOOST_TEST(farthest_vertex < spacing);  // ... and a covering
  // The same sample after a rigid motion.
  const smc::internal::Indexed_mesh moved = smc::internal::make_indexed_mesh(transformed(s, rigid));
  BOOST_TEST(smc::internal::poisson_disk_subsample(moved.points, spacing) == sample);

  // SHOT with support points subsampled (as on meshes larger than maximum_support_points):
  // rigid-motion invariant, finite, unit norm.
  smc::internal::Shot_options options;
  options.maximum_support_points = 1000;
  smc::internal::Shot_statistics stats;
  const Eigen::MatrixXd a = smc::internal::shot_descriptors<CGAL::Sequential_tag>(m, options, &stats);
  const Eigen::MatrixXd b = smc::internal::shot_descriptors<CGAL::Sequential_tag>(moved, options);
  BOOST_TEST(stats.support_points > 700u);
  BOOST_TEST(stats.support_points < 1400u);
  BOOST_TEST(all_finite_unit(a));
  BOOST_TEST((a - b).cwiseAbs().maxCoeff() < 1e-9);
}

BOOST_AUTO_TEST_CASE(subsampled_support_on_a_finer_mesh)
{
  // The level-5 sphere holds the level-4 vertices first (same positions), then the midpoints.
  // With a bound of 2562 support points, the Poisson-disk sample of the level-5 mesh is exactly
  // the level-4 vertex set, so its descriptors are those of the level-4 mesh up to the vertex
  // normals (computed on the finer mesh). Without the bound they differ more (resolution change).
  const smc::internal::Indexed_mesh coarse = smc::internal::make_indexed_mesh(bumpy_sphere(4));
  const smc::internal::Indexed_mesh fine = smc::internal::make_indexed_mesh(bumpy_sphere(5));
  const int n = coarse.number_of_vertices();
  BOOST_REQUIRE((coarse.points - fine.points.topRows(n)).cwiseAbs().maxCoeff() == 0.0);
  smc::internal::Shot_options bounded;
  bounded.maximum_support_points = static_cast<std::size_t>(n);
  smc::internal::Shot_statistics stats;
  const Eigen::MatrixXd sub = smc::internal::shot_descriptors<CGAL::Sequential_tag>(fine, bounded, &stats);
  BOOST_TEST(stats.support_points == static_cast<std::size_t>(n));
  const Eigen::MatrixXd reference = smc::internal::shot_descriptors<CGAL::Sequential_tag>(coarse);
  const Eigen::MatrixXd full = smc::internal::shot_descriptors<CGAL::Sequential_tag>(fine);
  const double sub_to_coarse = (sub.topRows(n) - reference).rowwise().norm().mean();
  const double full_to_coarse = (full.topRows(n) - reference).rowwise().norm().mean();
  BOOST_TEST_MESSAGE("SHOT fine sphere: mean distance to the coarse descriptors, subsampled support "
                     << sub_to_coarse << ", every vertex " << full_to_coarse);
  BOOST_TEST(sub_to_coarse < 0.02);
  BOOST_TEST(sub_to_coarse < 0.5 * full_to_coarse);
  // The default bound (20000) leaves this 10242-vertex mesh alone.
  smc::internal::shot_descriptors<CGAL::Sequential_tag>(fine, smc::internal::Shot_options(), &stats);
  BOOST_TEST(stats.support_points == static_cast<std::size_t>(fine.number_of_vertices()));
}

BOOST_AUTO_TEST_CASE(distinctive_under_a_near_isometric_bend)
{
  // A bumpy tube (no symmetry) of length 8 and radius 0.5, bent by 90 degrees: the descriptor of
  // a vertex on the bent tube is closer to its own descriptor on the straight tube than to those
  // of other vertices.
  const double length = 8;
  auto bumps = [](const Point& p) {
    const double a = std::atan2(p.y(), p.x());
    const double s = 1 + 0.15 * std::sin(3 * a + 0.7 * p.z()) * std::cos(1.3 * p.z()) +
                     0.08 * std::sin(2.1 * p.z() + a);
    return Point(s * p.x(), s * p.y(), p.z());
  };
  const Mesh straight = transformed(tube(48, 96, 0.5, length), bumps);
  const Mesh bent = transformed(straight, [&](const Point& p) { return bend_point(p, length, pi / 2); });
  const Eigen::MatrixXd a = smc::compute_shot_descriptors(straight);
  const Eigen::MatrixXd b = smc::compute_shot_descriptors(bent);
  const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(straight);
  const double radius = smc::Matching_settings().shot_radius * std::sqrt(im.total_area);

  // For tested vertices v (away from the open ends): rank of |a_v - b_v| among |a_v - b_w| for
  // the vertices w farther than 2R from v, and the nearest descriptor on the bent tube.
  int tested = 0, hits = 0, below_median = 0;
  double percentile_total = 0, same_total = 0, median_total = 0, chance = 0;
  std::vector<double> others;
  for(int v = 0; v < im.number_of_vertices(); v += 7)
  {
    const double z = im.points(v, 2);
    if(z < 1.5 || z > length - 1.5) continue;
    ++tested;
    const Eigen::VectorXd distance = (b.rowwise() - a.row(v)).rowwise().norm();
    Eigen::Index best = 0;
    distance.minCoeff(&best);
    int near = 0;
    others.clear();
    for(int w = 0; w < im.number_of_vertices(); ++w)
    {
      const double d = (im.point(w) - im.point(v)).norm();
      if(d < radius) ++near;
      if(d > 2 * radius) others.push_back(distance[w]);
    }
    if((im.point(static_cast<int>(best)) - im.point(v)).norm() < radius) ++hits;
    chance += static_cast<double>(near) / im.number_of_vertices();
    const double same = distance[v];
    percentile_total += static_cast<double>(std::count_if(others.begin(), others.end(),
                                                          [&](double d) { return d < same; })) /
                        others.size();
    std::nth_element(others.begin(), others.begin() + others.size() / 2, others.end());
    const double median = others[others.size() / 2];
    below_median += same < median ? 1 : 0;
    same_total += same;
    median_total += median;
  }
  const double hit_rate = static_cast<double>(hits) / tested;
  const double mean_percentile = percentile_total / tested;
  const double below_median_rate = static_cast<double>(below_median) / tested;
  const double ratio = same_total / median_total;
  BOOST_TEST_MESSAGE("SHOT bend: " << tested << " vertices; same-vertex distance below the median "
                     "distance to far vertices for " << below_median_rate << ", mean percentile "
                     << mean_percentile << ", mean same / mean median " << ratio
                     << ", nearest descriptor within R for " << hit_rate << " (chance "
                     << chance / tested << ")");
  BOOST_TEST(below_median_rate > 0.85);
  BOOST_TEST(mean_percentile < 0.15);
  BOOST_TEST(ratio < 0.5);
  BOOST_TEST(hit_rate > 5 * chance / tested);
}

BOOST_AUTO_TEST_CASE(surface_mesh_and_polyhedron_agree)
{
  const Mesh s = bumpy_sphere(2);
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(s, p);
  const Eigen::MatrixXd a = smc::compute_shot_descriptors(s);
  const Eigen::MatrixXd b = smc::compute_shot_descriptors(p);
  BOOST_TEST(a.rows() == b.rows());
  // Rows follow each mesh's vertex index map: pair them through the positions.
  const smc::internal::Indexed_mesh ms = smc::internal::make_indexed_mesh(s);
  const smc::internal::Indexed_mesh mp = smc::internal::make_indexed_mesh(p);
  std::map<std::array<double, 3>, int> row_of;
  for(int i = 0; i < mp.number_of_vertices(); ++i)
    row_of[{mp.points(i, 0), mp.points(i, 1), mp.points(i, 2)}] = i;
  BOOST_TEST(row_of.size() == static_cast<std::size_t>(ms.number_of_vertices()));
  double difference = 0;
  for(int i = 0; i < ms.number_of_vertices(); ++i)
  {
    const auto it = row_of.find({ms.points(i, 0), ms.points(i, 1), ms.points(i, 2)});
    BOOST_REQUIRE(it != row_of.end());
    difference = std::max(difference, (a.row(i) - b.row(it->second)).cwiseAbs().maxCoeff());
  }
  BOOST_TEST(difference < 1e-12);
  // The subset version with Polyhedron vertex handles.
  std::vector<CGAL::Polyhedron_3<Kernel>::Vertex_handle> some;
  for(auto v = p.vertices_begin(); v != p.vertices_end(); ++v) some.push_back(v);
  std::reverse(some.begin(), some.end());
  some.resize(20);
  const Eigen::MatrixXd c = smc::compute_shot_descriptors(p, some);
  BOOST_TEST((c.row(0) - b.row(b.rows() - 1)).cwiseAbs().maxCoeff() == 0.0);
  BOOST_TEST((c.row(19) - b.row(b.rows() - 20)).cwiseAbs().maxCoeff() == 0.0);
}

BOOST_AUTO_TEST_CASE(subset_matches_all_vertices)
{
  const Mesh s = bumpy_sphere(2);
  const Eigen::MatrixXd all = smc::compute_shot_descriptors(s, params::shot_radius(0.1));
  std::vector<Vertex> some = {Vertex(5), Vertex(0), Vertex(161), Vertex(5)};
  const Eigen::MatrixXd d = smc::compute_shot_descriptors(s, some, params::shot_radius(0.1));
  BOOST_TEST(d.rows() == 4);
  for(int k = 0; k < 4; ++k)
    BOOST_TEST((d.row(k) - all.row(static_cast<int>(some[k]))).cwiseAbs().maxCoeff() == 0.0);
}

BOOST_AUTO_TEST_CASE(sequential_equals_parallel)
{
#ifdef CGAL_LINKED_WITH_TBB
  const Mesh s = bumpy_sphere(4);
  const Eigen::MatrixXd a = smc::compute_shot_descriptors<CGAL::Sequential_tag>(s);
  const Eigen::MatrixXd b = smc::compute_shot_descriptors<CGAL::Parallel_tag>(s);
  BOOST_TEST((a.array() == b.array()).all());
#else
  BOOST_TEST_MESSAGE("TBB not available: parallel SHOT not tested");
#endif
}

BOOST_AUTO_TEST_CASE(named_parameters)
{
  const Mesh s = bumpy_sphere(2);
  // vertex_point_map: positions read from a map (here, moved rigidly) instead of the mesh.
  const Mesh moved = transformed(s, rigid);
  std::vector<Point> positions(num_vertices(s));
  for(Vertex v : s.vertices()) positions[static_cast<std::size_t>(v)] = moved.point(v);
  const Eigen::MatrixXd a = smc::compute_shot_descriptors(moved);
  const Eigen::MatrixXd b = smc::compute_shot_descriptors(s, params::vertex_point_map(Position_map{&positions}));
  BOOST_TEST((a - b).cwiseAbs().maxCoeff() == 0.0);
  // vertex_index_map: a permutation permutes the rows (up to rounding: the summation order
  // follows the indices); in both orders of the parameters.
  const std::size_t n = num_vertices(s);
  std::vector<std::size_t> permutation(n);
  for(std::size_t i = 0; i < n; ++i) permutation[i] = (i * 37 + 11) % n;  // n = 162, gcd(37, 162) = 1
  const Eigen::MatrixXd base = smc::compute_shot_descriptors(s, params::shot_radius(0.07));
  const Eigen::MatrixXd c = smc::compute_shot_descriptors(
      s, params::shot_radius(0.07).vertex_index_map(Index_map{&permutation}));
  const Eigen::MatrixXd e = smc::compute_shot_descriptors(
      s, params::shot_radius(0.07, params::vertex_index_map(Index_map{&permutation})));
  for(std::size_t i = 0; i < n; ++i)
  {
    BOOST_TEST((c.row(static_cast<Eigen::Index>(permutation[i])) - base.row(static_cast<Eigen::Index>(i)))
                   .cwiseAbs().maxCoeff() < 1e-12);
    BOOST_TEST((e.row(static_cast<Eigen::Index>(permutation[i])) - base.row(static_cast<Eigen::Index>(i)))
                   .cwiseAbs().maxCoeff() < 1e-12);
  }
  // The subset version with a custom index map: rows follow the requested vertices.
  const std::vector<Vertex> some = {Vertex(3), Vertex(100)};
  const Eigen::MatrixXd f = smc::compute_shot_descriptors(
      s, some, params::shot_radius(0.07).vertex_index_map(Index_map{&permutation}));
  BOOST_TEST((f.row(0) - base.row(3)).cwiseAbs().maxCoeff() < 1e-12);
  BOOST_TEST((f.row(1) - base.row(100)).cwiseAbs().maxCoeff() < 1e-12);
}

BOOST_AUTO_TEST_CASE(bad_input_throws)
{
  // Non-triangle face.
  Mesh quad;
  {
    const Vertex a = quad.add_vertex(Point(0, 0, 0)), b = quad.add_vertex(Point(1, 0, 0)),
                 c = quad.add_vertex(Point(1, 1, 0)), d = quad.add_vertex(Point(0, 1, 0));
    quad.add_face(a, b, c, d);
  }
  std::string message = error_message([&] { smc::compute_shot_descriptors(quad); });
  BOOST_TEST(contains(message, "triangle"), message);
  BOOST_CHECK_THROW(smc::compute_shot_descriptors(quad), smc::Invalid_mesh_error);
  // NaN coordinate.
  Mesh nan_mesh = icosphere(1);
  nan_mesh.point(Vertex(3)) = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  message = error_message([&] { smc::compute_shot_descriptors(nan_mesh); });
  BOOST_TEST(contains(message, "non-finite"), message);
  BOOST_CHECK_THROW(smc::compute_shot_descriptors(nan_mesh), smc::Invalid_mesh_error);
  // Empty mesh.
  message = error_message([&] { smc::compute_shot_descriptors(Mesh()); });
  BOOST_TEST(contains(message, "empty"), message);
  BOOST_CHECK_THROW(smc::compute_shot_descriptors(Mesh()), smc::Invalid_mesh_error);
  // Radius <= 0, NaN, infinite.
  const Mesh s = icosphere(1);
  for(double r : {0.0, -0.05, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
  {
    message = error_message([&] { smc::compute_shot_descriptors(s, params::shot_radius(r)); });
    BOOST_TEST(contains(message, "shot_radius"), message);
    BOOST_CHECK_THROW(smc::compute_shot_descriptors(s, params::shot_radius(r)), smc::Invalid_parameter_error);
  }
  // Internal entry: vertex index out of range.
  const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(s);
  const int bad = 1000;
  BOOST_CHECK_THROW(smc::internal::shot_descriptors<CGAL::Sequential_tag>(im, &bad, 1, smc::internal::Shot_options()),
                    smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_SUITE_END()
