// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The manual's settings table (doc/settings.md) is the registry's: every row, in order, with the
// type, defaults, range, stage and documentation line the registry gives; the setting names
// that the other pages of the manual and the README write in backquotes as named parameters
// exist in the registry or are one of the other named parameters; the defaults that the other
// pages' tables give for registry settings are the registry's; and the README's library example
// is the snippet of examples/match_meshes.cpp.

#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

std::string read_file(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The table the registry makes: one row per setting.
std::string registry_table()
{
  std::string t = "| setting | type | default | default for given maps | range | stage | what it does |\n"
                  "|---|---|---|---|---|---|---|\n";
  for(const smc::Setting_info& s : smc::matching_settings_registry())
    t += "| `" + s.name + "` | " + s.type + " | `" + s.default_text + "` | " +
         (s.given_default_text == s.default_text ? std::string("") : "`" + s.given_default_text + "`") + " | " +
         s.range_text + " | " + smc::to_string(s.stage) + " | " + s.documentation + " |\n";
  return t;
}

const char* const begin_marker = "<!-- registry table: begin -->\n";
const char* const end_marker = "<!-- registry table: end -->";

/// The cells of a markdown table row ("| a | b |"), trimmed; "\\|" inside a cell is not a separator.
std::vector<std::string> table_cells(const std::string& line)
{
  std::vector<std::string> cells;
  std::string cell;
  for(std::size_t i = 1; i < line.size(); ++i)
  {
    if(line[i] == '|' && line[i - 1] != '\\')
    {
      cells.push_back(cell);
      cell.clear();
    }
    else
      cell += line[i];
  }
  for(std::string& c : cells)
  {
    const std::size_t b = c.find_first_not_of(" \t"), e = c.find_last_not_of(" \t");
    c = b == std::string::npos ? std::string() : c.substr(b, e - b + 1);
  }
  return cells;
}

/// A cell as plain text: without backquotes, runs of blanks made one space.
std::string plain(const std::string& cell)
{
  std::string out;
  for(char c : cell)
  {
    if(c == '`') continue;
    if((c == ' ' || c == '\t') && (out.empty() || out.back() == ' ')) continue;
    out += c == '\t' ? ' ' : c;
  }
  while(!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

/// Whether a table cell shows `value`: the cell is the value, or starts with it and a space
/// ("40 (m)", "[4, 3, 2, 1] (the last one repeats)").
bool shows(const std::string& cell, const std::string& value)
{
  const std::string c = plain(cell);
  return c == value || (c.size() > value.size() && c.compare(0, value.size(), value) == 0 && c[value.size()] == ' ');
}

struct Default_check
{
  std::size_t rows = 0;
  std::vector<std::string> errors;
};

/// Checks, in the markdown text `text` of `page`, every table row whose first cell starts with a
/// registry setting in backquotes, against the registry defaults, in the columns of its header
/// named like "default" (a column whose name also says "given" holds the default for given maps;
/// empty there means the same as the default).
void check_table_defaults(const std::string& page, const std::string& text, Default_check& out)
{
  std::map<std::string, const smc::Setting_info*> registry;
  for(const smc::Setting_info& s : smc::matching_settings_registry()) registry[s.name] = &s;
  const std::regex first_setting("^`([a-z_0-9]+)`");
  std::istringstream lines(text);
  std::string line, previous;
  std::vector<std::pair<std::size_t, bool> > default_columns;  // (column, for given maps)
  bool in_table = false;
  for(std::size_t number = 1; std::getline(lines, line); ++number, previous = line)
  {
    if(line.empty() || line[0] != '|')
    {
      in_table = false;
      continue;
    }
    if(line.compare(0, 4, "|---") == 0 || line.compare(0, 5, "| ---") == 0)
    {
      // The separator: the previous line is the header.
      in_table = true;
      default_columns.clear();
      const std::vector<std::string> header = table_cells(previous);
      for(std::size_t c = 0; c < header.size(); ++c)
      {
        std::string h = header[c];
        std::transform(h.begin(), h.end(), h.begin(), [](unsigned char x) { return char(std::tolower(x)); });
        if(h.find("default") != std::string::npos) default_columns.emplace_back(c, h.find("given") != std::string::npos);
      }
      continue;
    }
    if(!in_table || default_columns.empty()) continue;
    const std::vector<std::string> cells = table_cells(line);
    std::smatch m;
    if(cells.empty() || !std::regex_search(cells[0], m, first_setting)) continue;
    const auto it = registry.find(m[1]);
    if(it == registry.end()) continue;
    const smc::Setting_info& s = *it->second;
    ++out.rows;
    for(const auto& column : default_columns)
    {
      if(column.first >= cells.size()) continue;
      const std::string& cell = cells[column.first];
      const bool ok = column.second ? (shows(cell, s.given_default_text) ||
                                       (plain(cell).empty() && s.given_default_text == s.default_text))
                                    : (shows(cell, s.default_text) || shows(cell, s.given_default_text));
      if(!ok)
        out.errors.push_back(page + ":" + std::to_string(number) + ": " + s.name + " shows \"" + cell +
                             "\" as its " + (column.second ? "default for given maps" : "default") +
                             "; the registry says \"" + (column.second ? s.given_default_text : s.default_text) + "\"" +
                             (column.second || s.given_default_text == s.default_text
                                  ? std::string()
                                  : " (for given maps \"" + s.given_default_text + "\")"));
    }
  }
}

/// The text between the line `// [snippet:NAME]` and the line `// [/snippet:NAME]` of `source`.
std::string snippet(const std::string& source, const std::string& name)
{
  const std::string begin = "// [snippet:" + name + "]\n", end = "// [/snippet:" + name + "]";
  const std::size_t b = source.find(begin);
  if(b == std::string::npos) return std::string();
  const std::size_t e = source.find(end, b);
  if(e == std::string::npos) return std::string();
  return source.substr(b + begin.size(), e - b - begin.size());
}

/// The text of the first ```cpp block of a markdown page (without its fences).
std::string first_cpp_block(const std::string& page)
{
  const std::string fence = "```cpp\n";
  const std::size_t b = page.find(fence);
  if(b == std::string::npos) return std::string();
  const std::size_t e = page.find("\n```", b + fence.size() - 1);
  if(e == std::string::npos) return std::string();
  return page.substr(b + fence.size(), e + 1 - b - fence.size());
}

/// The Markdown pages of the manual: README.md, benchmark/README.md and doc/*.md.
std::vector<std::string> manual_pages()
{
  std::vector<std::string> pages = {std::string(SMC_SOURCE_DIR) + "/README.md",
                                    std::string(SMC_SOURCE_DIR) + "/benchmark/README.md"};
  for(const auto& entry : std::filesystem::directory_iterator(std::string(SMC_SOURCE_DIR) + "/doc"))
    if(entry.path().extension() == ".md") pages.push_back(entry.path().string());
  return pages;
}

} // namespace

BOOST_AUTO_TEST_SUITE(settings_documentation)

BOOST_AUTO_TEST_CASE(the_manual_table_is_the_registry)
{
  const std::string doc = read_file(std::string(SMC_SOURCE_DIR) + "/doc/settings.md");
  BOOST_TEST_REQUIRE(!doc.empty(), "doc/settings.md is missing");
  const std::size_t b = doc.find(begin_marker), e = doc.find(end_marker);
  BOOST_TEST_REQUIRE((b != std::string::npos && e != std::string::npos && b < e),
                     "doc/settings.md has no registry table markers");
  const std::string table = doc.substr(b + std::string(begin_marker).size(), e - b - std::string(begin_marker).size());
  const std::string expected = registry_table();
  if(table != expected)
  {
    const std::string out = std::string(SMC_TEST_BINARY_DIR) + "/settings_table.md";
    std::ofstream(out) << expected;
    BOOST_ERROR("doc/settings.md's table differs from the registry; the registry's table is in " + out);
  }
}

BOOST_AUTO_TEST_CASE(named_parameters_in_the_manual_exist)
{
  // `name(` in the manual's pages and the README: a named parameter call, which must be a
  // registry setting or one of the package's or CGAL's other named parameters.
  std::set<std::string> known;
  for(const smc::Setting_info& s : smc::matching_settings_registry()) known.insert(s.name);
#define SMC_TEST_KNOWN_PARAMETER(TAG, VALUE, FUNCTION) known.insert(#FUNCTION);
  CGAL_SMC_NAMED_PARAMETERS(SMC_TEST_KNOWN_PARAMETER)
#undef SMC_TEST_KNOWN_PARAMETER
  known.insert("initial_maps");  // initial_maps(a, b) makes the pair of initial_maps_pair
  // CGAL's own named parameters that the package reads.
  for(const char* cgal : {"visitor", "verbose", "vertex_point_map", "vertex_index_map", "face_index_map",
                          "number_of_iterations", "default_values"})
    known.insert(cgal);
  const std::regex call("(?:params|parameters)::([a-z_]+)\\(");
  std::size_t calls = 0;
  for(const std::string& page : manual_pages())
  {
    const std::string text = read_file(page);
    for(std::sregex_iterator it(text.begin(), text.end(), call), end; it != end; ++it)
    {
      ++calls;
      const std::string name = (*it)[1];
      if(!known.count(name))
        BOOST_ERROR(page + ": params::" + name + "( is neither a setting of the registry nor a named parameter");
    }
  }
  BOOST_TEST_MESSAGE(calls << " named parameter calls in the manual");
}

BOOST_AUTO_TEST_CASE(settings_set_by_name_in_the_manual_exist)
{
  // Settings the pages set by name: `--set name=`, `set("name"` and `"name": value` in settings
  // files (JSON objects in code blocks); each must be a registry setting.
  std::set<std::string> registry;
  for(const smc::Setting_info& s : smc::matching_settings_registry()) registry.insert(s.name);
  const std::regex by_name("--set ([a-z_0-9]+)=|\\.set\\(\"([a-z_0-9]+)\"|[{,]\\s*\"([a-z_0-9]+)\":");
  std::size_t names = 0;
  for(const std::string& page : manual_pages())
  {
    const std::string text = read_file(page);
    for(std::sregex_iterator it(text.begin(), text.end(), by_name), end; it != end; ++it)
    {
      const std::string name = (*it)[1].matched ? (*it)[1] : (*it)[2].matched ? (*it)[2] : (*it)[3];
      if(name == "name") continue;  // the placeholder of `--set name=value`
      ++names;
      if(!registry.count(name)) BOOST_ERROR(page + ": \"" + name + "\" is set by name but is not a setting of the registry");
    }
  }
  BOOST_TEST(names >= 10u, names << " settings set by name in the manual");
}

BOOST_AUTO_TEST_CASE(the_readme_example_is_the_example_program)
{
  // The README's first C++ block is the text between the snippet markers of
  // examples/match_meshes.cpp, exactly.
  const std::string readme = read_file(std::string(SMC_SOURCE_DIR) + "/README.md");
  const std::string source = read_file(std::string(SMC_SOURCE_DIR) + "/examples/match_meshes.cpp");
  const std::string expected = snippet(source, "match");
  BOOST_TEST_REQUIRE(!expected.empty(), "examples/match_meshes.cpp has no // [snippet:match] ... // [/snippet:match]");
  const std::string block = first_cpp_block(readme);
  BOOST_TEST_REQUIRE(!block.empty(), "README.md has no ```cpp block");
  if(block != expected)
  {
    std::size_t i = 0;
    while(i < block.size() && i < expected.size() && block[i] == expected[i]) ++i;
    const std::size_t line = std::size_t(std::count(expected.begin(), expected.begin() + std::ptrdiff_t(i), '\n')) + 1;
    BOOST_ERROR("README.md's first ```cpp block differs from the snippet of examples/match_meshes.cpp from line " +
                std::to_string(line) + " of the snippet on");
  }
}

BOOST_AUTO_TEST_CASE(examples_shown_in_the_manual_are_the_example_programs)
{
  // A ```cpp block after "<!-- example: examples/NAME.cpp -->" is that file, exactly (the build
  // compiles the examples; scripts/extract_doc_snippets.py leaves these blocks to them).
  const std::regex marked("<!-- example: (examples/[a-z_]+\\.cpp) -->\n```cpp\n");
  std::size_t shown = 0;
  for(const std::string& page : manual_pages())
  {
    const std::string text = read_file(page);
    for(std::sregex_iterator it(text.begin(), text.end(), marked), end; it != end; ++it)
    {
      ++shown;
      const std::size_t begin = std::size_t(it->position() + it->length());
      const std::size_t close = text.find("\n```", begin - 1);
      BOOST_TEST_REQUIRE(close != std::string::npos);
      const std::string block = text.substr(begin, close + 1 - begin);
      const std::string file = (*it)[1];
      BOOST_TEST((block == read_file(std::string(SMC_SOURCE_DIR) + "/" + file)),
                 page << " shows " << file << " but differs from the file");
    }
  }
  BOOST_TEST(shown >= 3u, shown << " example programs shown in the manual");
}

BOOST_AUTO_TEST_CASE(defaults_in_the_manual_tables_are_the_registry_s)
{
  // The tables of the other pages that list registry settings with a "default" column show the
  // registry's defaults (doc/settings.md has its own test).
  Default_check check;
  for(const auto& entry : std::filesystem::directory_iterator(std::string(SMC_SOURCE_DIR) + "/doc"))
    if(entry.path().extension() == ".md" && entry.path().filename() != "settings.md")
      check_table_defaults(entry.path().string(), read_file(entry.path().string()), check);
  check_table_defaults(std::string(SMC_SOURCE_DIR) + "/README.md", read_file(std::string(SMC_SOURCE_DIR) + "/README.md"),
                       check);
  for(const std::string& e : check.errors) BOOST_ERROR(e);
  // The parser found the tables (doc/coupled_refinement.md lists the refinement's settings with
  // both defaults).
  BOOST_TEST(check.rows >= 5u, check.rows << " table rows with a registry setting and a default column");
  BOOST_TEST_MESSAGE(check.rows << " table rows of registry settings with defaults checked");
}

BOOST_AUTO_TEST_CASE(the_default_check_sees_a_wrong_default)
{
  // The check itself: a table that gives the wrong default fails, the right ones pass.
  Default_check bad, good;
  check_table_defaults("bad.md",
                       "| setting | default | default for given maps | meaning |\n|---|---|---|---|\n"
                       "| `number_of_candidates` | 30 | 20 | m |\n| `ring_schedule` | `[4, 3, 2, 1]` | `[6, 4, 3]` | r |\n",
                       bad);
  check_table_defaults("good.md",
                       "| setting | default | default for given maps | meaning |\n|---|---|---|---|\n"
                       "| `number_of_candidates` | 40 (m) | 20 | m |\n| `unary_weight` | `0.03` | | mu |\n",
                       good);
  BOOST_TEST(bad.rows == 2u);
  BOOST_TEST(bad.errors.size() == 2u);
  BOOST_TEST(good.rows == 2u);
  BOOST_TEST(good.errors.empty());
}

BOOST_AUTO_TEST_SUITE_END()
