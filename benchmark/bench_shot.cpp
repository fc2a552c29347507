// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// SHOT benchmark:
//  1. time and peak memory of compute_shot_descriptors at about 5k, 25k and 100k vertices,
//     sequential and with Parallel_tag, with the average number of neighbours per support;
//  2. the fixed-radius neighbour search: the package's uniform grid against CGAL's Kd_tree with
//     Fuzzy_sphere queries;
//  3. descriptor quality on the shared FAUST_r and TOSCA_r data (when present), per support
//     radius: for sample vertices of shape A, the vertex of shape B with the nearest descriptor,
//     and its Euclidean distance (on B, / sqrt(area(B))) to the ground-truth vertex; "local" picks
//     the nearest descriptor only among vertices within 0.1 sqrt(area(B)) of the ground truth,
//     as a refinement step sees it.
//
// Usage: bench_shot [--quick] [--pairs N] [--no-quality]
//   --quick: 5k vertices only; --pairs N: shape pairs per dataset for part 3 (default 20).

#include <CGAL/Surface_mesh_correspondence/shot.h>

#include "bench_util.h"

#include <CGAL/Kd_tree.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <cstdlib>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
using smc_bench::Report;

namespace {

// ------------------------------------------------------------------ 1. time and memory

void time_and_memory(const std::vector<int>& sizes)
{
  Report report({"vertices", "mode", "seconds_total", "seconds_descriptors", "cpu_seconds_descriptors",
                 "peak_MiB", "support_points", "avg_neighbors", "enlarged"});
  for(int n : sizes)
  {
    std::string description;
    const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(n, &description);
    const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(mesh);
    std::cout << "mesh: " << description << ", " << num_vertices(mesh) << " vertices" << std::endl;
    // mode 0: sequential, 1: Parallel_tag, 2: sequential with every vertex as a support point
    // (no Poisson-disk bound; only differs on meshes with more than 20000 vertices).
    for(int mode = 0; mode < 3; ++mode)
    {
#ifndef CGAL_LINKED_WITH_TBB
      if(mode == 1) continue;
#endif
      const bool parallel = mode == 1;
      smc::internal::Shot_options options;
      if(mode == 2)
      {
        if(im.number_of_vertices() <= static_cast<int>(options.maximum_support_points)) continue;
        options.maximum_support_points = 0;
      }
      // Best of 3 runs (the machine is shared); total = public function (mesh copy included).
      double best_total = 1e30, best_descriptors = 1e30, best_cpu = 1e30, peak = 0;
      smc::internal::Shot_statistics stats;
      for(int run = 0; run < 3; ++run)
      {
        Eigen::MatrixXd d;
        if(mode != 2)
        {
#ifdef __GLIBC__
          malloc_trim(0);  // give freed blocks back, so that reused memory is counted again
#endif
          smc_bench::reset_peak_memory();
          const double before = smc_bench::current_memory_mib();
          smc_bench::Timer timer;
#ifdef CGAL_LINKED_WITH_TBB
          if(parallel) d = smc::compute_shot_descriptors<CGAL::Parallel_tag>(mesh);
          else
#endif
            d = smc::compute_shot_descriptors<CGAL::Sequential_tag>(mesh);
          best_total = std::min(best_total, timer.seconds());
          peak = std::max(peak, smc_bench::peak_memory_mib() - before);
          d.resize(0, 0);
        }
        smc_bench::Timer timer;
        const std::clock_t cpu_start = std::clock();
#ifdef CGAL_LINKED_WITH_TBB
        if(parallel) d = smc::internal::shot_descriptors<CGAL::Parallel_tag>(im, options, &stats);
        else
#endif
          d = smc::internal::shot_descriptors<CGAL::Sequential_tag>(im, options, &stats);
        best_descriptors = std::min(best_descriptors, timer.seconds());
        best_cpu = std::min(best_cpu, static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        if(mode == 2) break;  // slow: one run
      }
      report.add({std::to_string(num_vertices(mesh)),
                  mode == 0 ? "Sequential" : mode == 1 ? "Parallel" : "Sequential_all_support",
                  mode == 2 ? "-" : Report::num(best_total, 4), Report::num(best_descriptors, 4),
                  Report::num(best_cpu, 4),
                  mode == 2 ? "-" : Report::num(peak, 1), std::to_string(stats.support_points),
                  Report::num(stats.average_neighbors, 1), std::to_string(stats.enlarged_supports)});
    }
  }
  std::cout << "\n# SHOT wall-clock time (best of 3; total = public function with the mesh copy), "
               "process CPU time of the descriptor part (all threads), and peak memory above the "
               "resident size before the call (default shot_radius "
            << smc::Matching_settings().shot_radius << ")\n";
  report.print();
}

// ------------------------------------------------------------------ 2. neighbour search

typedef smc_bench::Kernel::Point_3 Point_3;
typedef CGAL::Search_traits_3<smc_bench::Kernel> Base_traits;
typedef CGAL::Pointer_property_map<Point_3>::type Point_map;
typedef CGAL::Search_traits_adapter<std::size_t, Point_map, Base_traits> Traits;
typedef CGAL::Kd_tree<Traits> Tree;
typedef CGAL::Fuzzy_sphere<Traits> Sphere;

void neighbor_search(const std::vector<int>& sizes)
{
  Report report({"vertices", "radius_rel", "grid_build_s", "grid_query_s", "kdtree_build_s",
                 "kdtree_query_s", "avg_neighbors", "same_counts"});
  for(int n : sizes)
  {
    const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(n);
    const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(mesh);
    const int nv = im.number_of_vertices();
    for(double relative : {0.05, 0.08, 0.12})
    {
      const double radius = relative * std::sqrt(im.total_area);
      std::vector<int> grid_count(nv, 0), tree_count(nv, 0);
      smc_bench::Timer timer;
      const smc::internal::Uniform_point_grid grid(im.points, radius);
      const double grid_build = timer.seconds();
      timer.reset();
      for(int v = 0; v < nv; ++v)
      {
        const Eigen::Vector3d q = im.points.row(v).transpose();
        grid.for_each_in_ball(q.data(), radius, [&](int, double, std::size_t) { ++grid_count[v]; });
      }
      const double grid_query = timer.seconds();

      std::vector<Point_3> points(nv);
      for(int v = 0; v < nv; ++v) points[v] = Point_3(im.points(v, 0), im.points(v, 1), im.points(v, 2));
      timer.reset();
      std::vector<std::size_t> keys(nv);
      for(int v = 0; v < nv; ++v) keys[v] = static_cast<std::size_t>(v);
      Tree tree(keys.begin(), keys.end(), Tree::Splitter(), Traits(Point_map(points.data())));
      tree.build();
      const double tree_build = timer.seconds();
      timer.reset();
      std::vector<std::size_t> found;
      for(int v = 0; v < nv; ++v)
      {
        found.clear();
        tree.search(std::back_inserter(found), Sphere(points[v], radius, 0.0, tree.traits()));
        // Fuzzy_sphere includes the boundary (d <= r); count d < r as the grid does.
        int inside = 0;
        for(std::size_t j : found)
          if(CGAL::squared_distance(points[j], points[v]) < radius * radius) ++inside;
        tree_count[v] = inside;
      }
      const double tree_query = timer.seconds();
      double total = 0;
      for(int c : grid_count) total += c;
      report.add({std::to_string(nv), Report::num(relative, 2), Report::num(grid_build, 4),
                  Report::num(grid_query, 4), Report::num(tree_build, 4), Report::num(tree_query, 4),
                  Report::num(total / nv, 1), grid_count == tree_count ? "yes" : "NO"});
    }
  }
  std::cout << "\n# Fixed-radius neighbour search over all vertices (counts include the vertex itself)\n";
  report.print();
}

// ------------------------------------------------------------------ 3. quality on real data

std::vector<int> read_vts(const std::string& file)
{
  std::ifstream in(file);
  std::vector<int> v;
  int x;
  while(in >> x) v.push_back(x - 1);
  return v;
}

void quality(const std::string& dataset, int number_of_pairs)
{
  const std::string dir = smc_bench::data_directory() + "/" + dataset + "/";
  std::ifstream pairs_file(dir + "test_pairs.txt");
  if(!pairs_file)
  {
    std::cout << "\n# " << dataset << ": " << dir << "test_pairs.txt not found, quality skipped\n";
    return;
  }
  std::vector<std::pair<std::string, std::string> > pairs;
  std::string a, b;
  while(pairs_file >> a >> b) pairs.emplace_back(a, b);
  // Spread the chosen pairs over the list.
  std::vector<std::pair<std::string, std::string> > chosen;
  for(int k = 0; k < number_of_pairs && !pairs.empty(); ++k)
    chosen.push_back(pairs[(static_cast<std::size_t>(k) * pairs.size()) / number_of_pairs]);

  const std::vector<double> radii = {0.04, 0.05, 0.06, 0.08, 0.10, 0.12};
  std::vector<double> error(radii.size(), 0), within5(radii.size(), 0), within10(radii.size(), 0),
      local_error(radii.size(), 0), seconds(radii.size(), 0);
  std::size_t samples = 0, shapes = 0;
  for(const auto& pair : chosen)
  {
    smc_bench::Mesh mesh_a, mesh_b;
    if(!smc_bench::read_mesh(dir + "off/" + pair.first + ".off", mesh_a) ||
       !smc_bench::read_mesh(dir + "off/" + pair.second + ".off", mesh_b))
      continue;
    const std::vector<int> vts_a = read_vts(dir + "corres/" + pair.first + ".vts");
    const std::vector<int> vts_b = read_vts(dir + "corres/" + pair.second + ".vts");
    const smc::internal::Indexed_mesh ma = smc::internal::make_indexed_mesh(mesh_a);
    const smc::internal::Indexed_mesh mb = smc::internal::make_indexed_mesh(mesh_b);
    const double scale = std::sqrt(mb.total_area);
    shapes += 2;
    std::size_t pair_samples = 0;
    for(std::size_t r = 0; r < radii.size(); ++r)
    {
      smc::internal::Shot_options options;
      options.relative_radius = radii[r];
      smc_bench::Timer timer;
      const Eigen::MatrixXd da = smc::internal::shot_descriptors<CGAL::Sequential_tag>(ma, options);
      const Eigen::MatrixXd db = smc::internal::shot_descriptors<CGAL::Sequential_tag>(mb, options);
      seconds[r] += timer.seconds();
      const Eigen::VectorXd norms_b = db.rowwise().squaredNorm();
      pair_samples = 0;
      for(std::size_t k = 0; k < vts_a.size() && k < vts_b.size(); k += 5)
      {
        // |db_w - da_v|^2 up to the constant |da_v|^2.
        const Eigen::VectorXd distance = norms_b - 2 * (db * da.row(vts_a[k]).transpose());
        Eigen::Index best = 0;
        distance.minCoeff(&best);
        const Eigen::Vector3d truth = mb.point(vts_b[k]);
        const double e = (mb.point(static_cast<int>(best)) - truth).norm() / scale;
        error[r] += e;
        within5[r] += e < 0.05;
        within10[r] += e < 0.10;
        double best_local = 1e300;
        int local = vts_b[k];
        for(int w = 0; w < mb.number_of_vertices(); ++w)
          if((mb.point(w) - truth).norm() < 0.1 * scale && distance[w] < best_local)
          {
            best_local = distance[w];
            local = w;
          }
        local_error[r] += (mb.point(local) - truth).norm() / scale;
        ++pair_samples;
      }
    }
    samples += pair_samples;
  }
  if(samples == 0)
  {
    std::cout << "\n# " << dataset << ": no readable pair, quality skipped\n";
    return;
  }
  Report report({"shot_radius", "mean_error", "within_0.05", "within_0.10", "local_mean_error",
                 "seconds_per_shape"});
  for(std::size_t r = 0; r < radii.size(); ++r)
    report.add({Report::num(radii[r], 2), Report::num(error[r] / samples, 4),
                Report::num(within5[r] / samples, 3), Report::num(within10[r] / samples, 3),
                Report::num(local_error[r] / samples, 4), Report::num(seconds[r] / shapes, 4)});
  std::cout << "\n# " << dataset << ": nearest-descriptor matching, " << chosen.size() << " pairs, "
            << samples << " samples (Euclidean error on the target / sqrt(area))\n";
  report.print();
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false, with_quality = true;
  int pairs = 20;
  for(int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if(arg == "--quick") quick = true;
    else if(arg == "--no-quality") with_quality = false;
    else if(arg == "--pairs" && i + 1 < argc) pairs = std::atoi(argv[++i]);
    else
    {
      std::cerr << "usage: bench_shot [--quick] [--pairs N] [--no-quality]\n";
      return 1;
    }
  }
  const std::vector<int> sizes = quick ? std::vector<int>{5000} : std::vector<int>{5000, 25000, 100000};
  time_and_memory(sizes);
  neighbor_search(sizes);
  if(with_quality)
  {
    quality("FAUST_r", pairs);
    quality("TOSCA_r", pairs);
  }
  return 0;
}
