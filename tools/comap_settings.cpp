// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_settings.h"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

namespace comap {

namespace {

/// A small JSON reader for settings: objects of settings, whose values are numbers, true/false,
/// strings, lists of numbers and lists of lists of numbers.
class Json_reader
{
public:
  Json_reader(const std::string& text, std::string what) : text_(text), what_(std::move(what)) {}

  // Skips white space and // comments (to the end of the line), which `comap settings` writes.
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
  /// Consumes `null` when it comes next.
  bool null_token()
  {
    if(peek() != 'n') return false;
    if(text_.compare(pos_, 4, "null") != 0) fail("expected a value");
    pos_ += 4;
    return true;
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
  smc::Setting_value value()
  {
    const char c = peek();
    if(c == '"') return string_token();
    if(c == 't' || c == 'f')
    {
      const bool b = c == 't';
      const std::string word = b ? "true" : "false";
      if(text_.compare(pos_, word.size(), word) != 0) fail("expected true or false");
      pos_ += word.size();
      return b;
    }
    if(c == '[')
    {
      ++pos_;
      if(peek() == '[')
      {
        std::vector<std::vector<double> > lists;
        while(true)
        {
          expect('[');
          std::vector<double> list;
          if(peek() != ']')
            while(true)
            {
              list.push_back(number());
              if(peek() != ',') break;
              ++pos_;
            }
          expect(']');
          lists.push_back(list);
          if(peek() != ',') break;
          ++pos_;
        }
        expect(']');
        return lists;
      }
      std::vector<double> list;
      if(peek() != ']')
        while(true)
        {
          list.push_back(number());
          if(peek() != ',') break;
          ++pos_;
        }
      expect(']');
      return list;
    }
    return number();
  }
  [[noreturn]] void fail(const std::string& message) const
  {
    // The line and column of the position.
    std::size_t line = 1, column = 1;
    for(std::size_t i = 0; i < pos_ && i < text_.size(); ++i)
    {
      if(text_[i] == '\n')
      {
        ++line;
        column = 1;
      }
      else
        ++column;
    }
    throw Input_error(what_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
  }

private:
  const std::string& text_;
  std::string what_;
  std::size_t pos_ = 0;
};

} // namespace

smc::Setting_value parse_setting_value(const std::string& text, const std::string& what)
{
  Json_reader reader(text, what);
  const smc::Setting_value v = reader.value();
  if(!reader.at_end()) reader.fail("unexpected text after the value");
  return v;
}

void read_settings_file(const std::string& file, smc::Matching_settings& settings)
{
  std::ifstream in(file);
  if(!in) throw Input_error("cannot open the settings file " + file);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  Json_reader reader(text, file);
  reader.expect('{');
  if(reader.peek() != '}')
    while(true)
    {
      const std::string key = reader.string_token();
      reader.expect(':');
      try
      {
        if(reader.null_token())
          settings.text(key);  // null: the registry's default (checks that the name exists)
        else
          settings.set(key, reader.value());
      }
      catch(const smc::Error& e)
      {
        throw Input_error(file + ": " + e.what());
      }
      if(reader.peek() != ',') break;
      reader.expect(',');
    }
  reader.expect('}');
  if(!reader.at_end()) reader.fail("unexpected text after the settings object");
}

void set_setting(const std::string& assignment, smc::Matching_settings& settings)
{
  const std::size_t eq = assignment.find('=');
  if(eq == std::string::npos || eq == 0)
    throw Usage_error("--set needs NAME=VALUE (not \"" + assignment + "\")");
  const std::string name = assignment.substr(0, eq);
  std::string value = assignment.substr(eq + 1);
  const char first = value.empty() ? '\0' : value[0];
  const bool json_like = first == '[' || first == '"' || first == '-' || first == '.' ||
                         std::isdigit(static_cast<unsigned char>(first)) || value == "true" || value == "false";
  if(!json_like)
    value = "\"" + value + "\"";  // a word
  else if(first != '[' && value.find(',') != std::string::npos)
    value = "[" + value + "]";  // 4,3,2,1
  try
  {
    settings.set(name, parse_setting_value(value, "--set " + name));
  }
  catch(const smc::Error& e)
  {
    throw Usage_error(std::string("--set: ") + e.what());
  }
  catch(const Input_error& e)
  {
    throw Usage_error(e.what());
  }
}

std::string settings_help()
{
  std::ostringstream out;
  out << "Expert settings (the library's settings registry), in --settings FILE.json as\n"
         "{\"name\": value, ...} or with --set name=value; defaults in brackets, \"given maps:\" the default\n"
         "when refining maps that were given and kept:\n";
  const char* stage = "";
  for(const smc::Setting_info& s : smc::matching_settings_registry())
  {
    if(std::string(stage) != smc::to_string(s.stage))
    {
      stage = smc::to_string(s.stage);
      out << "\n" << stage << ":\n";
    }
    out << "  " << s.name << " (" << s.type << ", " << s.range_text << ") [" << s.default_text
        << (s.given_default_text != s.default_text ? "; given maps: " + s.given_default_text : std::string()) << "]\n"
        << "      " << s.documentation << "\n";
  }
  return out.str();
}

void add_settings_options(Option_parser& p, smc::Matching_settings& settings, std::vector<std::string>* settings_files)
{
  p.value("--settings", "FILE.json", "expert settings, a JSON object {\"name\": value}; see the list below", "",
          [&settings, settings_files](const std::string& v) {
            read_settings_file(v, settings);
            if(settings_files) settings_files->push_back(v);
          });
  p.value("--set", "NAME=VALUE", "one expert setting (repeatable; after --settings, in order)", "",
          [&settings](const std::string& v) { set_setting(v, settings); });
  p.epilogue(settings_help());
}

std::string settings_file_template()
{
  std::ostringstream out;
  out << "// The settings of the library's registry with their defaults: a settings file for\n"
         "// comap match, bench and demo (--settings FILE). Change the values you need and delete the\n"
         "// other lines, or leave them. null keeps the registry's default: the settings whose default\n"
         "// depends on where the refined maps came from are null. Text after // is a comment.\n"
         "{";
  const char* stage = "";
  const std::vector<smc::Setting_info>& registry = smc::matching_settings_registry();
  for(std::size_t i = 0; i < registry.size(); ++i)
  {
    const smc::Setting_info& s = registry[i];
    if(std::string(stage) != smc::to_string(s.stage))
    {
      stage = smc::to_string(s.stage);
      out << "\n  // ------------------------------------------------ " << stage << "\n";
    }
    const bool by_origin = s.given_default_text != s.default_text;
    out << "  // " << s.documentation << "\n  // " << s.type << ", " << s.range_text;
    if(by_origin)
      out << "; default " << s.default_text << " for automatic maps, " << s.given_default_text << " for given maps";
    out << "\n  " << Json_writer::quote(s.name) << ": "
        << (by_origin ? std::string("null") : s.type == "word" ? Json_writer::quote(s.default_text) : s.default_text)
        << (i + 1 < registry.size() ? "," : "") << "\n";
  }
  out << "}\n";
  return out.str();
}

int run_settings(int argc, char** argv)
{
  Option_parser p("settings", "comap settings > FILE.json",
                  "Prints every setting of the library's registry with its default, type, range and documentation, "
                  "as a settings file to edit and pass to comap match, bench or demo with --settings FILE.json.");
  bool run = true;
  const std::vector<std::string> extra = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(!extra.empty()) throw Usage_error("unexpected argument " + extra.front());
  std::cout << settings_file_template();
  return 0;
}

void write_settings(Json_writer& json, const std::string& key, const smc::Matching_settings& settings,
                    smc::Map_origin origin)
{
  const smc::Matching_settings resolved = settings.resolved(origin);
  json.begin_object(key);
  for(const smc::Setting_info& s : smc::matching_settings_registry())
    json.raw_value(s.name, s.type == "word" ? Json_writer::quote(resolved.text(s.name)) : resolved.text(s.name));
  json.end_object();
}

} // namespace comap
