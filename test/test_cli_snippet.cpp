// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The README's library snippet (examples/match_meshes.cpp, one call of match_shapes()) and
// `comap match` give the same maps, byte for byte: on the demo's pair (Homer and its re-posed,
// remeshed copy; the generated capsule pair without libcgal-demo), whose maps `comap demo` writes
// too, and on a FAUST_r pair when the shared data is there.

#include "test_cli_helpers.h"

#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

using namespace smc_cli_test;

namespace {

/// Runs the example program; its exit code.
int run_example(const std::string& arguments)
{
  const std::string command = std::string(SMC_TEST_BINARY_DIR) + "/bin/match_meshes " + arguments + " > " +
                              in_scratch("example.out") + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

/// The shared benchmark data (SMC_DATA, else ../shared/data next to the sources), or "".
std::string shared_data()
{
  const char* env = std::getenv("SMC_DATA");
  const std::string dir = env ? env : std::string(SMC_SOURCE_DIR) + "/../shared/data";
  return std::filesystem::exists(dir + "/FAUST_r/off") ? dir : std::string();
}

/// comap match and the example on the same two files: the same maps, byte for byte.
void check_same_maps(const std::string& a, const std::string& b, const std::string& name)
{
  const std::string c12 = in_scratch(name + "_comap_12.map"), c21 = in_scratch(name + "_comap_21.map");
  const Run r = comap("match " + a + " " + b + " --out-12 " + c12 + " --out-21 " + c21 + " --quiet");
  BOOST_TEST_REQUIRE(r.code == 0, "comap match failed: " << r.err);
  BOOST_TEST_REQUIRE(run_example(a + " " + b + " " + in_scratch(name + "_example")) == 0,
                     "match_meshes failed: " << read_text(in_scratch("example.out")));
  const std::string e12 = read_text(in_scratch(name + "_example_12.map")),
                    e21 = read_text(in_scratch(name + "_example_21.map"));
  BOOST_TEST(!e12.empty());
  BOOST_TEST((e12 == read_text(c12)), name << ": the maps 1 -> 2 of the snippet and of comap match differ");
  BOOST_TEST((e21 == read_text(c21)), name << ": the maps 2 -> 1 of the snippet and of comap match differ");
}

} // namespace

BOOST_AUTO_TEST_SUITE(library_snippet)

BOOST_AUTO_TEST_CASE(snippet_and_comap_match_agree_on_the_demo_pair)
{
  const std::string out = in_scratch("demo");
  const Run demo = comap("demo --out " + out + " --quiet");
  BOOST_TEST_REQUIRE(demo.code == 0, "comap demo failed: " << demo.err);
  const bool homer = std::filesystem::exists(out + "/homer_posed.off");
  const std::string stem = out + "/" + (homer ? "homer" : "capsule");
  BOOST_TEST_MESSAGE("demo pair: " << (homer ? "Homer" : "the generated capsule"));
  // With libcgal-demo installed, Homer is extracted from its archive (atomically: no temporary
  // file is left beside the outputs).
  if(std::filesystem::exists("/usr/share/doc/libcgal-demo/data.tar.gz"))
    BOOST_TEST(homer, "libcgal-demo is installed but the demo did not use homer.off");
  for(const auto& entry : std::filesystem::directory_iterator(out))
    BOOST_TEST(entry.path().filename().string().find(".tmp-") == std::string::npos,
               "temporary file left in the demo folder: " << entry.path());
  check_same_maps(stem + ".off", stem + "_posed.off", "demo");
  // The demo runs the same call on the same meshes (1-based maps, like the example's).
  BOOST_TEST((read_text(out + "/final_12.map") == read_text(in_scratch("demo_example_12.map"))));
  BOOST_TEST((read_text(out + "/final_21.map") == read_text(in_scratch("demo_example_21.map"))));
}

BOOST_AUTO_TEST_CASE(snippet_and_comap_match_agree_on_a_faust_pair)
{
  const std::string data = shared_data();
  if(data.empty())
  {
    BOOST_TEST_MESSAGE("no FAUST_r data (SMC_DATA or ../shared/data): skipped");
    return;
  }
  check_same_maps(data + "/FAUST_r/off/tr_reg_000.off", data + "/FAUST_r/off/tr_reg_001.off", "faust");
}

BOOST_AUTO_TEST_SUITE_END()
