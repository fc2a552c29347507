// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Index-based wrappers of CGAL's geodesic distance packages on the flat mesh copy:
//  - Exact_geodesic_solver: CGAL::Surface_mesh_shortest_path (exact polyhedral geodesics,
//    Xin-Wang / Chen-Han style windows), single source to all vertices;
//  - Heat_method_solver: CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3 in
//    Intrinsic_Delaunay mode, factorised once, one source at a time (the multi-source mode of
//    CGAL 5.5 normalises wrongly, so it is never used).
// Both run on an internal CGAL::Surface_mesh copy of the Indexed_mesh (vertex i of the copy is
// vertex i of the Indexed_mesh), so they work for any input FaceGraph and any index map.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CGAL_GEODESICS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CGAL_GEODESICS_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Geodesic_kernel;
typedef CGAL::Surface_mesh<Geodesic_kernel::Point_3> Geodesic_surface_mesh;

/// Builds a Surface_mesh from the vertices `vertex_list` (global indices) of `m` and the triangles
/// whose vertices are all in the list; `local` maps global to local indices (-1 elsewhere).
inline void make_surface_mesh(const Indexed_mesh& m, const std::vector<int>& vertex_list,
                              const std::vector<int>& local, Geodesic_surface_mesh& out)
{
  out.clear();
  out.reserve(static_cast<Geodesic_surface_mesh::size_type>(vertex_list.size()), 0, 0);
  std::vector<Geodesic_surface_mesh::Vertex_index> vs;
  vs.reserve(vertex_list.size());
  for(int v : vertex_list)
    vs.push_back(out.add_vertex(Geodesic_kernel::Point_3(m.points(v, 0), m.points(v, 1), m.points(v, 2))));
  for(int f = 0; f < m.number_of_triangles(); ++f)
  {
    const int a = local[m.triangles(f, 0)], b = local[m.triangles(f, 1)], c = local[m.triangles(f, 2)];
    if(a < 0 || b < 0 || c < 0) continue;
    if(out.add_face(vs[a], vs[b], vs[c]) == Geodesic_surface_mesh::null_face())
      throw Invalid_mesh_error("geodesic distances: the mesh could not be copied into a Surface_mesh "
                               "(inconsistent orientation?)");
  }
}

/// Exact polyhedral geodesic distances (CGAL Surface_mesh_shortest_path) from one vertex.
class Exact_geodesic_solver
{
  typedef CGAL::Surface_mesh_shortest_path_traits<Geodesic_kernel, Geodesic_surface_mesh> Traits;
  typedef CGAL::Surface_mesh_shortest_path<Traits> Shortest_path;

public:
  explicit Exact_geodesic_solver(const Indexed_mesh& m)
      : n_(m.number_of_vertices()), mesh_(new Geodesic_surface_mesh())
  {
    std::vector<int> all(n_), local(n_);
    for(int v = 0; v < n_; ++v) all[v] = local[v] = v;
    make_surface_mesh(m, all, local, *mesh_);
    shortest_path_.reset(new Shortest_path(*mesh_));
  }
  Exact_geodesic_solver(const Exact_geodesic_solver&) = delete;
  Exact_geodesic_solver& operator=(const Exact_geodesic_solver&) = delete;

  int number_of_vertices() const { return n_; }

  /// Distances from `source` to every vertex (+infinity in other components).
  void distances(int source, std::vector<double>& out)
  {
    check_vertex_index(source, n_, "exact geodesic distances (source)");
    shortest_path_->remove_all_source_points();
    shortest_path_->add_source_point(Geodesic_surface_mesh::Vertex_index(source));
    shortest_path_->build_sequence_tree();
    out.resize(n_);
    for(int v = 0; v < n_; ++v)
    {
      const double d = CGAL::to_double(
          shortest_path_->shortest_distance_to_source_points(Geodesic_surface_mesh::Vertex_index(v)).first);
      out[v] = d < 0 ? std::numeric_limits<double>::infinity() : d;
    }
    out[source] = 0;
  }

private:
  int n_;
  std::unique_ptr<Geodesic_surface_mesh> mesh_;  // on the heap: shortest_path_ refers to it
  std::unique_ptr<Shortest_path> shortest_path_;
};

/// Heat-method geodesic distances (Crane, Weischedel, Wardetzky 2013) with CGAL Heat_method_3 on
/// the intrinsic Delaunay triangulation; one solver per connected component, factorised once.
/// Vertices in other components than the source get +infinity.
class Heat_method_solver
{
  typedef CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<
      Geodesic_surface_mesh, CGAL::Heat_method_3::Intrinsic_Delaunay>
      Heat;
  typedef Geodesic_surface_mesh::Property_map<Geodesic_surface_mesh::Vertex_index, double> Distance_map;

public:
  explicit Heat_method_solver(const Indexed_mesh& m)
      : n_(m.number_of_vertices()), component_(m.component), local_(n_)
  {
    const int nc = m.number_of_components;
    std::vector<std::vector<int> > lists(nc);
    for(int v = 0; v < n_; ++v)
    {
      local_[v] = static_cast<int>(lists[component_[v]].size());
      lists[component_[v]].push_back(v);
    }
    parts_.resize(nc);
    for(int c = 0; c < nc; ++c)
    {
      Part& p = parts_[c];
      p.vertices = lists[c];
      p.mesh.reset(new Geodesic_surface_mesh());
      std::vector<int> local(n_, -1);
      for(std::size_t i = 0; i < p.vertices.size(); ++i) local[p.vertices[i]] = static_cast<int>(i);
      make_surface_mesh(m, p.vertices, local, *p.mesh);
      p.distance = p.mesh->add_property_map<Geodesic_surface_mesh::Vertex_index, double>(
                              "v:smc_heat_distance", 0.0).first;
      p.heat.reset(new Heat(*p.mesh));
    }
  }

  Heat_method_solver(const Heat_method_solver&) = delete;
  Heat_method_solver& operator=(const Heat_method_solver&) = delete;

  int number_of_vertices() const { return n_; }

  /// Distances from `source` to every vertex.
  void distances(int source, std::vector<double>& out)
  {
    check_vertex_index(source, n_, "heat method geodesic distances (source)");
    Part& p = parts_[component_[source]];
    p.heat->clear_sources();
    p.heat->add_source(Geodesic_surface_mesh::Vertex_index(local_[source]));
    p.heat->estimate_geodesic_distances(p.distance);
    out.assign(n_, std::numeric_limits<double>::infinity());
    for(std::size_t i = 0; i < p.vertices.size(); ++i)
      out[p.vertices[i]] = p.distance[Geodesic_surface_mesh::Vertex_index(static_cast<Geodesic_surface_mesh::size_type>(i))];
    out[source] = 0;
  }

private:
  struct Part
  {
    std::vector<int> vertices;  // global indices, in local order
    std::unique_ptr<Geodesic_surface_mesh> mesh;
    Distance_map distance;
    std::unique_ptr<Heat> heat;
  };
  int n_;
  std::vector<int> component_, local_;
  std::vector<Part> parts_;
};

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CGAL_GEODESICS_H
