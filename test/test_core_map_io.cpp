// SPDX-License-Identifier: GPL-3.0-or-later
// Map and correspondence files: round trips in both index bases, errors naming file and line.

#include <CGAL/Surface_mesh_correspondence/map_io.h>

#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

std::string io_error_of(const std::string& text, int base, const std::string& name = "m.map")
{
  std::istringstream in(text);
  try
  {
    smc::read_vertex_indices(in, base, name);
  }
  catch(const smc::IO_error& e)
  {
    return e.what();
  }
  return "no exception";
}

std::string map_error_of(const smc::Vertex_index_map_vector& m, std::size_t ns, std::size_t nt)
{
  try
  {
    smc::check_vertex_map(m, ns, nt, "map 1->2");
  }
  catch(const smc::Invalid_map_error& e)
  {
    return e.what();
  }
  return "no exception";
}

} // namespace

BOOST_AUTO_TEST_SUITE(map_io)

BOOST_AUTO_TEST_CASE(round_trip_in_both_bases)
{
  const smc::Vertex_index_map_vector m = {0, 4, 2, 2, 7};
  for(int base : {0, 1})
  {
    std::ostringstream out;
    smc::write_vertex_indices(out, m, base);
    std::istringstream in(out.str());
    BOOST_TEST(smc::read_vertex_indices(in, base) == m, boost::test_tools::per_element());
  }
  std::ostringstream one;
  smc::write_vertex_indices(one, m, 1);
  BOOST_TEST(one.str() == "1\n5\n3\n3\n8\n");
  // Through a file, with blank lines, comments, CRLF and surrounding spaces (the datasets' files end
  // with an empty line).
  const std::string file = "smc_test_map_io.map";
  {
    std::ofstream f(file);
    f << "# a comment\n 3\r\n\n1\t\n";
  }
  const auto r = smc::read_vertex_indices(file, 1);
  BOOST_TEST(r.size() == 2u);
  BOOST_TEST(r[0] == 2u);
  BOOST_TEST(r[1] == 0u);
  std::remove(file.c_str());
}

BOOST_AUTO_TEST_CASE(bad_entries_name_file_and_line)
{
  BOOST_TEST(io_error_of("1\n2\nx\n", 1) == "m.map:3: expected one vertex index, found \"x\"");
  BOOST_TEST(io_error_of("1\n2 3\n", 1) == "m.map:2: expected one vertex index, found \"2 3\"");
  BOOST_TEST(io_error_of("4\n0\n", 1) == "m.map:2: vertex index 0 is below the index base 1");
  BOOST_TEST(io_error_of("-1\n", 0) == "m.map:1: vertex index -1 is below the index base 0");
  BOOST_TEST(io_error_of("1.5\n", 0).find("expected one vertex index") != std::string::npos);
  BOOST_TEST(io_error_of("99999999999999999999999\n", 0).find("m.map:1") != std::string::npos);
  BOOST_CHECK_THROW(smc::read_vertex_indices("/nonexistent/dir/none.map", 1), smc::IO_error);
  BOOST_CHECK_THROW(smc::write_vertex_indices("/nonexistent/dir/none.map", {1}, 1), smc::IO_error);
  std::istringstream in("1\n");
  BOOST_CHECK_THROW(smc::read_vertex_indices(in, 2), smc::Invalid_parameter_error);
}

BOOST_AUTO_TEST_CASE(map_checks)
{
  BOOST_TEST(map_error_of({0, 1, 2}, 3, 3) == "no exception");
  BOOST_TEST(map_error_of({0, 1}, 3, 3) == "map 1->2 has 2 entries but the source mesh has 3 vertices");
  BOOST_TEST(map_error_of({0, 5, 1}, 3, 5) ==
             "map 1->2: entry 1 is vertex 5 (0-based), out of range for a target mesh of 5 vertices");
  BOOST_CHECK_THROW(smc::check_vertex_indices({1, 9}, 9, "gt"), smc::Invalid_map_error);
  BOOST_CHECK_NO_THROW(smc::check_vertex_indices({1, 8}, 9, "gt"));
}

BOOST_AUTO_TEST_CASE(atomic_output_files)
{
  // A file written through Atomic_output_file keeps its previous content until commit(); an object
  // destroyed without commit() (an exception while writing) leaves neither a truncated file nor its
  // temporary file; the temporary file is hidden and sits in the same folder.
  char name[] = "/tmp/smc_test_atomic_XXXXXX";
  const char* made = ::mkdtemp(name);
  BOOST_TEST_REQUIRE(made != nullptr);
  const std::string dir = made, file = dir + "/m.map";
  auto content = [](const std::string& f) {
    std::ifstream in(f);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  auto entries = [&] {
    std::size_t n = 0;
    for(const auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
    return n;
  };
  std::ofstream(file) << "old\n";
  {
    smc::Atomic_output_file out(file);
    BOOST_TEST(out.temporary_filename().rfind(dir + "/.m.map.tmp-", 0) == 0u);
    out.stream() << "new\n";
    out.close();
    BOOST_TEST(content(file) == "old\n");  // written, not yet committed
    BOOST_TEST(content(out.temporary_filename()) == "new\n");
  }  // destroyed without commit()
  BOOST_TEST(content(file) == "old\n");
  BOOST_TEST(entries() == 1u);
  {
    smc::Atomic_output_file out(file);
    out.stream() << "new\n";
    out.commit();
  }
  BOOST_TEST(content(file) == "new\n");
  BOOST_TEST(entries() == 1u);
  // write_vertex_indices() goes through it.
  smc::write_vertex_indices(file, {2, 0}, 1);
  BOOST_TEST(content(file) == "3\n1\n");
  BOOST_TEST(entries() == 1u);
  BOOST_CHECK_THROW(smc::Atomic_output_file(dir + "/missing/m.map"), smc::IO_error);
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
