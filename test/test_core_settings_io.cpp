// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Settings files (settings_io.h): the template of the registry reads back as the registry's
// defaults; comments, null, lists and lists of lists are read; malformed text, unknown names and
// bad values are refused with the file and the line.

#include <CGAL/Surface_mesh_correspondence/settings_io.h>

#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

/// The message of the exception `f` throws (of type E), or "" when it throws none.
template <typename E, typename F>
std::string settings_error_of(F f)
{
  try
  {
    f();
  }
  catch(const E& e)
  {
    return e.what();
  }
  return "";
}

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

} // namespace

BOOST_AUTO_TEST_SUITE(settings_files)

BOOST_AUTO_TEST_CASE(the_template_reads_back_as_the_registry)
{
  const std::string text = smc::settings_file_template();
  const std::vector<smc::Settings_file_entry> entries = smc::parse_settings_file(text, "template");
  const std::vector<smc::Setting_info>& registry = smc::matching_settings_registry();
  BOOST_TEST_REQUIRE(entries.size() == registry.size());
  smc::Matching_settings read;
  for(std::size_t i = 0; i < entries.size(); ++i)
  {
    BOOST_TEST(entries[i].name == registry[i].name);
    // null exactly where the default depends on the maps' origin.
    BOOST_TEST(!entries[i].value == (registry[i].default_text != registry[i].given_default_text), registry[i].name);
    if(entries[i].value) read.set(entries[i].name, *entries[i].value);
  }
  const smc::Matching_settings defaults;
  for(const smc::Setting_info& s : registry) BOOST_TEST(read.text(s.name) == defaults.text(s.name), s.name);
}

BOOST_AUTO_TEST_CASE(values_comments_and_null)
{
  const std::string text = "// expert run\n{\n  \"number_of_candidates\": 60, // more candidates\n"
                           "  \"ring_schedule\": [6, 4,3],\n  \"use_coupling\": false,\n  \"distance_oracle\": \"local\",\n"
                           "  \"unary_weight\": null,\n  \"initialization_fits\": [[30, 1, 0.1], [60, 0.5, 0.01]]\n}\n";
  const std::vector<smc::Settings_file_entry> e = smc::parse_settings_file(text, "expert.json");
  BOOST_TEST_REQUIRE(e.size() == 6u);
  BOOST_TEST(e[0].line == 3u);
  BOOST_TEST(std::get<double>(*e[0].value) == 60.0);
  BOOST_TEST((std::get<std::vector<double> >(*e[1].value) == std::vector<double>{6, 4, 3}));
  BOOST_TEST(std::get<bool>(*e[2].value) == false);
  BOOST_TEST(std::get<std::string>(*e[3].value) == "local");
  BOOST_TEST(!e[4].value);
  const auto fits = std::get<std::vector<std::vector<double> > >(*e[5].value);
  BOOST_TEST_REQUIRE(fits.size() == 2u);
  BOOST_TEST(fits[1][2] == 0.01);

  const std::string file = "test_core_settings_io.json";
  {
    std::ofstream out(file);
    out << text;
  }
  smc::Matching_settings s;
  s.set("unary_weight", 7.0);  // null leaves it as it is
  smc::read_settings_file(file, s);
  BOOST_TEST(s.text("number_of_candidates") == "60");
  BOOST_TEST(s.text("ring_schedule") == "[6, 4, 3]");
  BOOST_TEST(s.text("use_coupling") == "false");
  BOOST_TEST(s.text("unary_weight") == "7");
  std::remove(file.c_str());
}

BOOST_AUTO_TEST_CASE(errors_name_the_file_and_the_line)
{
  // Malformed JSON: file, line and column.
  const std::string syntax = settings_error_of<smc::IO_error>(
      [] { smc::parse_settings_file("{\n  \"number_of_candidates\": 60,\n  \"ring_schedule\": [6,, 3]\n}", "a.json"); });
  BOOST_TEST(mentions(syntax, "a.json:3:"), syntax);
  BOOST_TEST(mentions(syntax, "expected a number"), syntax);
  BOOST_TEST(mentions(settings_error_of<smc::IO_error>([] { smc::parse_settings_file("{\"use_coupling\": true", "b"); }),
                      "b:1:"));
  BOOST_TEST(mentions(settings_error_of<smc::IO_error>([] { smc::parse_settings_file("{} {}", "c"); }), "unexpected text"));
  // Unknown name: the closest valid one, with the line.
  const std::string unknown = settings_error_of<smc::Invalid_parameter_error>(
      [] { smc::parse_settings_file("{\n\n \"number_of_candidate\": 30}", "d.json"); });
  BOOST_TEST(mentions(unknown, "d.json:3:"), unknown);
  BOOST_TEST(mentions(unknown, "did you mean \"number_of_candidates\""), unknown);
  // Wrong type, out of range, unknown word.
  BOOST_TEST(mentions(settings_error_of<smc::Invalid_parameter_error>(
                          [] { smc::parse_settings_file("{\"number_of_candidates\": \"many\"}", "e"); }),
                      "number_of_candidates"));
  BOOST_TEST(mentions(settings_error_of<smc::Invalid_parameter_error>(
                          [] { smc::parse_settings_file("{\"unary_weight\": -1}", "f"); }),
                      "out of its range"));
  BOOST_TEST(mentions(settings_error_of<smc::Invalid_parameter_error>(
                          [] { smc::parse_settings_file("{\"distance_oracle\": \"fast\"}", "g"); }),
                      "automatic, dense or local"));
  // A missing file.
  smc::Matching_settings s;
  BOOST_TEST(mentions(settings_error_of<smc::IO_error>([&] { smc::read_settings_file("no/such/settings.json", s); }),
                      "no/such/settings.json"));
  // One value (--set).
  BOOST_TEST(std::get<double>(smc::parse_setting_value(" 2.5 ", "--set x")) == 2.5);
  BOOST_TEST(mentions(settings_error_of<smc::IO_error>([] { smc::parse_setting_value("2.5 x", "--set x"); }), "--set x:1:"));
}

BOOST_AUTO_TEST_SUITE_END()
