// SPDX-License-Identifier: GPL-3.0-or-later
// Named parameters: defaults, each of ours given, ours and CGAL's mixed in both orders, combine().

#include <CGAL/Surface_mesh_correspondence/parameters.h>

#include <boost/test/unit_test.hpp>

#include <string>
#include <type_traits>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
namespace np_tags = CGAL::Surface_mesh_correspondence::internal_np;

namespace {

// A function reading parameters the way the package's entry points do.
struct Read_values
{
  int candidates;
  double mu;
  int iterations;
  bool verbose;
  bool candidates_default;
};

template <typename NamedParameters = params::Default_named_parameters>
Read_values read_values(const NamedParameters& np = params::default_values())
{
  using params::choose_parameter;
  using params::get_parameter;
  Read_values r;
  r.candidates = choose_parameter(get_parameter(np, np_tags::number_of_candidates), 20);
  r.mu = choose_parameter(get_parameter(np, np_tags::unary_weight), 1.5);
  r.iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 7);
  r.verbose = choose_parameter(get_parameter(np, CGAL::internal_np::verbose), false);
  r.candidates_default =
      params::is_default_parameter<NamedParameters, np_tags::number_of_candidates_t>::value;
  return r;
}

} // namespace

BOOST_AUTO_TEST_SUITE(named_parameters)

BOOST_AUTO_TEST_CASE(defaults_are_used_when_nothing_is_given)
{
  const Read_values r = read_values();
  BOOST_TEST(r.candidates == 20);
  BOOST_TEST(r.mu == 1.5);
  BOOST_TEST(r.iterations == 7);
  BOOST_TEST(!r.verbose);
  BOOST_TEST(r.candidates_default);
}

BOOST_AUTO_TEST_CASE(each_of_ours_is_read)
{
  BOOST_TEST(read_values(params::number_of_candidates(33)).candidates == 33);
  BOOST_TEST(!read_values(params::number_of_candidates(33)).candidates_default);
  BOOST_TEST(read_values(params::unary_weight(0.25)).mu == 0.25);
  // Every tag of the list has a function that stores its value.
  auto p = params::ring_schedule(std::vector<int>{6, 4, 3});
  std::vector<int> rings = params::choose_parameter(params::get_parameter(p, np_tags::ring_schedule),
                                                    std::vector<int>());
  BOOST_TEST(rings.size() == 3u);
  BOOST_TEST(rings[0] == 6);
}

BOOST_AUTO_TEST_CASE(ours_then_cgal_chained)
{
  const Read_values r = read_values(params::number_of_candidates(12).number_of_iterations(99).verbose(true));
  BOOST_TEST(r.candidates == 12);
  BOOST_TEST(r.iterations == 99);
  BOOST_TEST(r.verbose);
  BOOST_TEST(r.mu == 1.5);
}

BOOST_AUTO_TEST_CASE(cgal_then_ours_pushed)
{
  const Read_values r = read_values(
      params::unary_weight(3.0, params::number_of_candidates(8, CGAL::parameters::number_of_iterations(5))));
  BOOST_TEST(r.candidates == 8);
  BOOST_TEST(r.mu == 3.0);
  BOOST_TEST(r.iterations == 5);
}

BOOST_AUTO_TEST_CASE(combine_merges_in_both_orders)
{
  auto ours = params::unary_weight(0.5, params::number_of_candidates(40));
  auto cgal = CGAL::parameters::number_of_iterations(11).verbose(true);
  const Read_values a = read_values(params::combine(ours, cgal));
  const Read_values b = read_values(params::combine(cgal, ours));
  for(const Read_values& r : {a, b})
  {
    BOOST_TEST(r.candidates == 40);
    BOOST_TEST(r.mu == 0.5);
    BOOST_TEST(r.iterations == 11);
    BOOST_TEST(r.verbose);
  }
  // The first pack wins when both give a parameter.
  BOOST_TEST(read_values(params::combine(params::number_of_candidates(1), params::number_of_candidates(2)))
                 .candidates == 1);
  // The empty pack is neutral on either side.
  BOOST_TEST(read_values(params::combine(params::default_values(), ours)).candidates == 40);
  BOOST_TEST(read_values(params::combine(ours, params::default_values())).candidates == 40);
}

BOOST_AUTO_TEST_CASE(references_are_kept_for_non_copyable_values)
{
  std::vector<int> seeds = {1, 2, 3};
  auto p = params::seed_vertices(std::cref(seeds));
  const std::vector<int>& got = params::get_parameter_reference(p, np_tags::seed_vertices);
  BOOST_TEST(&got == &seeds);
}

BOOST_AUTO_TEST_SUITE_END()
