// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Resolution sweep reproducing Table 1 of Azencot, Dubrovina and Guibas (2019): the time of the
// preprocessing (spectra, HKS/WKS/SHOT descriptor stacks, geodesic distance oracles of both
// shapes), of the data preparation (candidate sets, unary and pairwise terms) and of the TRW-S
// solves of a coupled refinement of three outer iterations (6-, 4- and 3-ring neighbourhoods,
// six TRW-S calls), for one TOSCA_r pair at increasing vertex counts.
//
//   bench_resolution [--pair A B] [--sizes N1,N2,...] [--rings 6,4,3] [--sequential]
//
// The pair (default wolf0 wolf1: 4344 vertices, the resolution of the paper's first row) is
// remeshed with CGAL's isotropic remeshing to about each size (0: the original mesh). Initial
// maps come from the dataset's maps/WKSini_direct by nearest-vertex transfer (remeshed vertex ->
// nearest original vertex -> dataset map -> nearest remeshed vertex), the ground truth likewise,
// so the errors before and after refinement are printed as a sanity check.
// Needs ../shared/data/TOSCA_r (or SMC_DATA). Parallel (TBB) unless --sequential.

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include "bench_util.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = smc::parameters;
using smc_bench::Mesh;
using smc_bench::Report;
using smc_bench::Timer;

namespace {

struct Paper_row
{
  int vertices;
  double preprocessing_seconds, data_minutes, trws_minutes;
};
// Table 1 of the paper (pre-processing in seconds, the others in minutes; MATLAB + TRW-S on a
// 6-core 3.5 GHz Xeon E5).
const Paper_row paper[] = {{4344, 3.82, 0.45, 7.54},
                           {6890, 7.36, 1.3, 8.52},
                           {12500, 20.22, 3.68, 15.80},
                           {19248, 18.27, 8.55, 26.45},
                           {27894, 23.50, 16.20, 38.39}};

std::vector<int> parse_list(const char* s)
{
  std::vector<int> out;
  std::string field;
  for(const char* p = s;; ++p)
  {
    if(*p == ',' || *p == '\0')
    {
      out.push_back(std::atoi(field.c_str()));
      field.clear();
      if(*p == '\0') break;
    }
    else
      field += *p;
  }
  return out;
}

/// For every vertex of `from`, the vertex nearest to it (Euclidean) in the search structure.
smc::Vertex_index_map_vector nearest_vertices(const Mesh& from, const smc_bench::Nearest_vertex_search& to)
{
  smc::Vertex_index_map_vector out(num_vertices(from));
  for(Mesh::Vertex_index v : from.vertices()) out[v.idx()] = to.nearest(from.point(v));
  return out;
}

/// `input` remeshed isotropically to about `n` vertices (within 3%): the target edge length is
/// corrected from the vertex count of each attempt.
Mesh remeshed_to_count(const Mesh& input, int n)
{
  double scale = 1.0;
  Mesh best;
  for(int attempt = 0; attempt < 4; ++attempt)
  {
    // smc_bench::remeshed_to() picks the edge length for n vertices; scale it by asking for n * scale.
    Mesh m = smc_bench::remeshed_to(input, static_cast<int>(n * scale));
    const double ratio = static_cast<double>(num_vertices(m)) / n;
    if(attempt == 0 || std::abs(ratio - 1) < std::abs(static_cast<double>(num_vertices(best)) / n - 1)) best = m;
    if(std::abs(ratio - 1) < 0.03) break;
    scale /= ratio;
  }
  return best;
}

template <typename Tag>
int run(const std::string& a_name, const std::string& b_name, const std::vector<int>& sizes,
        const std::vector<int>& rings)
{
  const std::string dir = smc_bench::data_directory() + "/TOSCA_r";
  Mesh a0, b0;
  if(!smc_bench::read_mesh(dir + "/off/" + a_name + ".off", a0) || !smc_bench::read_mesh(dir + "/off/" + b_name + ".off", b0))
  {
    std::cerr << "bench_resolution: needs " << dir << "/off/" << a_name << ".off and " << b_name
              << ".off (set SMC_DATA to the shared data directory)\n";
    return 1;
  }
  const auto map_ab = smc::read_vertex_indices(dir + "/maps/WKSini_direct/" + a_name + "_" + b_name + ".map", 1);
  const auto map_ba = smc::read_vertex_indices(dir + "/maps/WKSini_direct/" + b_name + "_" + a_name + ".map", 1);
  const auto vts_a = smc::read_vertex_indices(dir + "/corres/" + a_name + ".vts", 1);
  const auto vts_b = smc::read_vertex_indices(dir + "/corres/" + b_name + ".vts", 1);
  // Nearest-vertex search in the original shapes, for the transfers.
  const smc_bench::Nearest_vertex_search A0(a0), B0(b0);

  Report report({"vertices_a", "vertices_b", "preprocessing_s", "data_preparation_min", "trws_min",
                 "refinement_min", "paper_vertices", "paper_preprocessing_s", "paper_data_preparation_min",
                 "paper_trws_min", "error_before", "error_after", "outer_iterations"});
  for(std::size_t row = 0; row < sizes.size(); ++row)
  {
    const int n = sizes[row];
    Timer remesh_timer;
    const Mesh a = n > 0 ? remeshed_to_count(a0, n) : a0;
    const Mesh b = n > 0 ? remeshed_to_count(b0, n) : b0;
    std::cerr << "size " << (n > 0 ? std::to_string(n) : std::string("original")) << ": " << num_vertices(a) << " and "
              << num_vertices(b) << " vertices (remeshed in " << Report::num(remesh_timer.seconds(), 1) << " s)\n";
    Timer timer;
    const smc::Correspondence_shape<Mesh, Tag> A(a), B(b);
    const double preprocessing = timer.seconds();
    const smc_bench::Nearest_vertex_search near_a(a), near_b(b);
    // Initial maps and ground truth by nearest-vertex transfer through the original meshes.
    const auto a_to_a0 = nearest_vertices(a, A0), b_to_b0 = nearest_vertices(b, B0);
    smc::Vertex_index_map_vector m12(num_vertices(a)), m21(num_vertices(b)), gt_a(vts_a.size()), gt_b(vts_b.size());
    for(std::size_t i = 0; i < m12.size(); ++i)
    {
      m12[i] = near_b.nearest(b0.point(Mesh::Vertex_index(static_cast<Mesh::size_type>(map_ab[a_to_a0[i]]))));
    }
    for(std::size_t i = 0; i < m21.size(); ++i)
    {
      m21[i] = near_a.nearest(a0.point(Mesh::Vertex_index(static_cast<Mesh::size_type>(map_ba[b_to_b0[i]]))));
    }
    for(std::size_t k = 0; k < vts_a.size(); ++k)
    {
      gt_a[k] = near_a.nearest(a0.point(Mesh::Vertex_index(static_cast<Mesh::size_type>(vts_a[k]))));
      gt_b[k] = near_b.nearest(b0.point(Mesh::Vertex_index(static_cast<Mesh::size_type>(vts_b[k]))));
    }
    const smc::Map_evaluator<Tag> on_b(b);
    const double before = on_b.geodesic_errors(m12, gt_a, gt_b).mean;
    const smc::Coupled_refinement_result r = smc::refine_coupled_maps<Tag>(
        A, B, m12, m21, params::ring_schedule(rings, params::stop_when_consistency_worsens(false)));
    const double after = on_b.geodesic_errors(m12, gt_a, gt_b).mean;
    const Paper_row& p = paper[std::min<std::size_t>(row, 4)];
    report.add({std::to_string(num_vertices(a)), std::to_string(num_vertices(b)), Report::num(preprocessing, 2),
                Report::num(r.data_preparation_seconds / 60, 3), Report::num(r.trws_seconds / 60, 3),
                Report::num(r.total_seconds / 60, 3), std::to_string(p.vertices), Report::num(p.preprocessing_seconds, 2),
                Report::num(p.data_minutes, 2), Report::num(p.trws_minutes, 2), Report::num(before, 4),
                Report::num(after, 4), std::to_string(r.outer_iterations)});
    std::cerr << "  preprocessing " << Report::num(preprocessing, 2) << " s, data preparation "
              << Report::num(r.data_preparation_seconds, 2) << " s, TRW-S " << Report::num(r.trws_seconds, 2)
              << " s; error " << Report::num(before, 4) << " -> " << Report::num(after, 4) << "\n";
  }
  std::cout << "Table 1 sweep: " << a_name << " - " << b_name << ", rings";
  for(int r : rings) std::cout << " " << r;
  std::cout << ", " << (std::is_same<Tag, CGAL::Sequential_tag>::value ? "sequential" : "parallel (TBB)")
            << "; preprocessing of both shapes in seconds, the rest in minutes; paper rows in order\n";
  report.print();
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  std::string a = "wolf0", b = "wolf1";
  std::vector<int> sizes = {0, 6890, 12500, 19248, 27894}, rings = {6, 4, 3};
  bool sequential = false;
  for(int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if(arg == "--pair" && i + 2 < argc)
    {
      a = argv[++i];
      b = argv[++i];
    }
    else if(arg == "--sizes" && i + 1 < argc)
      sizes = parse_list(argv[++i]);
    else if(arg == "--rings" && i + 1 < argc)
      rings = parse_list(argv[++i]);
    else if(arg == "--sequential")
      sequential = true;
    else
    {
      std::cerr << "usage: bench_resolution [--pair A B] [--sizes N1,N2,...] [--rings 6,4,3] [--sequential]\n";
      return 2;
    }
  }
#ifdef CGAL_LINKED_WITH_TBB
  if(!sequential) return run<CGAL::Parallel_tag>(a, b, sizes, rings);
#endif
  return run<CGAL::Sequential_tag>(a, b, sizes, rings);
}
