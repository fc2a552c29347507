// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_options.h"

#include <sys/stat.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace comap {

bool file_exists(const std::string& path)
{
  struct stat s;
  return ::stat(path.c_str(), &s) == 0 && S_ISREG(s.st_mode);
}

bool directory_exists(const std::string& path)
{
  struct stat s;
  return ::stat(path.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}

void make_directories(const std::string& path)
{
  if(path.empty() || directory_exists(path)) return;
  std::string partial;
  for(const std::string& part : split(path, '/'))
  {
    partial += part;
    if(!partial.empty() && !directory_exists(partial))
    {
      if(::mkdir(partial.c_str(), 0777) != 0 && errno != EEXIST)
        throw Input_error("cannot create directory " + partial + ": " + std::strerror(errno));
      if(!directory_exists(partial)) throw Input_error("cannot create directory " + partial + ": not a directory");
    }
    partial += '/';
  }
}

std::vector<std::string> Option_parser::parse(int argc, char** argv, int first, bool& run) const
{
  run = true;
  std::vector<std::string> positional;
  for(int i = first; i < argc; ++i)
  {
    std::string arg = argv[i];
    if(arg == "-h" || arg == "--help")
    {
      print_help(std::cout);
      run = false;
      return positional;
    }
    if(arg.size() < 2 || arg[0] != '-' || arg == "-")
    {
      positional.push_back(arg);
      continue;
    }
    if(arg == "--")
    {
      for(++i; i < argc; ++i) positional.push_back(argv[i]);
      break;
    }
    std::string value;
    bool has_inline_value = false;
    const std::size_t eq = arg.find('=');
    if(eq != std::string::npos)
    {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      has_inline_value = true;
    }
    const Entry* entry = nullptr;
    for(const Entry& e : entries_)
      if(!e.is_section && e.name == arg) entry = &e;
    if(!entry) throw Usage_error("unknown option " + arg);
    if(entry->takes_value)
    {
      if(!has_inline_value)
      {
        if(i + 1 >= argc) throw Usage_error("option " + arg + " needs a value (" + entry->metavar + ")");
        value = argv[++i];
      }
      entry->on_value(value);
    }
    else
    {
      if(has_inline_value) throw Usage_error("option " + arg + " takes no value");
      entry->on_flag();
    }
  }
  return positional;
}

void Option_parser::print_help(std::ostream& out) const
{
  out << "usage: " << usage_ << "\n\n";
  // The description, wrapped at 100 columns.
  std::size_t width = 0;
  std::istringstream text(description_);
  std::string w;
  while(text >> w)
  {
    if(width > 0 && width + 1 + w.size() > 100)
    {
      out << "\n";
      width = 0;
    }
    out << (width > 0 ? " " : "") << w;
    width += (width > 0 ? 1 : 0) + w.size();
  }
  out << "\n";
  for(const Entry& e : entries_)
  {
    if(e.is_section)
    {
      out << "\n" << e.name << ":\n";
      continue;
    }
    std::string left = "  " + e.name + (e.takes_value ? " " + e.metavar : "");
    std::string help = e.help;
    if(!e.default_text.empty()) help += " (default " + e.default_text + ")";
    const std::size_t column = 30;
    if(left.size() + 2 > column)
      out << left << "\n" << std::string(column, ' ');
    else
      out << left << std::string(column - left.size(), ' ');
    // Wrap the help at about 100 columns.
    std::size_t width = column;
    std::istringstream words(help);
    std::string word;
    bool first_word = true;
    while(words >> word)
    {
      if(!first_word && width + 1 + word.size() > 100)
      {
        out << "\n" << std::string(column, ' ');
        width = column;
        first_word = true;
      }
      out << (first_word ? "" : " ") << word;
      width += (first_word ? 0 : 1) + word.size();
      first_word = false;
    }
    out << "\n";
  }
  if(!epilogue_.empty()) out << "\n" << epilogue_;
}

int parse_int(const std::string& option, const std::string& text)
{
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s, &end, 10);
  if(text.empty() || end == s || *end != '\0' || errno == ERANGE || v < INT_MIN || v > INT_MAX)
    throw Usage_error("bad value for " + option + ": \"" + text + "\" is not an integer");
  return static_cast<int>(v);
}

int parse_int(const std::string& option, const std::string& text, int minimum, int maximum)
{
  const int v = parse_int(option, text);
  if(v < minimum || v > maximum)
    throw Usage_error("bad value for " + option + ": " + text + " is not in [" + std::to_string(minimum) + ", " +
                      (maximum == INT_MAX ? std::string("inf") : std::to_string(maximum)) + "]");
  return v;
}

double parse_double(const std::string& option, const std::string& text)
{
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  if(text.empty() || end == s || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw Usage_error("bad value for " + option + ": \"" + text + "\" is not a finite number");
  return v;
}

bool parse_bool(const std::string& option, const std::string& text)
{
  if(text == "on" || text == "true" || text == "yes" || text == "1") return true;
  if(text == "off" || text == "false" || text == "no" || text == "0") return false;
  throw Usage_error("bad value for " + option + ": \"" + text + "\" (expected on or off)");
}

std::vector<int> parse_int_list(const std::string& option, const std::string& text)
{
  std::vector<int> out;
  for(const std::string& field : split(text, ','))
  {
    if(field.empty())
      throw Usage_error("bad value for " + option + ": \"" + text + "\" (expected integers separated by commas)");
    out.push_back(parse_int(option, field));
  }
  if(out.empty()) throw Usage_error("bad value for " + option + ": empty list");
  return out;
}

int parse_choice(const std::string& option, const std::string& text, const std::vector<std::string>& choices)
{
  for(std::size_t i = 0; i < choices.size(); ++i)
    if(choices[i] == text) return static_cast<int>(i);
  std::string list;
  for(std::size_t i = 0; i < choices.size(); ++i) list += (i ? ", " : "") + choices[i];
  throw Usage_error("bad value for " + option + ": \"" + text + "\" (expected one of " + list + ")");
}

} // namespace comap
