// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_settings.h"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

namespace comap {

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
    settings.set(name, smc::parse_setting_value(value, "--set " + name));
  }
  catch(const smc::IO_error& e)
  {
    throw Usage_error(e.what());
  }
  catch(const smc::Error& e)
  {
    throw Usage_error(std::string("--set: ") + e.what());
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
            smc::read_settings_file(v, settings);
            if(settings_files) settings_files->push_back(v);
          });
  p.value("--set", "NAME=VALUE", "one expert setting (repeatable; after --settings, in order)", "",
          [&settings](const std::string& v) { set_setting(v, settings); });
  p.epilogue(settings_help());
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
  std::cout << smc::settings_file_template();
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
