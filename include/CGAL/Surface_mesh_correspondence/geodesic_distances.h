// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geodesic distance fields on triangle meshes: fast marching (our own implementation of Kimmel and
// Sethian 1998), the heat method (CGAL Heat_method_3 on the intrinsic Delaunay triangulation) and
// exact polyhedral geodesics (CGAL Surface_mesh_shortest_path). Every function works on any CGAL
// FaceGraph triangle mesh and writes into a vertex property map owned by the caller; the stateful
// classes precompute once and answer many queries. The index-based machinery is in
// internal/fast_marching.h and internal/cgal_geodesics.h.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_GEODESIC_DISTANCES_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_GEODESIC_DISTANCES_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/cgal_geodesics.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/graph/graph_traits.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The method used to compute geodesic distance fields (named parameter `geodesic_method`).
enum class Geodesic_method
{
  fast_marching,  ///< our fast marching (circular wave front, obtuse angles unfolded); the default
  heat_method,    ///< CGAL Heat_method_3, intrinsic Delaunay mode, one source at a time
  exact           ///< CGAL Surface_mesh_shortest_path (exact polyhedral distances; slow)
};

namespace internal {

/// The vertex indices of `sources`, which is either one vertex descriptor or a range of them.
template <typename TriangleMesh, typename Sources, typename VertexIndexMap>
std::vector<int> vertex_indices(const TriangleMesh&, const Sources& sources, const VertexIndexMap& vim)
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<int> out;
  if constexpr(std::is_convertible<Sources, vertex_descriptor>::value)
    out.push_back(static_cast<int>(get(vim, vertex_descriptor(sources))));
  else
    for(const auto& v : sources) out.push_back(static_cast<int>(get(vim, v)));
  return out;
}

/// Throws Invalid_parameter_error unless `v` is a vertex of the mesh (index in range).
inline void check_source_index(int v, int n, const char* function)
{
  if(v < 0 || v >= n)
    throw Invalid_parameter_error(std::string(function) + ": the source vertex (index " +
                                  std::to_string(v) + ") is not a vertex of the mesh");
}

/// Writes the values `d` (indexed like the Indexed_mesh) into the vertex property map `dm`.
template <typename VertexDescriptor, typename VertexDistanceMap>
void write_vertex_values(const std::vector<VertexDescriptor>& vertices, const std::vector<double>& d,
                         VertexDistanceMap dm)
{
  typedef typename boost::property_traits<VertexDistanceMap>::value_type Value;
  for(std::size_t i = 0; i < vertices.size(); ++i) put(dm, vertices[i], static_cast<Value>(d[i]));
}

/// Distances from `source` to every vertex of `m` with the given method (+infinity across
/// components). Allocates; for many sources use the classes.
inline void geodesic_distances_from(const Indexed_mesh& m, int source, Geodesic_method method,
                                    std::vector<double>& out)
{
  check_source_index(source, m.number_of_vertices(), "geodesic distances");
  switch(method)
  {
  case Geodesic_method::heat_method:
  {
    Heat_method_solver heat(m);
    heat.distances(source, out);
    return;
  }
  case Geodesic_method::exact:
  {
    Exact_geodesic_solver exact(m);
    exact.distances(source, out);
    return;
  }
  default:
  {
    Fast_marching_geometry g(m);
    Fast_marching_workspace ws(g);
    ws.run(source);
    ws.copy_distances(out);
  }
  }
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Fast marching geodesic distances on a triangle mesh, precomputed once for many queries.
///
/// Solves the eikonal equation \f$ |\nabla T| = 1 \f$, \f$ T = 0 \f$ at the sources, with the fast
/// marching method of Kimmel and Sethian (PNAS 1998): vertices are accepted in increasing order of
/// \f$ T \f$ and each accepted vertex updates its neighbours along edges and through the triangles
/// whose two other vertices are accepted. The triangle update uses a circular wave front (the
/// virtual point source \f$ S \f$ with \f$ |SA| = T(A) \f$, \f$ |SB| = T(B) \f$ in the unfolded
/// triangle, \f$ T(C) = |SC| \f$ when \f$ SC \f$ crosses \f$ AB \f$), exact for one source on a flat
/// mesh and much more accurate at short range than the planar front of the paper (measured in
/// doc/geodesics.md). Obtuse angles are split by unfolding neighbouring triangles, as in the
/// paper. Vertices in another connected component than every source get \f$ +\infty \f$.
///
/// Queries are not thread-safe (they share one workspace): use one object per thread.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles.
template <typename TriangleMesh>
class Fast_marching_geodesic_distances
{
public:
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;

  /// Builds the flat copy of `tm` and the update stencils.
  /// \param tm the mesh (triangles, manifold, no isolated vertex; several components allowed)
  /// \param np optional named parameters:
  ///   - `vertex_point_map`: the positions (default: the internal point map of `tm`);
  ///   - `vertex_index_map`: a bijection onto [0, n) (default: the mesh's own, initialised if needed).
  /// \throws Invalid_mesh_error when `tm` is empty, not a triangle mesh, non-manifold, has NaN
  ///         coordinates or degenerate faces.
  template <typename NamedParameters = CGAL::parameters::Default_named_parameters>
  explicit Fast_marching_geodesic_distances(const TriangleMesh& tm,
                                            const NamedParameters& np = CGAL::parameters::default_values())
      : mesh_(new internal::Indexed_mesh(
            internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices_)))
  {
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    index_ = [vim](vertex_descriptor v) { return static_cast<int>(get(vim, v)); };
    geometry_.reset(new internal::Fast_marching_geometry(*mesh_));
    workspace_.reset(new internal::Fast_marching_workspace(*geometry_));
  }

  /// Writes into `distances` the fast-marching distance from `sources` (one vertex or a range of
  /// vertices, all at distance 0) to every vertex; vertices farther than `maximum_distance` (and
  /// those in components without a source) get +infinity.
  /// \tparam Sources `vertex_descriptor` or a range of them
  /// \tparam VertexDistanceMap a writable property map, key `vertex_descriptor`, value a floating
  ///         point type
  /// \pre `maximum_distance >= 0`
  template <typename Sources, typename VertexDistanceMap>
  void compute(const Sources& sources, VertexDistanceMap distances,
               double maximum_distance = std::numeric_limits<double>::infinity())
  {
    const std::vector<int> s = indices(sources);
    workspace_->run(s.data(), s.size(), maximum_distance);
    workspace_->copy_distances(buffer_);
    internal::write_vertex_values(vertices_, buffer_, distances);
  }

  /// The fast-marching distance between two vertices, computed from `b` and stopped as soon as
  /// `a` is accepted (early termination). +infinity if they are in different components.
  double distance(vertex_descriptor a, vertex_descriptor b)
  {
    const int ia = index_(a), ib = index_(b);
    internal::check_source_index(ib, mesh_->number_of_vertices(), "Fast_marching_geodesic_distances::distance");
    internal::check_source_index(ia, mesh_->number_of_vertices(), "Fast_marching_geodesic_distances::distance");
    workspace_->run(&ib, 1, std::numeric_limits<double>::infinity(), &ia, 1);
    return workspace_->distance(ia);
  }

  /// The flat copy the computation runs on (vertex i = vertex of index i).
  const internal::Indexed_mesh& indexed_mesh() const { return *mesh_; }
  /// The index of `v` in the flat copy.
  int vertex_index(vertex_descriptor v) const { return index_(v); }

private:
  template <typename Sources>
  std::vector<int> indices(const Sources& sources) const
  {
    std::vector<int> out;
    if constexpr(std::is_convertible<Sources, vertex_descriptor>::value)
      out.push_back(index_(vertex_descriptor(sources)));
    else
      for(const auto& v : sources) out.push_back(index_(v));
    for(int i : out)
      internal::check_source_index(i, mesh_->number_of_vertices(), "fast marching geodesic distances");
    return out;
  }

  std::vector<vertex_descriptor> vertices_;
  std::unique_ptr<internal::Indexed_mesh> mesh_;
  std::function<int(vertex_descriptor)> index_;
  std::unique_ptr<internal::Fast_marching_geometry> geometry_;
  std::unique_ptr<internal::Fast_marching_workspace> workspace_;
  std::vector<double> buffer_;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Heat-method geodesic distances (Crane, Weischedel and Wardetzky 2013) with
/// `CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3` in `Intrinsic_Delaunay` mode, factorised
/// once and queried one source at a time (CGAL 5.5's multi-source mode normalises wrongly, so it
/// is not offered).
///
/// The heat \f$ u \f$ after one implicit step \f$ (M + t L_c) u = \delta_s \f$, \f$ t = h^2 \f$
/// (\f$ h \f$ the mean edge length), gives the unit field \f$ X = -\nabla u / |\nabla u| \f$, and
/// the distance solves \f$ L_c \phi = \nabla \cdot X \f$, shifted to 0 at the source. Each
/// connected component has its own solver; vertices of other components get \f$ +\infty \f$.
///
/// Queries are not thread-safe: use one object per thread.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles.
template <typename TriangleMesh>
class Heat_method_geodesic_distances
{
public:
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;

  /// Precomputes the intrinsic Delaunay triangulation and the two factorisations.
  /// \param tm the mesh
  /// \param np optional named parameters `vertex_point_map`, `vertex_index_map` (as for
  ///        Fast_marching_geodesic_distances).
  /// \throws Invalid_mesh_error for a bad mesh (see make_indexed_mesh()).
  template <typename NamedParameters = CGAL::parameters::Default_named_parameters>
  explicit Heat_method_geodesic_distances(const TriangleMesh& tm,
                                          const NamedParameters& np = CGAL::parameters::default_values())
      : mesh_(new internal::Indexed_mesh(
            internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices_)))
  {
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    index_ = [vim](vertex_descriptor v) { return static_cast<int>(get(vim, v)); };
    solver_.reset(new internal::Heat_method_solver(*mesh_));
  }

  /// Writes the heat-method distance from `source` into `distances`.
  /// \tparam VertexDistanceMap a writable property map, key `vertex_descriptor`, floating point value
  template <typename VertexDistanceMap>
  void compute(vertex_descriptor source, VertexDistanceMap distances)
  {
    const int s = index_(source);
    internal::check_source_index(s, mesh_->number_of_vertices(), "heat method geodesic distances");
    solver_->distances(s, buffer_);
    internal::write_vertex_values(vertices_, buffer_, distances);
  }

  const internal::Indexed_mesh& indexed_mesh() const { return *mesh_; }
  int vertex_index(vertex_descriptor v) const { return index_(v); }

private:
  std::vector<vertex_descriptor> vertices_;
  std::unique_ptr<internal::Indexed_mesh> mesh_;
  std::function<int(vertex_descriptor)> index_;
  std::unique_ptr<internal::Heat_method_solver> solver_;
  std::vector<double> buffer_;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes fast-marching geodesic distances from `sources` to every vertex of `tm`.
///
/// See Fast_marching_geodesic_distances for the method. With `maximum_distance` the run stops
/// once the front passes that radius (farther vertices get \f$ +\infty \f$); with
/// `target_vertices` it stops as soon as all of them are final (the values of the others are
/// then \f$ +\infty \f$ unless they were accepted before). Accepted values are identical to those
/// of a full run.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam Sources `vertex_descriptor` or a range of `vertex_descriptor` (all at distance 0)
/// \tparam VertexDistanceMap a writable property map, key `vertex_descriptor`, floating point value
/// \tparam NamedParameters a sequence of named parameters:
///   - `vertex_point_map` (default: internal point map of `tm`);
///   - `vertex_index_map` (default: the mesh's own, initialised if needed);
///   - `maximum_distance`: truncation radius, `double` >= 0 (default: +infinity);
///   - `target_vertices`: a range of `vertex_descriptor`; stop once all are final (default: none).
/// \pre `sources` is not empty.
/// \throws Invalid_mesh_error for a bad mesh, Invalid_parameter_error for a source that is not a
///         vertex or a negative `maximum_distance`.
template <typename TriangleMesh, typename Sources, typename VertexDistanceMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
void fast_marching_geodesic_distances(const TriangleMesh& tm, const Sources& sources,
                                      VertexDistanceMap distances,
                                      const NamedParameters& np = CGAL::parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const std::vector<int> s = internal::vertex_indices(tm, sources, vim);
  for(int i : s) internal::check_source_index(i, m.number_of_vertices(), "fast_marching_geodesic_distances");
  const double max_distance = choose_parameter(get_parameter(np, internal_np::maximum_distance),
                                               std::numeric_limits<double>::infinity());
  std::vector<int> targets;
  const auto& target_range = get_parameter(np, internal_np::target_vertices);
  if constexpr(!std::is_same<typename std::decay<decltype(target_range)>::type,
                             CGAL::internal_np::Param_not_found>::value)
    for(const auto& v : target_range)
    {
      targets.push_back(static_cast<int>(get(vim, v)));
      internal::check_source_index(targets.back(), m.number_of_vertices(),
                                   "fast_marching_geodesic_distances (target)");
    }
  internal::Fast_marching_geometry g(m);
  internal::Fast_marching_workspace ws(g);
  ws.run(s.data(), s.size(), max_distance, targets.data(), targets.size());
  std::vector<double> d;
  ws.copy_distances(d);
  internal::write_vertex_values(vertices, d, distances);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes heat-method geodesic distances from `source` to every vertex of `tm` (CGAL
/// Heat_method_3, intrinsic Delaunay mode). For many sources use Heat_method_geodesic_distances.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam VertexDistanceMap a writable property map, key `vertex_descriptor`, floating point value
/// \tparam NamedParameters `vertex_point_map`, `vertex_index_map` (as above)
/// \throws Invalid_mesh_error, Invalid_parameter_error (source not a vertex)
template <typename TriangleMesh, typename VertexDistanceMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
void heat_method_geodesic_distances(const TriangleMesh& tm,
                                    typename boost::graph_traits<TriangleMesh>::vertex_descriptor source,
                                    VertexDistanceMap distances,
                                    const NamedParameters& np = CGAL::parameters::default_values())
{
  Heat_method_geodesic_distances<TriangleMesh> heat(tm, np);
  heat.compute(source, distances);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes exact polyhedral geodesic distances (shortest paths on the surface of the triangle
/// mesh, CGAL Surface_mesh_shortest_path) from `source` to every vertex of `tm`; +infinity in other
/// components. Costs about 0.1-0.2 s per source on a 5k-vertex mesh: meant for references and tests.
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles
/// \tparam VertexDistanceMap a writable property map, key `vertex_descriptor`, floating point value
/// \tparam NamedParameters `vertex_point_map`, `vertex_index_map` (as above)
/// \throws Invalid_mesh_error, Invalid_parameter_error (source not a vertex)
template <typename TriangleMesh, typename VertexDistanceMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
void exact_geodesic_distances(const TriangleMesh& tm,
                              typename boost::graph_traits<TriangleMesh>::vertex_descriptor source,
                              VertexDistanceMap distances,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const int s = static_cast<int>(get(vim, source));
  internal::check_source_index(s, m.number_of_vertices(), "exact_geodesic_distances");
  internal::Exact_geodesic_solver exact(m);
  std::vector<double> d;
  exact.distances(s, d);
  internal::write_vertex_values(vertices, d, distances);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_GEODESIC_DISTANCES_H
