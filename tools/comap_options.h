// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: a small command-line parser (long options with a value or without, `--name=value`,
// positional arguments, generated --help with defaults) and strict value parsers whose errors
// name the option.

#ifndef SMC_TOOLS_COMAP_OPTIONS_H
#define SMC_TOOLS_COMAP_OPTIONS_H

#include "comap_common.h"

#include <climits>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace comap {

/// Long options of one subcommand.
class Option_parser
{
public:
  Option_parser(std::string command, std::string usage, std::string description)
      : command_(std::move(command)), usage_(std::move(usage)), description_(std::move(description))
  {}

  /// Starts a new group of options in --help.
  void section(const std::string& title) { entries_.push_back({title, "", "", "", true, false, {}, {}}); }

  /// An option without value (`--quiet`).
  void flag(const std::string& name, const std::string& help, std::function<void()> action)
  {
    entries_.push_back({name, "", help, "", false, false, std::move(action), {}});
  }

  /// An option with a value (`--candidates 20` or `--candidates=20`); `default_text` is shown
  /// in --help (empty: none).
  void value(const std::string& name, const std::string& metavar, const std::string& help,
             const std::string& default_text, std::function<void(const std::string&)> action)
  {
    entries_.push_back({name, metavar, help, default_text, false, true, {}, std::move(action)});
  }

  /// Text printed after the options in --help.
  void epilogue(const std::string& text) { epilogue_ = text; }

  /// The number of options (not counting sections).
  std::size_t number_of_options() const
  {
    std::size_t n = 0;
    for(const Entry& e : entries_) n += !e.is_section;
    return n;
  }

  /// Parses argv[first, argc); returns the positional arguments. Returns false in `run` when
  /// --help was given (the help is then printed on stdout).
  std::vector<std::string> parse(int argc, char** argv, int first, bool& run) const;

  void print_help(std::ostream& out) const;
  const std::string& command() const { return command_; }

private:
  struct Entry
  {
    std::string name, metavar, help, default_text;
    bool is_section, takes_value;
    std::function<void()> on_flag;
    std::function<void(const std::string&)> on_value;
  };
  std::string command_, usage_, description_, epilogue_;
  std::vector<Entry> entries_;
};

/// Strict parsers: the whole text must be the value; errors name the option.
int parse_int(const std::string& option, const std::string& text);
/// An integer in [minimum, maximum].
int parse_int(const std::string& option, const std::string& text, int minimum, int maximum);
double parse_double(const std::string& option, const std::string& text);
/// on/off, true/false, yes/no, 1/0.
bool parse_bool(const std::string& option, const std::string& text);
/// "6,4,3" -> {6, 4, 3}.
std::vector<int> parse_int_list(const std::string& option, const std::string& text);
/// One of `choices`; returns its position.
int parse_choice(const std::string& option, const std::string& text, const std::vector<std::string>& choices);

inline const char* on_off(bool b) { return b ? "on" : "off"; }

} // namespace comap

#endif // SMC_TOOLS_COMAP_OPTIONS_H
