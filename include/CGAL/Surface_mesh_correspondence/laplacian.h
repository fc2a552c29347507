// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The cotangent Laplace-Beltrami operator of a triangle mesh: stiffness matrix L and lumped mass
// matrix M, optionally on the intrinsic Delaunay triangulation of the mesh.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_LAPLACIAN_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_LAPLACIAN_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/intrinsic_delaunay.h>
#include <CGAL/Surface_mesh_correspondence/internal/tufted_cover.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The discrete Laplace-Beltrami operator of a triangle mesh with n vertices, as the pair of
/// sparse n x n matrices of the weak form \f$ L \phi = \lambda M \phi \f$.
struct Laplace_beltrami_matrices
{
  /// Cotangent stiffness matrix: for an edge (i, j),
  /// \f$ L_{ij} = -\frac{1}{2}(\cot\alpha_{ij} + \cot\beta_{ij}) \f$ (only one angle on the
  /// boundary: natural Neumann condition), \f$ L_{ii} = -\sum_{j \neq i} L_{ij} \f$. Symmetric
  /// positive semi-definite, \f$ L \mathbf{1} = 0 \f$.
  Eigen::SparseMatrix<double> stiffness_matrix;
  /// Lumped (diagonal) mass matrix: \f$ M_{ii} \f$ is a third of the area of the input triangles
  /// incident to vertex i (the same with or without intrinsic Delaunay flips).
  Eigen::SparseMatrix<double> mass_matrix;
  /// The diagonal of the mass matrix.
  Eigen::VectorXd mass;
  /// Edge flips made to reach the intrinsic Delaunay triangulation (0 without it).
  int number_of_flips = 0;
};

namespace internal {

/// Assembles the cotangent stiffness matrix L from the edge lengths of an (intrinsic)
/// triangulation: every halfedge adds half the cotangent of its opposite angle to its edge.
inline Eigen::SparseMatrix<double> cotangent_stiffness_matrix(const Intrinsic_triangulation& t)
{
  typedef Eigen::Triplet<double> Triplet;
  const int n = t.number_of_vertices;
  const int nh = t.number_of_halfedges();
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
  std::vector<Triplet> triplets;
  triplets.reserve(2 * static_cast<std::size_t>(nh) + static_cast<std::size_t>(n));
  for(int f = 0; f < t.number_of_triangles(); ++f)
    if(!(t.triangle_area(f) > 0))
      throw Numerical_error("Laplace-Beltrami operator: triangle " + std::to_string(f) +
                            " has zero area after intrinsic edge flips");
  for(int h = 0; h < nh; ++h)
  {
    const int i = t.origin[h], j = t.target(h);
    if(i == j) continue;  // a loop edge (Delta-complex) contributes nothing
    const double w = 0.5 * t.cotangent_opposite(h);
    triplets.emplace_back(i, j, -w);
    triplets.emplace_back(j, i, -w);
    diagonal[i] += w;
    diagonal[j] += w;
  }
  for(int i = 0; i < n; ++i) triplets.emplace_back(i, i, diagonal[i]);
  Eigen::SparseMatrix<double> stiffness(n, n);
  stiffness.setFromTriplets(triplets.begin(), triplets.end());
  stiffness.makeCompressed();
  return stiffness;
}

/// The lumped mass of every vertex: a third of the area of its incident (input) triangles.
inline Eigen::VectorXd lumped_mass(const Indexed_mesh& m)
{
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(m.number_of_vertices());
  for(int f = 0; f < m.number_of_triangles(); ++f)
    for(int c = 0; c < 3; ++c) mass[m.triangles(f, c)] += m.triangle_areas[f] / 3.0;
  return mass;
}

/// The margin of the intrinsic mollification of the tufted Laplacian, relative to the mean edge
/// length (Sharp and Crane 2020 use 1e-5 too).
constexpr double default_mollification = 1e-5;

/// The tufted cover of a mesh (tufted_cover()) after intrinsic mollification
/// (mollify_edge_lengths()) with a margin of `mollification` times its mean edge length, and the
/// lumped mass of the operators built on it: that of the input triangles, or of the mollified
/// ones when the mollification lengthened the edges (then no vertex has zero mass). `added` is the
/// length added to every edge.
struct Mollified_tufted_cover
{
  Intrinsic_triangulation triangulation;
  Eigen::VectorXd mass;
  double added = 0;
};

inline Mollified_tufted_cover mollified_tufted_cover(const Indexed_mesh& m, double mollification)
{
  Mollified_tufted_cover out;
  Intrinsic_triangulation& t = out.triangulation;
  t = tufted_cover(m);
  double mean_length = 0;
  for(double l : t.length) mean_length += l;
  mean_length /= double(std::max<std::size_t>(t.length.size(), 1));
  out.added = mollify_edge_lengths(t, mollification * mean_length);
  if(out.added > 0)
  {
    // Each triangle of the mesh is twice in the cover: half of the cover's lumped mass.
    out.mass = Eigen::VectorXd::Zero(m.number_of_vertices());
    for(int f = 0; f < t.number_of_triangles(); ++f)
      for(int c = 0; c < 3; ++c) out.mass[t.origin[std::size_t(3 * f + c)]] += t.triangle_area(f) / 6.0;
  }
  else
    out.mass = lumped_mass(m);
  return out;
}

/// The mass (diagonal of M) of laplace_beltrami_matrices(m, ...): the lumped mass of the input
/// triangles, or of the mollified tufted cover on a mesh that needs it
/// (Indexed_mesh::needs_tufted_cover()); intrinsic flips do not change it.
inline Eigen::VectorXd laplacian_mass(const Indexed_mesh& m)
{
  return m.needs_tufted_cover() ? mollified_tufted_cover(m, default_mollification).mass : lumped_mass(m);
}

inline Laplace_beltrami_matrices tufted_laplace_beltrami_matrices(const Indexed_mesh& m,
                                                                  double mollification = default_mollification,
                                                                  double* epsilon = nullptr,
                                                                  bool use_intrinsic_delaunay = true);

/// L and M of an indexed mesh; L on its intrinsic Delaunay triangulation when
/// `use_intrinsic_delaunay` is true (M is the lumped mass of the input triangles). A mesh with
/// non-manifold edges or vertices or faces of zero area (Indexed_mesh::needs_tufted_cover()) gets
/// the tufted Laplacian (tufted_laplace_beltrami_matrices()), the same operator on a manifold mesh
/// of well-shaped triangles.
inline Laplace_beltrami_matrices laplace_beltrami_matrices(const Indexed_mesh& m,
                                                           bool use_intrinsic_delaunay)
{
  if(m.needs_tufted_cover())
    return tufted_laplace_beltrami_matrices(m, default_mollification, nullptr, use_intrinsic_delaunay);
  Intrinsic_triangulation t = make_intrinsic_triangulation(m);
  Laplace_beltrami_matrices out;
  if(use_intrinsic_delaunay) out.number_of_flips = make_intrinsic_delaunay(t);
  out.stiffness_matrix = cotangent_stiffness_matrix(t);
  out.mass = lumped_mass(m);
  const int n = m.number_of_vertices();
  out.mass_matrix.resize(n, n);
  out.mass_matrix.reserve(Eigen::VectorXi::Ones(n));
  for(int i = 0; i < n; ++i) out.mass_matrix.insert(i, i) = out.mass[i];
  out.mass_matrix.makeCompressed();
  return out;
}

/// The tufted Laplacian of Sharp and Crane (2020): L and M of an indexed mesh that may have
/// non-manifold edges and vertices, from the intrinsic Delaunay triangulation of its tufted cover
/// (tufted_cover()): L is half the cover's cotangent matrix (the cover has every triangle twice),
/// expressed on the mesh's vertices; M is the lumped mass of the input triangles. Symmetric,
/// positive semi-definite, every off-diagonal entry non-positive, one zero eigenvalue per
/// component; on a closed manifold mesh it is the intrinsic Delaunay Laplacian
/// (laplace_beltrami_matrices() with `use_intrinsic_delaunay`). `number_of_flips` counts the flips
/// on the cover.
///
/// Faces of zero or nearly zero area (a mesh built with Mesh_requirements::allow_degenerate_faces)
/// are handled by intrinsic mollification (mollify_edge_lengths()) with a margin of `mollification`
/// times the mean edge length: when it lengthens the edges, M is the lumped mass of the mollified
/// triangles, so that no vertex has zero mass. `epsilon`, when given, receives the length added.
/// Without `use_intrinsic_delaunay`, L is the cotangent matrix of the (mollified) cover itself.
inline Laplace_beltrami_matrices tufted_laplace_beltrami_matrices(const Indexed_mesh& m, double mollification,
                                                                  double* epsilon, bool use_intrinsic_delaunay)
{
  Mollified_tufted_cover cover = mollified_tufted_cover(m, mollification);
  Intrinsic_triangulation& t = cover.triangulation;
  if(epsilon) *epsilon = cover.added;
  Laplace_beltrami_matrices out;
  const int n = m.number_of_vertices();
  out.mass = std::move(cover.mass);
  if(use_intrinsic_delaunay) out.number_of_flips = make_intrinsic_delaunay(t);
  out.stiffness_matrix = 0.5 * cotangent_stiffness_matrix(t);
  out.stiffness_matrix.makeCompressed();
  out.mass_matrix.resize(n, n);
  out.mass_matrix.reserve(Eigen::VectorXi::Ones(n));
  for(int i = 0; i < n; ++i) out.mass_matrix.insert(i, i) = out.mass[i];
  out.mass_matrix.makeCompressed();
  return out;
}

/// The default of the named parameter `use_intrinsic_delaunay` (see doc/spectral.md for the
/// measurements behind it).
constexpr bool default_use_intrinsic_delaunay = true;

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes the cotangent stiffness matrix and the lumped mass matrix of the Laplace-Beltrami
/// operator of a triangle mesh.
///
/// Row and column i correspond to the vertex of index i in the vertex index map. With
/// `use_intrinsic_delaunay` (the default), the matrices are those of the intrinsic Delaunay
/// triangulation of the same piecewise-flat surface (Fisher et al. 2007, Bobenko and
/// Springborn 2007): every off-diagonal entry of L is then non-positive, which makes the
/// operator accurate on meshes with obtuse or nearly degenerate triangles. Boundary edges get the
/// single cotangent of their one triangle (natural Neumann boundary condition); several
/// connected components give a block-diagonal L.
///
/// \f[ L_{ij} = -\tfrac{1}{2}(\cot\alpha_{ij} + \cot\beta_{ij}), \quad
///     L_{ii} = -\sum_{j\neq i} L_{ij}, \quad M_{ii} = \tfrac{1}{3}\sum_{t \ni i} |t| \f]
///
/// \tparam TriangleMesh a model of `FaceListGraph` (e.g. `CGAL::Surface_mesh`, `CGAL::Polyhedron_3`)
/// \tparam NamedParameters a sequence of named parameters
///
/// \param tm the triangle mesh
/// \param np optional named parameters among:
///   - `vertex_point_map`: the vertex positions; type: a readable property map from vertex
///     descriptors to points of a CGAL kernel; default: `get(CGAL::vertex_point, tm)`.
///   - `vertex_index_map`: a bijection from the vertices onto [0, n); type: a readable property
///     map with integer values; default: the mesh's own vertex index (initialised if needed).
///   - `use_intrinsic_delaunay`: assemble the operator on the intrinsic Delaunay triangulation;
///     type: `bool`; default: `true`.
///
/// \pre `tm` is a non-empty, manifold triangle mesh without isolated vertices, degenerate faces
///   or non-finite coordinates (else Invalid_mesh_error is thrown).
/// \returns the matrices (and the mass as a vector).
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Laplace_beltrami_matrices laplace_beltrami_matrices(
    const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const bool idt = choose_parameter(get_parameter(np, internal_np::use_intrinsic_delaunay),
                                    internal::default_use_intrinsic_delaunay);
  const internal::Indexed_mesh m =
      internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "Laplace-Beltrami: mesh");
  return internal::laplace_beltrami_matrices(m, idt);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_LAPLACIAN_H
