// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Vertex neighbourhoods and farthest point sampling on triangle meshes: k-rings, geodesic balls,
// and farthest point sampling inside a vertex set. These FaceGraph functions build the flat copy
// of the mesh at every call; code that calls them for every vertex uses the index-based workspaces
// of internal/neighborhood_search.h and internal/dijkstra.h instead (no allocation per call).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_NEIGHBORHOODS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_NEIGHBORHOODS_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/geodesic_distances.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>
#include <CGAL/Surface_mesh_correspondence/internal/neighborhood_search.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/graph/graph_traits.hpp>

#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Outputs the k-ring neighbourhood of a vertex or of a set of vertices: every vertex joined to
/// one of them by a path of at most `k` edges.
///
/// The output order is breadth-first: the distinct seeds in the given order, then ring 1, ring 2,
/// ... (deterministic). On a regular triangulation (valence 6) the k-ring of an interior vertex
/// has \f$ 1 + 3k(k+1) \f$ vertices.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam Seeds `vertex_descriptor` or a range of `vertex_descriptor`
/// \tparam OutputIterator an output iterator accepting `vertex_descriptor`
/// \tparam NamedParameters `vertex_point_map`, `vertex_index_map` (as in fast_marching_geodesic_distances())
/// \pre `k >= 0`
/// \throws Invalid_parameter_error for `k < 0` or a seed that is not a vertex; Invalid_mesh_error
template <typename TriangleMesh, typename Seeds, typename OutputIterator,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
OutputIterator k_ring_neighborhood(const TriangleMesh& tm, const Seeds& seeds, int k, OutputIterator out,
                                   const NamedParameters& np = CGAL::parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  const std::vector<int> s =
      internal::vertex_indices(tm, seeds, CGAL::get_initialized_vertex_index_map(tm, np));
  internal::K_ring_workspace ws(m);
  std::vector<int> ring;
  ws.k_ring(s.data(), s.size(), k, ring);
  for(int v : ring) *out++ = vertices[v];
  return out;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Outputs the geodesic ball of radius `radius` around a vertex or a set of vertices: the vertices
/// whose fast-marching distance to the seeds is at most `radius`, by increasing distance.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam Seeds `vertex_descriptor` or a non-empty range of `vertex_descriptor`
/// \tparam OutputIterator an output iterator accepting `vertex_descriptor`
/// \tparam NamedParameters `vertex_point_map`, `vertex_index_map`
/// \pre `radius >= 0`
/// \throws Invalid_parameter_error for a negative radius, no seed or a seed that is not a vertex
template <typename TriangleMesh, typename Seeds, typename OutputIterator,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
OutputIterator geodesic_ball(const TriangleMesh& tm, const Seeds& seeds, double radius, OutputIterator out,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  const std::vector<int> s =
      internal::vertex_indices(tm, seeds, CGAL::get_initialized_vertex_index_map(tm, np));
  internal::Fast_marching_geometry g(m);
  internal::Fast_marching_workspace ws(g);
  std::vector<int> ball;
  internal::geodesic_ball(ws, s.data(), s.size(), radius, ball);
  for(int v : ball) *out++ = vertices[v];
  return out;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Farthest point sampling of `number_of_samples` vertices inside the vertex set `vertex_set`.
///
/// The distance is the shortest path along the mesh edges whose two endpoints are in the set
/// (Dijkstra restricted to the set): paths may not leave the set, and it costs microseconds on
/// the sets of a few hundred vertices used for candidate selection. With the seeds
/// \f$ p_1, \dots, p_q \f$ first (distinct, in the given order), each next sample is
/// \f[ p_{j+1} = \arg\max_{v \in S \setminus \{p_1..p_j\}} \; \min_{i \le j} d_S(v, p_i), \f]
/// ties broken by the smallest vertex index; vertices unreachable from all samples count as
/// infinitely far. Without seeds the first sample is the vertex of smallest index. When the set
/// has at most `number_of_samples` vertices, all of it is output (in the same greedy order).
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam VertexRange a range of `vertex_descriptor` (duplicates are ignored)
/// \tparam OutputIterator an output iterator accepting `vertex_descriptor`
/// \tparam NamedParameters a sequence of named parameters:
///   - `seed_vertices`: a range of `vertex_descriptor` in `vertex_set`, the first samples
///     (default: none);
///   - `vertex_point_map`, `vertex_index_map` (as in fast_marching_geodesic_distances()).
/// \pre `number_of_samples > 0`, every seed is in `vertex_set`
/// \throws Invalid_parameter_error when a precondition fails or a vertex is not a vertex of `tm`
template <typename TriangleMesh, typename VertexRange, typename OutputIterator,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
OutputIterator farthest_point_sampling(const TriangleMesh& tm, const VertexRange& vertex_set,
                                       int number_of_samples, OutputIterator out,
                                       const NamedParameters& np = CGAL::parameters::default_values())
{
  using parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const std::vector<int> set = internal::vertex_indices(tm, vertex_set, vim);
  std::vector<int> seeds;
  const auto& seed_range = get_parameter(np, internal_np::seed_vertices);
  if constexpr(!std::is_same<typename std::decay<decltype(seed_range)>::type,
                             CGAL::internal_np::Param_not_found>::value)
    seeds = internal::vertex_indices(tm, seed_range, vim);
  internal::Edge_length_graph graph(m);
  internal::Farthest_point_sampler sampler(graph);
  std::vector<int> samples;
  sampler.sample(set.data(), set.size(), seeds.data(), seeds.size(), number_of_samples, samples);
  for(int v : samples) *out++ = vertices[v];
  return out;
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_NEIGHBORHOODS_H
