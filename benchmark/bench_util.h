// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Small helpers shared by the benchmark programs: wall-clock timing, peak resident memory (with a
// reset so each component can be measured in one process), the meshes benchmarks run on, and
// CSV + table printing.

#ifndef SMC_BENCH_UTIL_H
#define SMC_BENCH_UTIL_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace smc_bench {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;

/// Wall-clock seconds since construction (or the last reset()).
class Timer
{
public:
  Timer() : start_(std::chrono::steady_clock::now()) {}
  void reset() { start_ = std::chrono::steady_clock::now(); }
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

private:
  std::chrono::steady_clock::time_point start_;
};

/// Reads a "VmXXX:   1234 kB" line of /proc/self/status, in MiB (0 when unavailable).
inline double proc_status_mib(const char* key)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string k(key);
  while(std::getline(in, line))
    if(line.compare(0, k.size(), k) == 0)
    {
      std::istringstream s(line.substr(k.size() + 1));
      double kb = 0;
      s >> kb;
      return kb / 1024.0;
    }
  return 0;
}

/// Resets the process's peak resident set size to its current size (Linux >= 4.0), so that
/// peak_memory_mib() afterwards measures the peak of what runs next.
inline void reset_peak_memory()
{
  std::ofstream clear("/proc/self/clear_refs");
  if(clear) clear << "5";
}

/// Peak resident set size since the start or the last reset_peak_memory(), in MiB.
inline double peak_memory_mib() { return proc_status_mib("VmHWM:"); }
/// Current resident set size, in MiB.
inline double current_memory_mib() { return proc_status_mib("VmRSS:"); }

/// Directory of the shared benchmark data (../shared/data from the project root), overridable
/// with the SMC_DATA environment variable.
inline std::string data_directory()
{
  if(const char* env = std::getenv("SMC_DATA")) return env;
#ifdef SMC_SOURCE_DIR
  return std::string(SMC_SOURCE_DIR) + "/../shared/data";
#else
  return "../shared/data";
#endif
}

inline bool read_mesh(const std::string& file, Mesh& m)
{
  m.clear();
  std::ifstream in(file);
  return in && CGAL::IO::read_OFF(in, m) && !m.is_empty();
}

/// A closed torus-like test surface with bumps (genus 1, no symmetry), with about n vertices.
inline Mesh generated_mesh(int n)
{
  const int nu = std::max(8, static_cast<int>(std::sqrt(n * 2.0)));
  const int nv = std::max(4, n / nu);
  const double pi = 3.14159265358979323846;
  Mesh m;
  std::vector<Mesh::Vertex_index> vs;
  for(int j = 0; j < nv; ++j)
    for(int i = 0; i < nu; ++i)
    {
      const double u = 2 * pi * (i + 0.5 * (j % 2)) / nu, v = 2 * pi * j / nv;
      const double r = 1.0 + 0.15 * std::sin(3 * u) * std::cos(2 * v);
      vs.push_back(m.add_vertex(Point((3 + r * std::cos(v)) * std::cos(u),
                                      (3 + r * std::cos(v)) * std::sin(u), r * std::sin(v))));
    }
  auto id = [&](int i, int j) { return vs[((j + nv) % nv) * nu + ((i % nu) + nu) % nu]; };
  for(int j = 0; j < nv; ++j)
    for(int i = 0; i < nu; ++i)
    {
      if(j % 2 == 0)
      {
        m.add_face(id(i, j), id(i + 1, j), id(i, j + 1));
        m.add_face(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      }
      else
      {
        m.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        m.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      }
    }
  return m;
}

/// The vertex of a mesh nearest to a point (Euclidean), with CGAL's kd-tree: benchmarks use it to
/// carry maps and ground truth from a mesh to a remeshed copy of it.
class Nearest_vertex_search
{
  typedef CGAL::Search_traits_3<Kernel> Base_traits;
  typedef CGAL::Pointer_property_map<Point>::const_type Point_map;
  typedef CGAL::Search_traits_adapter<std::size_t, Point_map, Base_traits> Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits, CGAL::Distance_adapter<std::size_t, Point_map, CGAL::Euclidean_distance<Base_traits> > >
      Search;

public:
  explicit Nearest_vertex_search(const Mesh& m)
  {
    for(Mesh::Vertex_index v : m.vertices()) points_.push_back(m.point(v));
    const Point_map ppmap = CGAL::make_property_map(std::as_const(points_));
    tree_.reset(new Search::Tree(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(points_.size()),
                                 Search::Splitter(), Traits(ppmap)));
    tree_->build();
  }
  std::size_t nearest(const Point& p) const
  {
    const Point_map ppmap = CGAL::make_property_map(points_);
    Search search(*tree_, p, 1, 0, true, Search::Distance(ppmap));
    return search.begin()->first;
  }

private:
  std::vector<Point> points_;
  std::unique_ptr<Search::Tree> tree_;
};

/// Remeshes `m` isotropically (CGAL) to about `n` vertices.
inline Mesh remeshed_to(const Mesh& input, int n)
{
  Mesh m = input;
  const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(m));
  // A closed mesh has about 2n triangles of area sqrt(3)/4 e^2 each.
  const double edge = std::sqrt(2.0 * area / (std::sqrt(3.0) * n));
  CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(m), edge, m,
                                                     CGAL::parameters::number_of_iterations(3));
  m.collect_garbage();
  return m;
}

/// The benchmark mesh with about n vertices: a TOSCA_r shape (david0 by default, or the file
/// named by SMC_BENCH_MESH) remeshed to n vertices when the shared data is present, else the
/// generated torus. `description` says which was used.
inline Mesh benchmark_mesh(int n, std::string* description = nullptr)
{
  std::string file = std::getenv("SMC_BENCH_MESH") ? std::getenv("SMC_BENCH_MESH")
                                                   : data_directory() + "/TOSCA_r/off/david0.off";
  Mesh base;
  if(read_mesh(file, base))
  {
    Mesh m = (std::abs(static_cast<int>(num_vertices(base)) - n) < n / 20) ? base : remeshed_to(base, n);
    if(description) *description = file + (num_vertices(m) == num_vertices(base) ? "" : " remeshed");
    return m;
  }
  if(description) *description = "generated bumpy torus";
  return generated_mesh(n);
}

/// Rows of named values, printed as CSV (for scripts) and as an aligned table (for people).
class Report
{
public:
  explicit Report(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  void add(const std::vector<std::string>& row) { rows_.push_back(row); }
  static std::string num(double x, int precision = 3)
  {
    std::ostringstream s;
    s << std::fixed << std::setprecision(precision) << x;
    return s.str();
  }
  void print_csv(std::ostream& out) const
  {
    auto line = [&](const std::vector<std::string>& r) {
      for(std::size_t i = 0; i < r.size(); ++i) out << (i ? "," : "") << r[i];
      out << "\n";
    };
    line(columns_);
    for(const auto& r : rows_) line(r);
  }
  void print_table(std::ostream& out) const
  {
    std::vector<std::size_t> w(columns_.size());
    for(std::size_t i = 0; i < columns_.size(); ++i) w[i] = columns_[i].size();
    for(const auto& r : rows_)
      for(std::size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], r[i].size());
    auto line = [&](const std::vector<std::string>& r) {
      for(std::size_t i = 0; i < r.size(); ++i) out << std::setw(static_cast<int>(w[i]) + 2) << r[i];
      out << "\n";
    };
    line(columns_);
    for(const auto& r : rows_) line(r);
  }
  void print(std::ostream& out = std::cout) const
  {
    out << "--- CSV\n";
    print_csv(out);
    out << "--- table\n";
    print_table(out);
  }

private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string> > rows_;
};

} // namespace smc_bench

#endif // SMC_BENCH_UTIL_H
