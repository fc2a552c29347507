// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One mesh matched against several others, every shape prepared once:
//   match_one_against_many REFERENCE.off OTHER.off [OTHER.off ...]
// For each OTHER: automatic initial maps, then the coupled refinement, with the prepared shapes.
// The reference's shape is prepared once (spectrum, descriptors, distance oracle) and keeps what
// the first initialisation computes for it (its 200-eigenpair spectrum and descriptors), so the
// later pairs compute them for OTHER only. Prints the time of each step and writes
// REFERENCE-to-OTHER maps as match_<k>_12.map and match_<k>_21.map (0-based).

#include <CGAL/Surface_mesh_correspondence.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <iostream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
typedef CGAL::Surface_mesh<CGAL::Epick::Point_3> Mesh;
typedef CGAL::Parallel_if_available_tag Concurrency;
typedef smc::Correspondence_shape<Mesh, Concurrency> Shape;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool read(const char* file, Mesh& m)
{
  if(CGAL::IO::read_polygon_mesh(file, m)) return true;
  std::cerr << "cannot read " << file << "\n";
  return false;
}

} // namespace

int main(int argc, char** argv)
{
  if(argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " REFERENCE.off OTHER.off [OTHER.off ...]\n";
    return 1;
  }
  Mesh reference_mesh;
  if(!read(argv[1], reference_mesh)) return 1;
  try
  {
    auto start = std::chrono::steady_clock::now();
    const Shape reference(reference_mesh, smc::parameters::default_values(), argv[1]);
    std::cout << argv[1] << ": prepared in " << seconds_since(start) << " s\n";
    for(int k = 2; k < argc; ++k)
    {
      Mesh mesh;
      if(!read(argv[k], mesh)) return 1;
      start = std::chrono::steady_clock::now();
      const Shape other(mesh, smc::parameters::default_values(), argv[k]);
      const double prepared = seconds_since(start);
      smc::Vertex_index_map_vector x12, x21;
      const smc::Automatic_initialization_result init =
          smc::automatic_initial_maps<Concurrency>(reference, other, x12, x21);
      const smc::Coupled_refinement_result refined = smc::refine_coupled_maps(
          reference, other, x12, x21, smc::parameters::refinement_preset(smc::Refinement_preset::automatic_maps));
      std::cout << argv[k] << ": prepared in " << prepared << " s, initial maps in " << init.total_seconds
                << " s (spectra and descriptors " << init.spectra_seconds << " s, " << init.reused_descriptors
                << " of 2 kept from an earlier pair), refined in " << refined.total_seconds << " s\n";
      const std::string prefix = "match_" + std::to_string(k - 1);
      smc::write_vertex_indices(prefix + "_12.map", x12, 0);
      smc::write_vertex_indices(prefix + "_21.map", x21, 0);
    }
  }
  catch(const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
