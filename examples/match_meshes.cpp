// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The whole pipeline on two mesh files in one call: match_shapes() computes the maps in both
// directions from the two meshes alone (the README's library example).
//   match_meshes A.off B.off [PREFIX]
// writes PREFIX_12.map and PREFIX_21.map (1-based vertex indices, one per line, like
// `comap match`).

// [snippet:match]
#include <CGAL/Surface_mesh_correspondence.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace smc = CGAL::Surface_mesh_correspondence;
typedef CGAL::Surface_mesh<CGAL::Epick::Point_3> Mesh;
typedef Mesh::Property_map<Mesh::Vertex_index, Mesh::Vertex_index> Vertex_to_vertex;

// map_12[v]: the vertex of m2 matched to vertex v of m1; map_21 the other way round.
smc::Matching_result match(Mesh& m1, Mesh& m2, Vertex_to_vertex& map_12, Vertex_to_vertex& map_21)
{
  map_12 = m1.add_property_map<Mesh::Vertex_index, Mesh::Vertex_index>("v:match").first;
  map_21 = m2.add_property_map<Mesh::Vertex_index, Mesh::Vertex_index>("v:match").first;
  return smc::match_shapes<CGAL::Parallel_if_available_tag>(m1, m2, map_12, map_21);
}
// [/snippet:match]

#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>

#include <fstream>
#include <iostream>
#include <string>

namespace {

bool write_map(const std::string& file, const Mesh& source, const Vertex_to_vertex& map)
{
  std::ofstream out(file);
  for(Mesh::Vertex_index v : source.vertices()) out << map[v].idx() + 1 << "\n";
  return bool(out);
}

} // namespace

int main(int argc, char** argv)
{
  if(argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " A.off B.off [PREFIX]\n";
    return 1;
  }
  const std::string prefix = argc > 3 ? argv[3] : "match";
  Mesh m1, m2;
  if(!CGAL::IO::read_polygon_mesh(argv[1], m1) || !CGAL::IO::read_polygon_mesh(argv[2], m2))
  {
    std::cerr << "cannot read " << argv[1] << " or " << argv[2] << "\n";
    return 1;
  }
  try
  {
    Vertex_to_vertex map_12, map_21;
    const smc::Matching_result r = match(m1, m2, map_12, map_21);
    for(const std::string& decision : r.decisions) std::cout << decision << "\n";
    std::cout << "inconsistent vertices: " << r.inconsistent_vertices_before << " -> "
              << r.inconsistent_vertices_after << ", " << r.total_seconds << " s\n";
    if(!write_map(prefix + "_12.map", m1, map_12) || !write_map(prefix + "_21.map", m2, map_21))
    {
      std::cerr << "cannot write " << prefix << "_12.map or " << prefix << "_21.map\n";
      return 1;
    }
    std::cout << "wrote " << prefix << "_12.map and " << prefix << "_21.map\n";
  }
  catch(const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
