// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The weighted descriptor stack of the paper (Section 4.2): F(i) = (w1 f1(i), ..., wk fk(i)),
// with HKS, WKS, SHOT and an optional user-supplied descriptor, each block normalised so that
// the weights mean the same thing on every shape.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_DESCRIPTOR_STACK_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_DESCRIPTOR_STACK_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/shot.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Settings of the descriptor stack: the weight of each block (0 leaves a block out) and the
/// parameters of each descriptor. The defaults are the package's defaults for matching
/// near-isometric shapes.
struct Descriptor_settings
{
  double hks_weight = internal::matching_defaults().hks_weight;    ///< weight of the heat kernel signature block
  double wks_weight = internal::matching_defaults().wks_weight;    ///< weight of the wave kernel signature block
  double shot_weight = internal::matching_defaults().shot_weight;  ///< weight of the SHOT block
  /// weight of the user-supplied block, if any
  double user_weight = internal::matching_defaults().user_descriptor_weight;
  int number_of_hks_scales = internal::matching_defaults().number_of_hks_scales;      ///< HKS times
  int number_of_wks_energies = internal::matching_defaults().number_of_wks_energies;  ///< WKS energies
  /// WKS variance, in multiples of the energy step
  double wks_variance = internal::matching_defaults().wks_variance;
  double shot_radius = internal::matching_defaults().shot_radius;  ///< SHOT radius relative to sqrt(area)

  /// The descriptor settings of `m` (`hks_weight`, `wks_weight`, `shot_weight`,
  /// `user_descriptor_weight`, `number_of_hks_scales`, `number_of_wks_energies`, `wks_variance`,
  /// `shot_radius`).
  static Descriptor_settings from(const Matching_settings& m)
  {
    Descriptor_settings s;
    s.hks_weight = m.hks_weight;
    s.wks_weight = m.wks_weight;
    s.shot_weight = m.shot_weight;
    s.user_weight = m.user_descriptor_weight;
    s.number_of_hks_scales = m.number_of_hks_scales;
    s.number_of_wks_energies = m.number_of_wks_energies;
    s.wks_variance = m.wks_variance;
    s.shot_radius = m.shot_radius;
    return s;
  }

  /// Reads the settings from named parameters (see from(const Matching_settings&)), keeping the
  /// registry's defaults for those not given.
  template <typename NamedParameters>
  static Descriptor_settings from(const NamedParameters& np)
  {
    return from(Matching_settings::from(np));
  }

  /// Throws Invalid_parameter_error for a negative or non-finite weight, or when every weight is 0.
  void check(bool has_user_block = false) const
  {
    const double w[4] = {hks_weight, wks_weight, shot_weight, user_weight};
    const char* names[4] = {"hks_weight", "wks_weight", "shot_weight", "user_descriptor_weight"};
    for(int b = 0; b < 4; ++b)
      if(!(w[b] >= 0) || !std::isfinite(w[b]))
        throw Invalid_parameter_error(std::string("descriptor stack: ") + names[b] + " = " +
                                      std::to_string(w[b]) + " must be finite and non-negative");
    if(hks_weight == 0 && wks_weight == 0 && shot_weight == 0 && !(has_user_block && user_weight > 0))
      throw Invalid_parameter_error("descriptor stack: every descriptor weight is 0");
  }
};

namespace internal {

/// Scales `block` so that its rows have unit area-weighted mean squared norm, then by `weight`,
/// and copies it into columns [column, column + block.cols()) of `stack`.
inline void append_descriptor_block(const Eigen::MatrixXd& block, const Eigen::VectorXd& vertex_areas,
                                    double weight, Eigen::MatrixXf& stack, Eigen::Index column,
                                    const char* name)
{
  const double area = vertex_areas.sum();
  const double mean_square = (vertex_areas.array() * block.rowwise().squaredNorm().array()).sum() / area;
  if(!std::isfinite(mean_square))
    throw Numerical_error(std::string("descriptor stack: the ") + name + " block has non-finite values");
  const double factor = mean_square > 0 ? weight / std::sqrt(mean_square) : 0.0;
  stack.middleCols(column, block.cols()) = (block * factor).cast<float>();
}

/// Per-vertex lumped areas (one third of the incident triangle areas).
inline Eigen::VectorXd vertex_areas(const Indexed_mesh& m)
{
  Eigen::VectorXd a = Eigen::VectorXd::Zero(m.number_of_vertices());
  for(int f = 0; f < m.number_of_triangles(); ++f)
    for(int c = 0; c < 3; ++c) a[m.triangles(f, c)] += m.triangle_areas[static_cast<std::size_t>(f)] / 3.0;
  return a;
}

/// The descriptor stack of a mesh whose spectrum is already computed. `user` (n x d, may be
/// empty) is the user-supplied block.
template <typename ConcurrencyTag>
Eigen::MatrixXf descriptor_stack(const Indexed_mesh& m, const Laplace_beltrami_spectrum& spectrum,
                                 const Descriptor_settings& s, const Eigen::MatrixXd& user = Eigen::MatrixXd())
{
  s.check(user.size() > 0);
  const Eigen::Index n = m.number_of_vertices();
  if(user.size() > 0 && user.rows() != n)
    throw Invalid_parameter_error("descriptor stack: the user descriptors have " + std::to_string(user.rows()) +
                                  " rows for a mesh of " + std::to_string(n) + " vertices");
  if(spectrum.number_of_vertices() != n)
    throw Invalid_parameter_error("descriptor stack: the spectrum is not the mesh's");
  std::vector<Eigen::MatrixXd> blocks;
  std::vector<double> weights;
  std::vector<const char*> names;
  if(s.hks_weight > 0)
  {
    blocks.push_back(heat_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_hks_scales(s.number_of_hks_scales)));
    weights.push_back(s.hks_weight);
    names.push_back("HKS");
  }
  if(s.wks_weight > 0)
  {
    blocks.push_back(wave_kernel_signature<ConcurrencyTag>(
        spectrum, parameters::number_of_wks_energies(s.number_of_wks_energies,
                                                     parameters::wks_variance(s.wks_variance))));
    weights.push_back(s.wks_weight);
    names.push_back("WKS");
  }
  if(s.shot_weight > 0)
  {
    Shot_options options;
    options.relative_radius = s.shot_radius;
    blocks.push_back(shot_descriptors<ConcurrencyTag>(m, options));
    weights.push_back(s.shot_weight);
    names.push_back("SHOT");
  }
  if(user.size() > 0 && s.user_weight > 0)
  {
    if(!user.allFinite()) throw Invalid_parameter_error("descriptor stack: the user descriptors are not all finite");
    blocks.push_back(user);
    weights.push_back(s.user_weight);
    names.push_back("user");
  }
  Eigen::Index columns = 0;
  for(const auto& b : blocks) columns += b.cols();
  Eigen::MatrixXf stack(n, columns);
  const Eigen::VectorXd areas = vertex_areas(m);
  Eigen::Index column = 0;
  for(std::size_t b = 0; b < blocks.size(); ++b)
  {
    append_descriptor_block(blocks[b], areas, weights[b], stack, column, names[b]);
    column += blocks[b].cols();
  }
  return stack;
}

/// Reads a user descriptor property map (vertex -> random-access range of numbers, the same
/// length for every vertex) into an n x d matrix, rows in vertex index order.
template <typename VertexDescriptor, typename DescriptorMap>
Eigen::MatrixXd read_user_descriptors(const std::vector<VertexDescriptor>& vertices, const DescriptorMap& map)
{
  Eigen::MatrixXd out;
  for(std::size_t i = 0; i < vertices.size(); ++i)
  {
    const auto& row = get(map, vertices[i]);
    const Eigen::Index d = static_cast<Eigen::Index>(std::size(row));
    if(i == 0) out.resize(static_cast<Eigen::Index>(vertices.size()), d);
    if(d != out.cols())
      throw Invalid_parameter_error("user descriptors: vertex " + std::to_string(i) + " has " + std::to_string(d) +
                                    " values, vertex 0 has " + std::to_string(out.cols()));
    Eigen::Index c = 0;
    for(const auto& x : row) out(static_cast<Eigen::Index>(i), c++) = static_cast<double>(x);
  }
  return out;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes the weighted descriptor stack of every vertex of `tm`:
/// \f[ F(i) = \big(w_{hks}\,\hat f_{hks}(i),\; w_{wks}\,\hat f_{wks}(i),\; w_{shot}\,\hat f_{shot}(i),\; w_{user}\,\hat f_{user}(i)\big), \f]
/// where each block \f$ \hat f \f$ is the descriptor scaled so that the area-weighted mean of
/// \f$ \|\hat f(i)\|^2 \f$ over the surface is 1. With this normalisation the weights are
/// comparable between blocks and between shapes, and the unary term of the coupled refinement,
/// \f$ U(i,k) = \|F_1(i) - F_2(k)\|^2 \f$ (paper, Eq. 2), is about \f$ 2 \sum w^2 \f$ between
/// unrelated vertices.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag`
/// \tparam TriangleMesh a model of `FaceListGraph` (triangles)
/// \param tm the mesh
/// \param np optional named parameters: `hks_weight` (double, 0.5), `wks_weight` (double, 1),
///   `shot_weight` (double, 1), `user_descriptor_map` (vertex -> range of numbers, none),
///   `user_descriptor_weight` (double, 1), `number_of_hks_scales` (16),
///   `number_of_wks_energies` (100), `wks_variance` (7), `shot_radius` (0.08 of sqrt(area)),
///   `number_of_eigenpairs` (100), `vertex_point_map`, `vertex_index_map`.
/// \returns the n x D matrix (float) whose row i is the stack of vertex i.
/// \throws Invalid_mesh_error, Invalid_parameter_error
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
Eigen::MatrixXf descriptor_stack(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  const internal::Indexed_mesh m = internal::make_indexed_mesh(tm, np, internal::Mesh_requirements(), "mesh", &vertices);
  const Laplace_beltrami_spectrum spectrum(m, np);
  Eigen::MatrixXd user;
  const auto& user_map = parameters::get_parameter(np, internal_np::user_descriptor_map);
  if constexpr(!std::is_same<typename std::decay<decltype(user_map)>::type, CGAL::internal_np::Param_not_found>::value)
    user = internal::read_user_descriptors(vertices, user_map);
  return internal::descriptor_stack<ConcurrencyTag>(m, spectrum, Descriptor_settings::from(np), user);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_DESCRIPTOR_STACK_H
