// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: the library's settings (the registry, smc::Matching_settings) from a settings file
// (--settings FILE.json) and from --set NAME=VALUE, the expert part of --help generated from the
// registry, and the settings written into the JSON statistics.

#ifndef SMC_TOOLS_COMAP_SETTINGS_H
#define SMC_TOOLS_COMAP_SETTINGS_H

#include "comap_json.h"
#include "comap_options.h"

#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/settings_io.h>

#include <string>

namespace comap {

/// --set NAME=VALUE: VALUE as in a settings file; a bare word is a string, "4,3,2,1" a list.
void set_setting(const std::string& assignment, smc::Matching_settings& settings);

/// Registers --settings FILE.json and --set NAME=VALUE on `parser`, and the expert help: one line
/// per setting of the registry (name, type, defaults, range, documentation).
void add_settings_options(Option_parser& parser, smc::Matching_settings& settings,
                          std::vector<std::string>* settings_files = nullptr);

/// `comap settings`: prints smc::settings_file_template().
int run_settings(int argc, char** argv);

/// The expert help: the registry as text, one entry per setting.
std::string settings_help();

/// Writes every setting (resolved for maps of origin `origin`) as a JSON object named `key`.
void write_settings(Json_writer& json, const std::string& key, const smc::Matching_settings& settings,
                    smc::Map_origin origin);

} // namespace comap

#endif // SMC_TOOLS_COMAP_SETTINGS_H
