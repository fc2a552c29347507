// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One mesh matched against several others, every shape prepared once:
//   match_one_against_many REFERENCE.off OTHER.off [OTHER.off ...]
// Every shape is prepared once (Correspondence_shape: one eigensolve for the initialisation and
// the refinement, the initialisation's descriptors, the distance oracle), then match_shapes() runs
// the rest of the pipeline on the prepared shapes of each pair. Prints the time of each step and
// writes REFERENCE-to-OTHER maps as match_<k>_12.map and match_<k>_21.map (0-based).

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
      // [snippet:one_against_many]
      smc::Vertex_index_map_vector x12, x21;
      const smc::Matching_result r = smc::match_shapes<Concurrency>(reference, other, x12, x21);
      // [/snippet:one_against_many]
      std::cout << argv[k] << ": prepared in " << prepared << " s, matched in " << r.total_seconds
                << " s (initialisation " << r.seconds(smc::Matching_stage::initialization) << " s, refinement "
                << r.seconds(smc::Matching_stage::refinement) << " s)\n";
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
