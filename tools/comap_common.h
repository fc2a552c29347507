// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: types and small helpers shared by every subcommand (mesh type, concurrency tag,
// usage errors, progress lines on stderr, number formatting, file-system helpers).

#ifndef SMC_TOOLS_COMAP_COMMON_H
#define SMC_TOOLS_COMAP_COMMON_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/tags.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
}
} // namespace CGAL

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;

/// Every parallel code path of the library runs with this tag: TBB when the library found it.
#ifdef CGAL_LINKED_WITH_TBB
typedef CGAL::Parallel_tag Concurrency;
constexpr bool has_tbb = true;
#else
typedef CGAL::Sequential_tag Concurrency;
constexpr bool has_tbb = false;
#endif

/// The process's peak resident set size in MiB (VmHWM of /proc/self/status; 0 where unknown).
inline double peak_memory_mib()
{
  FILE* f = std::fopen("/proc/self/status", "r");
  if(!f) return 0;
  char line[256];
  double kib = 0;
  while(std::fgets(line, sizeof(line), f))
    if(std::strncmp(line, "VmHWM:", 6) == 0) kib = std::atof(line + 6);
  std::fclose(f);
  return kib / 1024.0;
}

/// A bad command line (unknown option, missing or malformed value): exit code 2.
class Usage_error : public std::runtime_error
{
public:
  explicit Usage_error(const std::string& what) : std::runtime_error(what) {}
};

/// Bad input that the library does not check itself (exit code 1, like the library's errors).
class Input_error : public std::runtime_error
{
public:
  explicit Input_error(const std::string& what) : std::runtime_error(what) {}
};

/// Progress lines on stderr, "[  12.3 s] message", silenced by --quiet; safe to call from
/// several threads.
class Progress
{
public:
  explicit Progress(bool quiet = false) : quiet_(quiet), start_(std::chrono::steady_clock::now()) {}
  bool quiet() const { return quiet_; }
  void set_quiet(bool q) { quiet_ = q; }
  /// Seconds since the program started.
  double elapsed() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void line(const std::string& message) const
  {
    if(quiet_) return;
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "[%7.1f s] ", elapsed());
    std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << stamp << message << std::endl;
  }

private:
  bool quiet_;
  std::chrono::steady_clock::time_point start_;
  mutable std::mutex mutex_;
};

/// Wall-clock stopwatch.
class Stopwatch
{
public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void reset() { start_ = std::chrono::steady_clock::now(); }

private:
  std::chrono::steady_clock::time_point start_;
};

/// `x` with `digits` digits after the point.
inline std::string fixed(double x, int digits = 3)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, x);
  return buffer;
}

/// `x` in the shortest form that reads back to the same double (for JSON, CSV and --help).
inline std::string shortest(double x)
{
  // The fewest digits that read back exactly, without an exponent when one is not needed.
  char buffer[64], first[64] = "";
  for(int precision = 1; precision <= 17; ++precision)
  {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, x);
    if(std::strtod(buffer, nullptr) != x) continue;
    if(first[0] == 0) std::snprintf(first, sizeof(first), "%s", buffer);
    if(std::strchr(buffer, 'e') == nullptr) return buffer;
  }
  return first;
}

/// `x` with `digits` significant digits.
inline std::string significant(double x, int digits = 6)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*g", digits, x);
  return buffer;
}

/// A percentage with one decimal: 0.7312 -> "73.1%".
inline std::string percent(double fraction) { return fixed(100.0 * fraction, 1) + "%"; }

/// Seconds, readable: "0.42 s", "12.3 s", "3 min 20 s".
inline std::string duration(double seconds)
{
  if(seconds < 10) return fixed(seconds, 2) + " s";
  if(seconds < 120) return fixed(seconds, 1) + " s";
  const long s = static_cast<long>(seconds + 0.5);
  if(s < 7200) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string((s % 3600) / 60) + " min";
}

/// "a,b,c" -> {"a", "b", "c"} (empty fields kept).
inline std::vector<std::string> split(const std::string& s, char separator)
{
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(s);
  while(std::getline(in, field, separator)) out.push_back(field);
  if(!s.empty() && s.back() == separator) out.emplace_back();
  return out;
}

inline std::string join(const std::vector<int>& values, const char* separator = ",")
{
  std::string out;
  for(std::size_t i = 0; i < values.size(); ++i) out += (i ? separator : "") + std::to_string(values[i]);
  return out;
}

/// The last component of a path without its extension: "/a/b/cat0.off" -> "cat0".
inline std::string stem(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

/// One line: newlines in a message become spaces.
inline std::string one_line(std::string s)
{
  for(char& c : s)
    if(c == '\n' || c == '\r') c = ' ';
  while(!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

bool file_exists(const std::string& path);
bool directory_exists(const std::string& path);
/// Creates `path` and its parents; throws Input_error naming the directory on failure.
void make_directories(const std::string& path);

} // namespace comap

#endif // SMC_TOOLS_COMAP_COMMON_H
