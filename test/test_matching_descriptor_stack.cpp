// SPDX-License-Identifier: GPL-3.0-or-later
// The weighted descriptor stack: block normalisation, weights, user block, invariances, errors.

#include <CGAL/Surface_mesh_correspondence/descriptor_stack.h>

#include "test_meshes.h"

#include <boost/property_map/function_property_map.hpp>
#include <boost/test/unit_test.hpp>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = smc::parameters;
using namespace smc_test;

namespace {

double area_weighted_mean_square(const Mesh& m, const Eigen::MatrixXf& f)
{
  const auto im = smc::internal::make_indexed_mesh(m);
  const Eigen::VectorXd a = smc::internal::vertex_areas(im);
  return (a.array() * f.cast<double>().rowwise().squaredNorm().array()).sum() / a.sum();
}

// A bumpy capsule without symmetries (SHOT needs a non-degenerate frame).
Mesh bumpy_capsule()
{
  return transformed(capsule(24, 6, 16, 1.0, 4.0), [](const Point& p) {
    const double s = 1.0 + 0.1 * std::sin(3 * p.z() + 0.5) * std::cos(2 * std::atan2(p.y(), p.x()) + 0.3 * p.z());
    return Point(s * p.x(), s * p.y(), p.z());
  });
}

} // namespace

BOOST_AUTO_TEST_SUITE(descriptor_stack)

BOOST_AUTO_TEST_CASE(blocks_are_normalised_and_weighted)
{
  const Mesh m = bumpy_capsule();
  const auto only_shot = smc::descriptor_stack(m, params::hks_weight(0.0, params::wks_weight(0.0)));
  BOOST_TEST(only_shot.cols() == 352);
  BOOST_TEST(area_weighted_mean_square(m, only_shot) == 1.0, boost::test_tools::tolerance(1e-5));
  const auto hks = smc::descriptor_stack(m, params::hks_weight(2.0, params::wks_weight(0.0, params::shot_weight(0.0))));
  BOOST_TEST(hks.cols() == 16);
  BOOST_TEST(area_weighted_mean_square(m, hks) == 4.0, boost::test_tools::tolerance(1e-5));
  const auto all = smc::descriptor_stack<CGAL::Parallel_if_available_tag>(m);
  BOOST_TEST(all.cols() == 16 + 100 + 352);
  // Default weights 0.5, 1, 1: mean squared norm 0.25 + 1 + 1.
  BOOST_TEST(area_weighted_mean_square(m, all) == 2.25, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(all.allFinite());
}

BOOST_AUTO_TEST_CASE(user_block_is_appended)
{
  const Mesh m = bumpy_capsule();
  // The height as a one-value user descriptor.
  auto height = boost::make_function_property_map<Vertex>([&m](Vertex v) { return std::vector<double>{m.point(v).z()}; });
  const auto f = smc::descriptor_stack(m, params::user_descriptor_map(height, params::user_descriptor_weight(3.0,
                                           params::hks_weight(0.0, params::wks_weight(0.0, params::shot_weight(0.0))))));
  BOOST_TEST(f.cols() == 1);
  BOOST_TEST(area_weighted_mean_square(m, f) == 9.0, boost::test_tools::tolerance(1e-5));
  // The column is proportional to the height.
  const double ratio = f(5, 0) / m.point(Vertex(5)).z();
  for(Vertex v : m.vertices())
    if(std::abs(m.point(v).z()) > 0.1) BOOST_TEST(f(v.idx(), 0) / m.point(v).z() == ratio, boost::test_tools::tolerance(1e-4));
  // Users may give only their own descriptor.
  auto bad = boost::make_function_property_map<Vertex>([](Vertex v) { return std::vector<double>(v.idx() == 3 ? 2 : 1, 0.0); });
  BOOST_CHECK_THROW(smc::descriptor_stack(m, params::user_descriptor_map(bad)), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(uniform_scaling_and_bending)
{
  const Mesh m = bumpy_capsule();
  const Mesh big = transformed(m, [](const Point& p) { return Point(250 * p.x(), 250 * p.y(), 250 * p.z()); });
  const auto a = smc::descriptor_stack(m), b = smc::descriptor_stack(big);
  BOOST_TEST((a - b).cwiseAbs().maxCoeff() < 1e-4);

  // Near-isometric bend of the capsule: the same vertex keeps a far closer stack than others.
  const Mesh bent = transformed(m, [](const Point& p) { return bend_point(p, 4.0, 0.6); });
  const auto c = smc::descriptor_stack(bent);
  double same = 0, other = 0;
  const Eigen::Index n = a.rows();
  for(Eigen::Index i = 0; i < n; ++i)
  {
    same += (a.row(i) - c.row(i)).squaredNorm();
    other += (a.row(i) - c.row((i + n / 2) % n)).squaredNorm();
  }
  BOOST_TEST_MESSAGE("bent capsule: mean squared stack distance same vertex " << same / n << ", other vertex " << other / n);
  BOOST_TEST(same < 0.35 * other);
}

BOOST_AUTO_TEST_CASE(bad_settings)
{
  const Mesh m = icosphere(2);
  BOOST_CHECK_THROW(smc::descriptor_stack(m, params::hks_weight(-1.0)), smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::descriptor_stack(m, params::hks_weight(0.0, params::wks_weight(0.0, params::shot_weight(0.0)))),
                    smc::Invalid_parameter_error);
  BOOST_CHECK_THROW(smc::descriptor_stack(Mesh()), smc::Invalid_mesh_error);
}

BOOST_AUTO_TEST_SUITE_END()
