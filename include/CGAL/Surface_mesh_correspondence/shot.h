// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// SHOT (Signature of Histograms of OrienTations) descriptors on the vertices of a triangle mesh.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_SHOT_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_SHOT_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/shot_impl.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <Eigen/Core>

#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

namespace internal {

template <typename T>
struct Shot_is_named_parameters : std::false_type
{};
template <typename T, typename Tag, typename Base>
struct Shot_is_named_parameters<CGAL::Named_function_parameters<T, Tag, Base> > : std::true_type
{};

template <typename NamedParameters>
Shot_options shot_options_from(const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  Shot_options options;
  options.relative_radius =
      choose_parameter(get_parameter(np, internal_np::shot_radius), internal::matching_defaults().shot_radius);
  check_shot_options(options);
  return options;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Length of a SHOT descriptor: 32 spatial sectors times 11 cosine bins.
constexpr int shot_descriptor_size = internal::shot_descriptor_size;

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes the SHOT descriptor (Tombari, Salti and Di Stefano, ECCV 2010 / CVIU 2014) of every
/// vertex of a triangle mesh.
///
/// For a vertex \f$ p \f$ with support radius \f$ R = r \sqrt{A} \f$ (\f$ A \f$ the total surface
/// area, \f$ r \f$ the parameter `shot_radius`), the support is the set of the other vertices
/// \f$ p_i \f$ with \f$ d_i = \|p_i - p\| < R \f$. The local reference frame is given by the
/// eigenvectors of
/// \f[ M = \frac{1}{\sum_i (R - d_i)} \sum_i (R - d_i)\,(p_i - p)(p_i - p)^\top, \f]
/// \f$ x \f$ for the largest eigenvalue, \f$ z \f$ for the smallest, each oriented towards the
/// side holding the majority of the support points (ties: the sign of
/// \f$ \sum_i (R - d_i) (p_i - p) \cdot x \f$; a flat support: \f$ z \f$ along the vertex normal),
/// and \f$ y = z \times x \f$. The support sphere is split into 32 sectors (8 azimuths x 2
/// elevations x 2 radial shells split at \f$ R/2 \f$); each sector holds an 11-bin histogram of
/// \f$ \cos\theta_i = n_i \cdot z \f$ over \f$ [-1, 1] \f$, \f$ n_i \f$ being the area-weighted
/// vertex normal of \f$ p_i \f$. Every support point is spread over the 16 neighbouring (cosine,
/// azimuth, elevation, radius) bins by quadrilinear interpolation, and the 352-vector is scaled
/// to unit Euclidean norm.
///
/// Few neighbours: the support radius of a vertex is \f$ \max(R, 1.25\, d_{10}) \f$,
/// \f$ d_{10} \f$ being the distance to its 10th nearest other vertex (all vertices on meshes with
/// fewer than 11), so the frame always rests on at least 10 points. Fine meshes: on meshes with
/// more than 20000 vertices, the support points are taken from a Poisson-disk subsample of about
/// 20000 vertices (every vertex still gets its descriptor), which bounds the cost per vertex. The
/// result is always finite with unit norm. See doc/shot.md.
///
/// The mesh must be consistently oriented: the cosines use the vertex normals given by the
/// orientation of the faces, so two meshes compared with SHOT must follow the same convention
/// (e.g. outward normals). Results are identical with `CGAL::Sequential_tag` and
/// `CGAL::Parallel_tag`.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (needs TBB).
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles.
/// \tparam NamedParameters a sequence of named parameters.
///
/// \param tm the mesh.
/// \param np optional named parameters among:
///   - `vertex_point_map`: the positions of the vertices. Type: a readable property map from
///     `vertex_descriptor` to a CGAL 3D point. Default: `get(CGAL::vertex_point, tm)`.
///   - `vertex_index_map`: row of each vertex in the result. Type: a readable property map from
///     `vertex_descriptor` to an integer, a bijection onto [0, num_vertices(tm)). Default: the
///     mesh's own vertex index map (initialised if needed).
///   - `shot_radius`: the support radius relative to the square root of the total surface area.
///     Type: `double` > 0. Default: 0.08.
///
/// \returns a `num_vertices(tm)` x 352 matrix; row \f$ i \f$ is the descriptor of the vertex of
/// index \f$ i \f$ (value \f$ ((r \cdot 2 + e) \cdot 8 + a) \cdot 11 + c \f$ of a row is cosine bin
/// \f$ c \f$ of the sector with radial shell \f$ r \f$, elevation \f$ e \f$, azimuth \f$ a \f$).
///
/// \pre `tm` is a non-empty, manifold, consistently oriented triangle mesh with finite
/// coordinates, no degenerate face and no isolated vertex (else `Invalid_mesh_error`);
/// `shot_radius` is finite and > 0 (else `Invalid_parameter_error`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters,
          typename = std::enable_if_t<internal::Shot_is_named_parameters<NamedParameters>::value> >
Eigen::MatrixXd compute_shot_descriptors(const TriangleMesh& tm,
                                         const NamedParameters& np = parameters::default_values())
{
  const internal::Shot_options options = internal::shot_options_from(np);
  internal::Mesh_requirements requirements;
  requirements.allow_isolated_vertices = false;
  const internal::Indexed_mesh m = internal::make_indexed_mesh(tm, np, requirements, "SHOT mesh");
  return internal::shot_descriptors<ConcurrencyTag>(m, options);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes the SHOT descriptors of some vertices of a triangle mesh: row \f$ k \f$ of the result
/// is the descriptor of the \f$ k \f$-th vertex of `vertices`, equal to the corresponding row of
/// `compute_shot_descriptors(tm, np)` (neighbours are taken among all vertices of `tm`).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (needs TBB).
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles.
/// \tparam VertexRange a range of `boost::graph_traits<TriangleMesh>::vertex_descriptor`.
/// \tparam NamedParameters a sequence of named parameters.
///
/// \param tm the mesh.
/// \param vertices the vertices to describe (repetitions allowed).
/// \param np optional named parameters, as for `compute_shot_descriptors(tm, np)`.
///
/// \returns a `size(vertices)` x 352 matrix.
///
/// \pre as for `compute_shot_descriptors(tm, np)`; every element of `vertices` is a vertex of `tm`.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh, typename VertexRange,
          typename NamedParameters = parameters::Default_named_parameters,
          typename = std::enable_if_t<!internal::Shot_is_named_parameters<VertexRange>::value> >
Eigen::MatrixXd compute_shot_descriptors(const TriangleMesh& tm, const VertexRange& vertices,
                                         const NamedParameters& np = parameters::default_values())
{
  const internal::Shot_options options = internal::shot_options_from(np);
  // One vertex index map for both the flat copy and the query rows.
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const auto np_with_index = np.vertex_index_map(vim);
  internal::Mesh_requirements requirements;
  requirements.allow_isolated_vertices = false;
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np_with_index, requirements, "SHOT mesh");
  std::vector<int> queries;
  for(const auto& v : vertices) queries.push_back(static_cast<int>(get(vim, v)));
  return internal::shot_descriptors<ConcurrencyTag>(m, queries.data(), queries.size(), options);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_SHOT_H
