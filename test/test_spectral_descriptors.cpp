// SPDX-License-Identifier: GPL-3.0-or-later
// HKS and WKS: brute-force references, isometry and scale invariance, normalisations,
// components, parallel evaluation, parameters.

#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>

#include "test_meshes.h"

#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/copy_face_graph.h>

#include <unsupported/Eigen/MatrixFunctions>

#include <boost/test/unit_test.hpp>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using namespace smc_test;

namespace {

// A flat strip of length 4.3 and width 1 in the y-z plane (x = 0), along z.
Mesh strip()
{
  return transformed(grid(43, 10, 4.3, 1.0), [](const Point& p) { return Point(0, p.y(), p.x()); });
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
  return (a - b).norm() / b.norm();
}

// Mean over vertices of |row_i(a) - row_i(b)|, and mean over all pairs i != j of
// |row_i(a) - row_j(a)|.
std::pair<double, double> same_and_different(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
  double same = 0, different = 0;
  const Eigen::Index n = a.rows();
  for(Eigen::Index i = 0; i < n; ++i)
  {
    same += (a.row(i) - b.row(i)).norm();
    for(Eigen::Index j = 0; j < n; ++j)
      if(j != i) different += (a.row(i) - a.row(j)).norm();
  }
  return std::make_pair(same / n, different / (n * (n - 1)));
}

// Area-weighted mean of each column (1 for the normalised descriptors).
Eigen::VectorXd column_means(const smc::Laplace_beltrami_spectrum& s, const Eigen::MatrixXd& d)
{
  return d.transpose() * s.mass() / s.total_area();
}

template <typename F>
std::string parameter_error_of(F&& f)
{
  try
  {
    f();
  }
  catch(const smc::Invalid_parameter_error& e)
  {
    return e.what();
  }
  catch(const std::exception& e)
  {
    return std::string("wrong exception: ") + e.what();
  }
  return "no exception";
}


} // namespace

BOOST_AUTO_TEST_SUITE(descriptors)

BOOST_AUTO_TEST_CASE(raw_hks_is_the_heat_kernel_diagonal)
{
  // Reference: the diagonal of exp(-t M^{-1} L) divided by M (matrix exponential, no
  // eigendecomposition), on a mesh small enough to keep all but one eigenpair.
  const Mesh m = jittered_sphere(1, 0.3);
  const smc::Laplace_beltrami_spectrum s(m, params::number_of_eigenpairs(41));
  const Eigen::MatrixXd L = Eigen::MatrixXd(s.stiffness_matrix());
  const Eigen::VectorXd& mass = s.mass();
  Eigen::VectorXd times(3);
  times << 1.0, 2.0, 4.0;  // exp(-lambda_42 t) is negligible
  const Eigen::MatrixXd hks = smc::heat_kernel_signature(s.eigenvalues(), s.eigenvectors(), times);
  BOOST_TEST(hks.rows() == 42);
  BOOST_TEST(hks.cols() == 3);
  for(int c = 0; c < 3; ++c)
  {
    const Eigen::MatrixXd heat = (-times[c] * (mass.cwiseInverse().asDiagonal() * L)).exp();
    const Eigen::VectorXd reference = heat.diagonal().cwiseQuotient(mass);
    BOOST_TEST(relative_difference(hks.col(c), reference) < 1e-6);
  }
}

BOOST_AUTO_TEST_CASE(raw_wks_matches_the_formula)
{
  const smc::Laplace_beltrami_spectrum s(jittered_sphere(2, 0.3), params::number_of_eigenpairs(30));
  Eigen::VectorXd energies(4);
  energies << 0.5, 1.5, 2.5, 3.0;
  const double sigma = 0.4;
  const Eigen::MatrixXd wks = smc::wave_kernel_signature(s.eigenvalues(), s.eigenvectors(), energies, sigma);
  double worst = 0;
  for(int i = 0; i < s.number_of_vertices(); ++i)
    for(int c = 0; c < 4; ++c)
    {
      double sum = 0;
      for(int j = 1; j < 30; ++j)  // j = 0 is the zero eigenvalue
      {
        const double phi = s.eigenvectors()(i, j), d = energies[c] - std::log(s.eigenvalues()[j]);
        sum += phi * phi * std::exp(-d * d / (2 * sigma * sigma));
      }
      worst = std::max(worst, std::abs(wks(i, c) - sum) / sum);
    }
  BOOST_TEST(worst < 1e-12);
}

BOOST_AUTO_TEST_CASE(automatic_times_energies_and_normalisations)
{
  const smc::Laplace_beltrami_spectrum s(jittered_sphere(2, 0.3), params::number_of_eigenpairs(40));
  const double A = s.total_area();
  const double l1 = s.eigenvalues()[1] * A, lmax = s.eigenvalues()[39] * A;
  // HKS times.
  const Eigen::VectorXd t = smc::heat_kernel_signature_times(s, params::number_of_hks_scales(5));
  BOOST_TEST(t.size() == 5);
  BOOST_TEST(t[0] == 4 * std::log(10.0) / lmax, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t[4] == 4 * std::log(10.0) / l1, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t[2] == std::sqrt(t[0] * t[4]), boost::test_tools::tolerance(1e-12));
  // WKS energies.
  const smc::Wave_kernel_signature_energies e =
      smc::wave_kernel_signature_energies(s, params::number_of_wks_energies(11, params::wks_variance(5.0)));
  BOOST_TEST(e.log_energies.size() == 11);
  BOOST_TEST(e.log_energies[0] == std::log(l1), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(e.log_energies[10] == std::log(lmax), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(e.sigma == 5.0 * (std::log(lmax) - std::log(l1)) / 10, boost::test_tools::tolerance(1e-12));

  // Normalised = raw on the unit-area spectrum, divided by the heat trace / C_e.
  const Eigen::VectorXd unit_values = s.eigenvalues() * A;
  const Eigen::MatrixXd unit_vectors = s.eigenvectors() * std::sqrt(A);
  const Eigen::MatrixXd hks = smc::heat_kernel_signature(s, params::number_of_hks_scales(5));
  Eigen::MatrixXd expected = smc::heat_kernel_signature(unit_values, unit_vectors, t);
  for(int c = 0; c < 5; ++c) expected.col(c) /= (-unit_values.array() * t[c]).exp().sum();
  BOOST_TEST(relative_difference(hks, expected) < 1e-12);
  const Eigen::MatrixXd wks =
      smc::wave_kernel_signature(s, params::number_of_wks_energies(11, params::wks_variance(5.0)));
  expected = smc::wave_kernel_signature(unit_values, unit_vectors, e.log_energies, e.sigma);
  for(int c = 0; c < 11; ++c)
  {
    double normaliser = 0;
    for(int j = 1; j < 40; ++j)
      normaliser += std::exp(-std::pow(e.log_energies[c] - std::log(unit_values[j]), 2) / (2 * e.sigma * e.sigma));
    expected.col(c) /= normaliser;
  }
  BOOST_TEST(relative_difference(wks, expected) < 1e-12);

  // Every column has unit area-weighted mean; defaults give 16 and 100 columns.
  const Eigen::MatrixXd hks16 = smc::heat_kernel_signature(s), wks100 = smc::wave_kernel_signature(s);
  BOOST_TEST(hks16.cols() == 16);
  BOOST_TEST(wks100.cols() == 100);
  BOOST_TEST((column_means(s, hks16).array() - 1).abs().maxCoeff() < 1e-10);
  BOOST_TEST((column_means(s, wks100).array() - 1).abs().maxCoeff() < 1e-10);
  BOOST_TEST(hks16.minCoeff() > 0);
  BOOST_TEST(wks100.minCoeff() > 0);
}

BOOST_AUTO_TEST_CASE(leading_eigenpairs_only)
{
  // number_of_eigenpairs(k): the signatures of the first k eigenpairs of a larger spectrum, by the
  // formulas written out here (times, energies and normalisers from eigenvalues 1 .. k - 1 only).
  const smc::Laplace_beltrami_spectrum s(jittered_sphere(2, 0.3), params::number_of_eigenpairs(40));
  const int k = 25;
  const double A = s.total_area();
  const Eigen::VectorXd t = smc::heat_kernel_signature_times(s, params::number_of_hks_scales(3, params::number_of_eigenpairs(k)));
  BOOST_TEST(t[0] == 4 * std::log(10.0) / (s.eigenvalues()[k - 1] * A), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t[2] == 4 * std::log(10.0) / (s.eigenvalues()[1] * A), boost::test_tools::tolerance(1e-12));
  const smc::Wave_kernel_signature_energies e = smc::wave_kernel_signature_energies(
      s, params::number_of_wks_energies(4, params::number_of_eigenpairs(k)));
  BOOST_TEST(e.log_energies[3] == std::log(s.eigenvalues()[k - 1] * A), boost::test_tools::tolerance(1e-12));
  const Eigen::MatrixXd hks = smc::heat_kernel_signature(s, params::number_of_hks_scales(3, params::number_of_eigenpairs(k)));
  const Eigen::MatrixXd wks = smc::wave_kernel_signature(s, params::number_of_wks_energies(4, params::number_of_eigenpairs(k)));
  double worst = 0;
  for(int i = 0; i < s.number_of_vertices(); ++i)
  {
    for(int c = 0; c < 3; ++c)
    {
      double sum = 0, trace = 0;
      for(int j = 0; j < k; ++j)
      {
        const double w = std::exp(-s.eigenvalues()[j] * A * t[c]), phi = s.eigenvectors()(i, j);
        sum += w * phi * phi * A;
        trace += w;
      }
      worst = std::max(worst, std::abs(hks(i, c) - sum / trace) / (sum / trace));
    }
    for(int c = 0; c < 4; ++c)
    {
      double sum = 0, normaliser = 0;
      for(int j = 1; j < k; ++j)
      {
        const double d = e.log_energies[c] - std::log(s.eigenvalues()[j] * A), phi = s.eigenvectors()(i, j);
        const double g = std::exp(-d * d / (2 * e.sigma * e.sigma));
        sum += g * phi * phi * A;
        normaliser += g;
      }
      worst = std::max(worst, std::abs(wks(i, c) - sum / normaliser) / (sum / normaliser));
    }
  }
  BOOST_TEST(worst < 1e-10);
  // Using them all is the default; more than the spectrum has, or none, is an error.
  BOOST_TEST((smc::wave_kernel_signature(s, params::number_of_eigenpairs(40)) - smc::wave_kernel_signature(s)).norm() == 0);
  BOOST_TEST(contains(parameter_error_of([&] { smc::wave_kernel_signature(s, params::number_of_eigenpairs(41)); }),
                      "number_of_eigenpairs = 41 must be in [1, 40]"));
  BOOST_TEST(contains(parameter_error_of([&] { smc::heat_kernel_signature(s, params::number_of_eigenpairs(0)); }),
                      "number_of_eigenpairs = 0"));
}

BOOST_AUTO_TEST_CASE(isometric_bending_keeps_the_descriptors)
{
  // A flat strip and the same strip bent onto a half cylinder (same connectivity, edge lengths
  // equal up to the chord error): the descriptors of a vertex agree far better than those of
  // two different vertices.
  const Mesh flat = strip();
  const Mesh bent = transformed(flat, [](const Point& p) { return bend_point(p, 4.3, pi); });
  const auto np = params::number_of_eigenpairs(60);
  const smc::Laplace_beltrami_spectrum a(flat, np), b(bent, np);
  BOOST_TEST(std::abs(a.total_area() - b.total_area()) < 1e-3 * a.total_area());
  const Eigen::MatrixXd ha = smc::heat_kernel_signature(a), hb = smc::heat_kernel_signature(b);
  const Eigen::MatrixXd wa = smc::wave_kernel_signature(a), wb = smc::wave_kernel_signature(b);
  const auto h = same_and_different(ha, hb), w = same_and_different(wa, wb);
  BOOST_TEST_MESSAGE("bent strip: HKS same vertex " << h.first << ", different vertices " << h.second
                                                    << "; WKS same vertex " << w.first
                                                    << ", different vertices " << w.second);
  BOOST_TEST(h.first < 0.01 * h.second);
  BOOST_TEST(w.first < 0.01 * w.second);
  BOOST_TEST(relative_difference(hb, ha) < 0.01);
  BOOST_TEST(relative_difference(wb, wa) < 0.01);
}

BOOST_AUTO_TEST_CASE(uniform_scaling_keeps_the_descriptors)
{
  const Mesh m = jittered_sphere(2, 0.3);
  const Mesh big = transformed(m, [](const Point& p) { return Point(40 * p.x(), 40 * p.y() + 3, 40 * p.z()); });
  const auto np = params::number_of_eigenpairs(50);
  const smc::Laplace_beltrami_spectrum a(m, np), b(big, np);
  BOOST_TEST(relative_difference(smc::heat_kernel_signature(b), smc::heat_kernel_signature(a)) < 1e-8);
  BOOST_TEST(relative_difference(smc::wave_kernel_signature(b), smc::wave_kernel_signature(a)) < 1e-8);
}

BOOST_AUTO_TEST_CASE(components_and_boundaries)
{
  // Two spheres (zero eigenvalue twice) and an open tube.
  Mesh two = icosphere(2);
  two.join(transformed(icosphere(2, 0.5), [](const Point& p) { return Point(p.x() + 3, p.y(), p.z()); }));
  for(const Mesh& m : {two, tube(16, 10)})
  {
    const smc::Laplace_beltrami_spectrum s(m, params::number_of_eigenpairs(40));
    const Eigen::MatrixXd hks = smc::heat_kernel_signature(s), wks = smc::wave_kernel_signature(s);
    BOOST_TEST(hks.allFinite());
    BOOST_TEST(wks.allFinite());
    BOOST_TEST(hks.minCoeff() > 0);
    BOOST_TEST((column_means(s, hks).array() - 1).abs().maxCoeff() < 1e-10);
    BOOST_TEST((column_means(s, wks).array() - 1).abs().maxCoeff() < 1e-10);
  }
  const smc::Laplace_beltrami_spectrum s(two, params::number_of_eigenpairs(40));
  BOOST_TEST(s.number_of_zero_eigenvalues() == 2);
  // The first automatic time uses the first non-zero eigenvalue.
  const Eigen::VectorXd t = smc::heat_kernel_signature_times(s);
  BOOST_TEST(t[15] == 4 * std::log(10.0) / (s.eigenvalues()[2] * s.total_area()),
             boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(parallel_and_convenience_overloads_agree)
{
  const Mesh m = jittered_sphere(3, 0.3);
  const auto np = params::number_of_eigenpairs(40, params::number_of_hks_scales(8));
  const smc::Laplace_beltrami_spectrum s(m, np);
  const Eigen::MatrixXd h = smc::heat_kernel_signature(s, np);
  const Eigen::MatrixXd w = smc::wave_kernel_signature(s, np);
  BOOST_TEST(h.cols() == 8);
#ifdef CGAL_LINKED_WITH_TBB
  BOOST_TEST((smc::heat_kernel_signature<CGAL::Parallel_tag>(s, np) - h).norm() == 0);
  BOOST_TEST((smc::wave_kernel_signature<CGAL::Parallel_tag>(s, np) - w).norm() == 0);
#endif
  BOOST_TEST((smc::heat_kernel_signature(m, np) - h).norm() == 0);
  BOOST_TEST((smc::wave_kernel_signature(m, np) - w).norm() == 0);
  // Polyhedron_3 gives the same numbers (copy_face_graph reorders the vertices: match them by
  // position).
  CGAL::Polyhedron_3<Kernel> p;
  CGAL::copy_face_graph(m, p);
  const auto im = smc::internal::make_indexed_mesh(m), ip = smc::internal::make_indexed_mesh(p);
  std::map<std::array<double, 3>, int> index_in_p;
  for(int v = 0; v < ip.number_of_vertices(); ++v)
    index_in_p[{ip.points(v, 0), ip.points(v, 1), ip.points(v, 2)}] = v;
  const Eigen::MatrixXd hp = smc::heat_kernel_signature(p, np), wp = smc::wave_kernel_signature(p, np);
  Eigen::MatrixXd hp_in_m(h.rows(), h.cols()), wp_in_m(w.rows(), w.cols());
  for(int v = 0; v < im.number_of_vertices(); ++v)
  {
    const int q = index_in_p.at({im.points(v, 0), im.points(v, 1), im.points(v, 2)});
    hp_in_m.row(v) = hp.row(q);
    wp_in_m.row(v) = wp.row(q);
  }
  BOOST_TEST(relative_difference(hp_in_m, h) < 1e-8);
  BOOST_TEST(relative_difference(wp_in_m, w) < 1e-8);
}

BOOST_AUTO_TEST_CASE(wks_rows_of_selected_vertices)
{
  // The rows computed alone are those of the whole signature, with all the eigenpairs or the
  // leading ones, in the order asked, repeated or not.
  const Mesh m = jittered_sphere(3, 0.3);
  const smc::Laplace_beltrami_spectrum s(m, params::number_of_eigenpairs(40));
  const std::vector<int> vertices = {17, 0, int(num_vertices(m)) - 1, 17};
  for(int k : {40, 12})
  {
    const auto np = params::number_of_eigenpairs(k, params::number_of_wks_energies(30));
    const Eigen::MatrixXd all = smc::wave_kernel_signature(s, np);
    const Eigen::MatrixXd rows = smc::internal::wave_kernel_signature_rows(s, vertices, np);
    BOOST_TEST(rows.rows() == 4);
    BOOST_TEST(rows.cols() == 30);
    for(std::size_t i = 0; i < vertices.size(); ++i)
      BOOST_TEST((rows.row(Eigen::Index(i)) - all.row(vertices[i])).norm() <= 1e-12 * all.row(vertices[i]).norm());
  }
  BOOST_TEST(smc::internal::wave_kernel_signature_rows(s, {}).rows() == 0);
}

BOOST_AUTO_TEST_CASE(bad_parameters_are_reported)
{
  const Mesh m = icosphere(2);
  const smc::Laplace_beltrami_spectrum s(m, params::number_of_eigenpairs(20));
  BOOST_TEST(contains(parameter_error_of([&] { smc::heat_kernel_signature(s, params::number_of_hks_scales(0)); }),
                      "number_of_hks_scales"));
  BOOST_TEST(contains(parameter_error_of([&] { smc::wave_kernel_signature(s, params::number_of_wks_energies(0)); }),
                      "number_of_wks_energies"));
  BOOST_TEST(contains(parameter_error_of([&] { smc::wave_kernel_signature(s, params::wks_variance(-1.0)); }),
                      "wks_variance"));
  BOOST_TEST(contains(parameter_error_of([&] {
                        smc::wave_kernel_signature(s.eigenvalues(), s.eigenvectors(), Eigen::VectorXd::Ones(2), 0.0);
                      }),
                      "sigma"));
  BOOST_TEST(contains(parameter_error_of([&] {
                        smc::heat_kernel_signature(s.eigenvalues().head(5), s.eigenvectors(), Eigen::VectorXd::Ones(2));
                      }),
                      "eigenvectors"));
  // Only the zero eigenvalue: no time range; one non-zero eigenvalue: no energy range.
  const smc::Laplace_beltrami_spectrum one(m, params::number_of_eigenpairs(1));
  BOOST_TEST(contains(parameter_error_of([&] { smc::heat_kernel_signature(one); }), "non-zero eigenvalue"));
  const smc::Laplace_beltrami_spectrum two(m, params::number_of_eigenpairs(2));
  BOOST_TEST(smc::heat_kernel_signature(two).allFinite());
  BOOST_TEST(contains(parameter_error_of([&] { smc::wave_kernel_signature(two); }), "two distinct"));
  // Bad k through the convenience overload.
  BOOST_TEST(contains(parameter_error_of([&] { smc::heat_kernel_signature(m, params::number_of_eigenpairs(0)); }),
                      "number_of_eigenpairs"));
}

BOOST_AUTO_TEST_SUITE_END()
