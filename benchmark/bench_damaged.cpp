// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Matching damaged meshes: a FAUST_r pair, and the same pair with the target damaged as
// remeshers and scanners do (test/damaged_meshes.h):
//   (a) a fin triangle on an existing edge (an edge in 3 faces),
//   (b) two touching sheets merged into an edge in 4 faces,
//   (c) a bow-tie vertex (two separate fans of faces),
//   (d) 1% of the faces of zero area (a vertex moved onto the line of the opposite edge).
// Every case is matched from scratch with the library defaults (match_shapes() on triangle soups,
// no initial maps). The maps to and from the damaged target are carried over to the clean target
// (damaged_meshes.h keeps the correspondence of the vertices), and the mean geodesic errors of
// both directions are measured on the clean meshes against the FAUST_r ground truth, so that every
// case is compared with the clean pair on the same samples.
//
// Usage: bench_damaged [--pair SOURCE TARGET] [--write DIR]
//   --pair   FAUST_r shape names (default tr_reg_002 tr_reg_007)
//   --write  also write the damaged targets as DIR/<case>.off
// The data directory is ../shared/data (or $SMC_DATA).

#include "bench_util.h"
#include "damaged_meshes.h"

#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;

namespace {

#ifdef CGAL_LINKED_WITH_TBB
typedef CGAL::Parallel_tag Tag;
#else
typedef CGAL::Sequential_tag Tag;
#endif

} // namespace

int main(int argc, char** argv)
{
  std::string source = "tr_reg_002", target = "tr_reg_007", write_dir;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--pair" && i + 2 < argc)
    {
      source = argv[++i];
      target = argv[++i];
    }
    else if(a == "--write" && i + 1 < argc)
      write_dir = argv[++i];
    else
    {
      std::cerr << "usage: bench_damaged [--pair SOURCE TARGET] [--write DIR]\n";
      return 2;
    }
  }
  const std::string dir = smc_bench::data_directory() + "/FAUST_r/";
  try
  {
    const smc::Triangle_soup soup_1 = smc::read_triangle_soup(dir + "off/" + source + ".off");
    const smc::Triangle_soup soup_2 = smc::read_triangle_soup(dir + "off/" + target + ".off");
    const smc::Vertex_index_map_vector gt_1 = smc::read_vertex_indices(dir + "corres/" + source + ".vts", 1);
    const smc::Vertex_index_map_vector gt_2 = smc::read_vertex_indices(dir + "corres/" + target + ".vts", 1);
    const smc::Map_evaluator<Tag> evaluator_1(soup_1), evaluator_2(soup_2);

    const smc_damage::Soup clean = smc_damage::soup_of(soup_2);
    struct Case
    {
      std::string name;
      smc_damage::Damaged damaged;
    };
    std::vector<Case> cases;
    cases.push_back({"clean", smc_damage::undamaged(clean)});
    cases.push_back({"fin", smc_damage::add_fin(clean, clean.triangles.size() / 2)});
    cases.push_back({"four_face_edge", smc_damage::merge_touching_edges(clean, 8)});
    cases.push_back({"bow_tie", smc_damage::pinch_vertices(clean, 8)});
    cases.push_back({"zero_area_1pct", smc_damage::collapse_faces(clean, 0.01)});

    std::cout << "FAUST_r " << source << " -> " << target << " (damage on the target; errors on the clean meshes)\n";
    std::cout << "case,vertices,faces,non_manifold_edges,non_manifold_vertices,degenerate_faces,"
                 "error_12,error_21,mean_error,difference,seconds\n";
    double clean_error = 0;
    std::vector<std::string> rows;
    for(const Case& c : cases)
    {
      if(!write_dir.empty()) smc_damage::write_off(write_dir + "/" + c.name + ".off", c.damaged.soup);
      const smc::Triangle_soup damaged(c.damaged.soup.points, c.damaged.soup.triangles,
                                       smc::Triangle_soup_origin{c.name});
      smc::Vertex_index_map_vector m12, m21;
      smc_bench::Timer timer;
      const smc::Matching_result result = smc::match_shapes<Tag>(soup_1, damaged, m12, m21);
      const double seconds = timer.seconds();
      // Back to the clean target: 1 -> 2 through to_clean, 2 -> 1 from each clean vertex's image.
      smc::Vertex_index_map_vector c12(m12.size()), c21(clean.points.size());
      for(std::size_t x = 0; x < m12.size(); ++x) c12[x] = std::size_t(c.damaged.to_clean[m12[x]]);
      for(std::size_t y = 0; y < c21.size(); ++y) c21[y] = m21[std::size_t(c.damaged.from_clean[y])];
      const double e12 = evaluator_2.geodesic_errors(c12, gt_1, gt_2).mean;
      const double e21 = evaluator_1.geodesic_errors(c21, gt_2, gt_1).mean;
      const double mean = 0.5 * (e12 + e21);
      if(c.name == "clean") clean_error = mean;
      std::printf("%s,%zu,%zu,%d,%d,%d,%.4f,%.4f,%.4f,%+.4f,%.2f\n", c.name.c_str(), c.damaged.soup.points.size(),
                  c.damaged.soup.triangles.size(), int(result.irregularities_2.non_manifold_edges.size()),
                  int(result.irregularities_2.non_manifold_vertices.size()), int(result.irregularities_2.degenerate_faces.size()), e12, e21, mean,
                  mean - clean_error, seconds);
      std::cout.flush();
      std::cerr << c.name << ": " << c.damaged.what << "\n";
    }
  }
  catch(const std::exception& e)
  {
    std::cerr << "bench_damaged: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
