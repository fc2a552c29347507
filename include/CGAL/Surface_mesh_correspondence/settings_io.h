// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Settings files: the settings of the registry (matching_settings.h) as a JSON object, with //
// comments and null for "the registry's default". The same reader serves the command line
// (`comap match --settings FILE`), the Python package and any program that wants its settings in
// a file; settings_file_template() writes the registry in that form, to edit.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_SETTINGS_IO_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_SETTINGS_IO_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

namespace internal {

/// The JSON of settings files: objects whose values are numbers, true/false, null, strings,
/// lists of numbers and lists of lists of numbers; white space and // comments between tokens.
/// Errors are IO_error naming `what`, the line and the column.
class Settings_json_reader
{
public:
  Settings_json_reader(const std::string& text, std::string what) : text_(text), what_(std::move(what)) {}

  void skip_space()
  {
    while(pos_ < text_.size())
    {
      if(std::isspace(static_cast<unsigned char>(text_[pos_])))
        ++pos_;
      else if(text_.compare(pos_, 2, "//") == 0)
        while(pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      else
        break;
    }
  }
  bool at_end()
  {
    skip_space();
    return pos_ >= text_.size();
  }
  char peek()
  {
    skip_space();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  void expect(char c)
  {
    if(peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  /// Consumes `null` when it comes next.
  bool null_token()
  {
    if(peek() != 'n') return false;
    if(text_.compare(pos_, 4, "null") != 0) fail("expected a value");
    pos_ += 4;
    return true;
  }
  std::string string_token()
  {
    expect('"');
    std::string out;
    while(pos_ < text_.size() && text_[pos_] != '"')
    {
      if(text_[pos_] == '\\' && pos_ + 1 < text_.size()) ++pos_;
      out += text_[pos_++];
    }
    if(pos_ >= text_.size()) fail("unterminated string");
    ++pos_;
    return out;
  }
  double number()
  {
    skip_space();
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double x = std::strtod(begin, &end);
    if(end == begin) fail("expected a number");
    pos_ += std::size_t(end - begin);
    return x;
  }
  /// Reads `[item, item, ...]`, possibly empty, calling `item()` for each element.
  template <typename Item>
  void list_of(Item item)
  {
    expect('[');
    if(peek() != ']')
      while(true)
      {
        item();
        if(peek() != ',') break;
        ++pos_;
      }
    expect(']');
  }
  std::vector<double> number_list()
  {
    std::vector<double> list;
    list_of([&] { list.push_back(number()); });
    return list;
  }
  Setting_value value()
  {
    const char c = peek();
    if(c == '"') return string_token();
    if(c == 't' || c == 'f')
    {
      const std::string word = c == 't' ? "true" : "false";
      if(text_.compare(pos_, word.size(), word) != 0) fail("expected true or false");
      pos_ += word.size();
      return c == 't';
    }
    if(c != '[') return number();
    // A list of numbers, or a list of lists: look past the '['.
    const std::size_t open = pos_++;
    const bool nested = peek() == '[';
    pos_ = open;
    if(!nested) return number_list();
    std::vector<std::vector<double> > lists;
    list_of([&] { lists.push_back(number_list()); });
    return lists;
  }
  /// The line of the current position (1-based).
  std::size_t line() const
  {
    std::size_t line = 1;
    for(std::size_t i = 0; i < pos_ && i < text_.size(); ++i) line += text_[i] == '\n';
    return line;
  }
  [[noreturn]] void fail(const std::string& message) const
  {
    std::size_t column = 1;
    for(std::size_t i = 0; i < pos_ && i < text_.size(); ++i) column = text_[i] == '\n' ? 1 : column + 1;
    throw IO_error(what_ + ":" + std::to_string(line()) + ":" + std::to_string(column) + ": " + message);
  }

private:
  const std::string& text_;
  std::string what_;
  std::size_t pos_ = 0;
};

inline std::string json_quoted(const std::string& s)
{
  std::string out = "\"";
  for(char c : s)
  {
    if(c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// One entry of a settings file: a setting of the registry and its value; no value for `null`
/// (the registry's default, which for some settings depends on where the refined maps came from).
struct Settings_file_entry
{
  std::string name;
  std::optional<Setting_value> value;
  std::size_t line = 0;  ///< where the entry starts in the file (1-based)
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Parses one value as a settings file writes it: a number, `true` / `false`, a string (a word of
/// an enumeration), a list of numbers or a list of lists of numbers.
/// \throws IO_error naming `what`, the line and the column when the text is not such a value.
inline Setting_value parse_setting_value(const std::string& text, const std::string& what)
{
  internal::Settings_json_reader reader(text, what);
  const Setting_value v = reader.value();
  if(!reader.at_end()) reader.fail("unexpected text after the value");
  return v;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The entries of a settings file's text, in their order, each checked against the registry.
/// \param text the contents of the settings file
/// \param what names the text in messages (the file name).
/// \throws IO_error (malformed JSON: `what:line:column: ...`) or Invalid_parameter_error (`what:line:
///   ...`: an unknown name, with the closest valid one, or a value of the wrong type or out of the
///   setting's range).
inline std::vector<Settings_file_entry> parse_settings_file(const std::string& text, const std::string& what)
{
  internal::Settings_json_reader reader(text, what);
  std::vector<Settings_file_entry> entries;
  Matching_settings check;
  reader.expect('{');
  if(reader.peek() != '}')
    while(true)
    {
      Settings_file_entry e;
      reader.skip_space();
      e.line = reader.line();
      e.name = reader.string_token();
      reader.expect(':');
      if(!reader.null_token()) e.value = reader.value();
      try
      {
        if(e.value)
          check.set(e.name, *e.value);
        else
          check.text(e.name);  // null: checks that the name exists
      }
      catch(const Invalid_parameter_error& error)
      {
        throw Invalid_parameter_error(what + ":" + std::to_string(e.line) + ": " + error.what());
      }
      entries.push_back(std::move(e));
      if(reader.peek() != ',') break;
      reader.expect(',');
    }
  reader.expect('}');
  if(!reader.at_end()) reader.fail("unexpected text after the settings object");
  return entries;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The entries of a settings file (parse_settings_file() on its contents).
/// \throws IO_error when the file cannot be read or is malformed, Invalid_parameter_error for an
///   unknown setting or a bad value, both naming the file and the line.
inline std::vector<Settings_file_entry> read_settings_file(const std::string& file)
{
  std::ifstream in(file);
  if(!in) throw IO_error("cannot open the settings file " + file);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if(in.bad()) throw IO_error("cannot read the settings file " + file);
  return parse_settings_file(buffer.str(), file);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Sets in `settings` the entries of a settings file (those with `null` keep the registry's
/// default); the other settings are left as they are. Throws as the overload above.
inline void read_settings_file(const std::string& file, Matching_settings& settings)
{
  for(const Settings_file_entry& e : read_settings_file(file))
    if(e.value) settings.set(e.name, *e.value);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The registry as a settings file to edit: every setting with its default, grouped by stage,
/// with its documentation, type and range in comments; the settings whose default depends on
/// where the refined maps came from are `null`. read_settings_file() reads it back.
inline std::string settings_file_template()
{
  std::ostringstream out;
  out << "// The settings of the library's registry with their defaults: a settings file for\n"
         "// comap match, bench and demo (--settings FILE), comap.batch and read_settings_file().\n"
         "// Change the values you need and delete the other lines, or leave them. null keeps the\n"
         "// registry's default: the settings whose default depends on where the refined maps came\n"
         "// from are null. Text after // is a comment.\n"
         "{";
  std::string stage;
  const std::vector<Setting_info>& registry = matching_settings_registry();
  for(std::size_t i = 0; i < registry.size(); ++i)
  {
    const Setting_info& s = registry[i];
    if(stage != to_string(s.stage))
    {
      stage = to_string(s.stage);
      out << "\n  // ------------------------------------------------ " << stage << "\n";
    }
    const bool by_origin = s.given_default_text != s.default_text;
    out << "  // " << s.documentation << "\n  // " << s.type << ", " << s.range_text;
    if(by_origin)
      out << "; default " << s.default_text << " for automatic maps, " << s.given_default_text << " for given maps";
    out << "\n  " << internal::json_quoted(s.name) << ": "
        << (by_origin ? std::string("null") : s.type == "word" ? internal::json_quoted(s.default_text) : s.default_text)
        << (i + 1 < registry.size() ? "," : "") << "\n";
  }
  out << "}\n";
  return out.str();
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_SETTINGS_IO_H
