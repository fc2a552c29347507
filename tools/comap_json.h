// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: a minimal streaming JSON writer (objects, arrays, numbers, strings, booleans) with
// two-space indentation. Non-finite numbers are written as null.

#ifndef SMC_TOOLS_COMAP_JSON_H
#define SMC_TOOLS_COMAP_JSON_H

#include "comap_common.h"

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace comap {

class Json_writer
{
public:
  explicit Json_writer(std::ostream& out) : out_(out) {}
  ~Json_writer() = default;

  Json_writer& begin_object(const std::string& key = "") { return open(key, '{'); }
  Json_writer& end_object() { return close('}'); }
  Json_writer& begin_array(const std::string& key = "") { return open(key, '['); }
  Json_writer& end_array() { return close(']'); }

  Json_writer& value(const std::string& key, double x) { return raw(key, number(x)); }
  Json_writer& value(const std::string& key, int x) { return raw(key, std::to_string(x)); }
  Json_writer& value(const std::string& key, long x) { return raw(key, std::to_string(x)); }
  Json_writer& value(const std::string& key, std::size_t x) { return raw(key, std::to_string(x)); }
  Json_writer& value(const std::string& key, bool x) { return raw(key, x ? "true" : "false"); }
  Json_writer& value(const std::string& key, const char* s) { return raw(key, quote(s)); }
  Json_writer& value(const std::string& key, const std::string& s) { return raw(key, quote(s)); }
  Json_writer& value(const std::string& key, const std::vector<double>& v)
  {
    std::string s = "[";
    for(std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
    return raw(key, s + "]");
  }
  Json_writer& value(const std::string& key, const std::vector<int>& v)
  {
    std::string s = "[";
    for(std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return raw(key, s + "]");
  }
  /// A value already written as JSON text.
  Json_writer& raw_value(const std::string& key, const std::string& json_text) { return raw(key, json_text); }
  /// An array element (inside begin_array()).
  template <typename T>
  Json_writer& element(const T& x)
  {
    return value("", x);
  }
  void finish() { out_ << "\n"; }

  static std::string number(double x) { return std::isfinite(x) ? shortest(x) : "null"; }
  static std::string quote(const std::string& s)
  {
    std::string out = "\"";
    for(char c : s)
    {
      switch(c)
      {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if(static_cast<unsigned char>(c) < 0x20)
        {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        }
        else
          out += c;
      }
    }
    return out + "\"";
  }

private:
  void separator(const std::string& key)
  {
    if(!first_.empty())
    {
      out_ << (first_.back() ? "\n" : ",\n");
      first_.back() = false;
    }
    out_ << std::string(2 * first_.size(), ' ');
    if(!key.empty()) out_ << quote(key) << ": ";
  }
  Json_writer& raw(const std::string& key, const std::string& text)
  {
    separator(key);
    out_ << text;
    return *this;
  }
  Json_writer& open(const std::string& key, char bracket)
  {
    separator(key);
    out_ << bracket;
    first_.push_back(true);
    return *this;
  }
  Json_writer& close(char bracket)
  {
    const bool empty = first_.back();
    first_.pop_back();
    if(!empty) out_ << "\n" << std::string(2 * first_.size(), ' ');
    out_ << bracket;
    return *this;
  }

  std::ostream& out_;
  std::vector<bool> first_;
};

} // namespace comap

#endif // SMC_TOOLS_COMAP_JSON_H
