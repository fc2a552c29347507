// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The precomputed data of one shape for matching: flat mesh, Laplace-Beltrami spectrum,
// descriptor stack, geodesic distance oracle, nearest-vertex search and the node order of the
// MRFs. Built once per mesh, it is reused for every pair the mesh takes part in.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_CORRESPONDENCE_SHAPE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_CORRESPONDENCE_SHAPE_H

#include <CGAL/Surface_mesh_correspondence/descriptor_stack.h>
#include <CGAL/Surface_mesh_correspondence/distance_oracle.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_data.h>
#include <CGAL/Surface_mesh_correspondence/internal/nearest_vertex.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include <Eigen/Core>

#include <array>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// What the input check found in a mesh beyond a manifold mesh of well-shaped triangles: what
/// remeshers and scanners leave and the matching handles (the tufted Laplacian of Sharp and Crane
/// 2020 with intrinsic mollification, see doc/spectral.md), instead of refusing the mesh.
/// Vertices are numbered as in the maps, faces in the input order.
struct Mesh_irregularities
{
  /// Edges (i < j) in more than two faces: a fin, two sheets touching along an edge.
  std::vector<std::array<std::size_t, 2> > non_manifold_edges;
  /// Vertices joining several separate fans of faces (a bow-tie).
  std::vector<std::size_t> non_manifold_vertices;
  /// Faces of (nearly) zero area: collinear vertices, slivers below 1e-12 of the squared longest
  /// edge.
  std::vector<std::size_t> degenerate_faces;

  /// Whether the mesh has none of these.
  bool empty() const { return non_manifold_edges.empty() && non_manifold_vertices.empty() && degenerate_faces.empty(); }
};

namespace internal {

inline Mesh_irregularities mesh_irregularities(const Indexed_mesh& m)
{
  Mesh_irregularities r;
  for(const auto& e : m.non_manifold_edges) r.non_manifold_edges.push_back({{std::size_t(e[0]), std::size_t(e[1])}});
  r.non_manifold_vertices.assign(m.non_manifold_vertices.begin(), m.non_manifold_vertices.end());
  r.degenerate_faces.assign(m.degenerate_faces.begin(), m.degenerate_faces.end());
  return r;
}

/// What the shapes accept: one connected component; boundaries, non-manifold edges and vertices
/// and faces of zero area (handled by the tufted Laplacian and mollification).
inline Mesh_requirements shape_requirements()
{
  Mesh_requirements req;
  req.allow_several_components = false;
  req.allow_non_manifold = true;
  req.allow_degenerate_faces = true;
  return req;
}

/// "1 non-manifold edge, 2 degenerate faces" (the counts that are not zero).
inline std::string irregularities_summary(const Mesh_irregularities& r)
{
  std::string s;
  auto add = [&](std::size_t count, const char* what) {
    if(count == 0) return;
    if(!s.empty()) s += ", ";
    s += std::to_string(count) + " " + what + (count == 1 ? "" : "s");
  };
  add(r.non_manifold_edges.size(), "non-manifold edge");
  add(r.non_manifold_vertices.size(), "non-manifold vertex");
  add(r.degenerate_faces.size(), "degenerate face");
  return s;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Checks that a triangle soup is a mesh Correspondence_shape and match_shapes() accept: at least
/// one vertex and one face, finite coordinates, faces of three distinct vertices in range, one
/// connected component without isolated vertices, faces oriented consistently across every edge
/// in two faces. Returns what the check found beyond a manifold mesh of well-shaped triangles,
/// which the matching handles (stricter: check_triangle_soup(), what a halfedge mesh can hold).
/// \throws Invalid_mesh_error naming the first problem, the vertex or face, and the soup's origin
inline Mesh_irregularities inspect_triangle_soup(const Triangle_soup& soup)
{
  return internal::mesh_irregularities(
      internal::make_soup_indexed_mesh(soup, internal::shape_requirements(), soup.origin().name));
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Seconds spent on each part of a shape's preprocessing.
struct Shape_preprocessing_times
{
  double mesh = 0;         ///< flat copy and checks
  double spectrum = 0;     ///< Laplace-Beltrami eigenpairs
  double descriptors = 0;  ///< HKS, WKS, SHOT and the stack
  double distances = 0;    ///< the geodesic distance oracle
  double initialization = 0;  ///< the automatic initialisation's descriptors
  double total() const { return mesh + spectrum + descriptors + distances + initialization; }
};

/// An n x D descriptor stack stored row by row.
typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Descriptor_matrix;

namespace internal {

/// Index-based precomputed data of a shape (what the algorithms use).
struct Shape_data
{
  Indexed_mesh mesh;
  double scale = 1;  ///< sqrt(total area): every distance is divided by it
  std::unique_ptr<Laplace_beltrami_spectrum> spectrum;
  /// The `precomputed_spectrum` (shared when given by shared pointer, else a copy) when it has
  /// more eigenpairs than `spectrum` (null otherwise): automatic_initial_maps() on the shape
  /// takes its eigenpairs from it.
  std::shared_ptr<const Laplace_beltrami_spectrum> larger_spectrum;
  /// n x D descriptor stack, row-major: the MRF's unary terms read whole rows (vertex
  /// descriptors) at random, and a column-major row is D cache lines apart.
  Descriptor_matrix descriptors;
  std::variant<Local_distance_oracle, Dense_distance_oracle> oracle;
  std::unique_ptr<Nearest_vertex_search> nearest;
  /// Node order of the MRFs whose nodes are this shape's vertices: a breadth-first order, which
  /// keeps the neighbours of a node close in memory (TRW-S is faster and converges better).
  std::vector<int> node_order;     ///< node -> vertex
  std::vector<int> node_of_vertex; ///< vertex -> node
  Shape_preprocessing_times times;
  /// Filled by the first automatic_initial_maps(), repair_torn_maps() or
  /// compare_with_automatic_maps() call on the shape (shared by copies of the shape).
  std::shared_ptr<Shape_initialization_cache> initialization = std::make_shared<Shape_initialization_cache>();

  int number_of_vertices() const { return mesh.number_of_vertices(); }
  /// The spectrum with the most eigenpairs that the shape holds.
  const Laplace_beltrami_spectrum& largest_spectrum() const { return larger_spectrum ? *larger_spectrum : *spectrum; }

  /// Breadth-first order over every component, starting each component at its smallest vertex.
  void compute_node_order()
  {
    const int n = mesh.number_of_vertices();
    node_order.clear();
    node_order.reserve(static_cast<std::size_t>(n));
    node_of_vertex.assign(static_cast<std::size_t>(n), -1);
    for(int start = 0; start < n; ++start)
    {
      if(node_of_vertex[start] >= 0) continue;
      std::size_t head = node_order.size();
      node_of_vertex[start] = static_cast<int>(node_order.size());
      node_order.push_back(start);
      while(head < node_order.size())
      {
        const int v = node_order[head++];
        for(const int* w = mesh.neighbors_begin(v); w != mesh.neighbors_end(v); ++w)
          if(node_of_vertex[*w] < 0)
          {
            node_of_vertex[*w] = static_cast<int>(node_order.size());
            node_order.push_back(*w);
          }
      }
    }
  }
};

/// Settings of a shape's preprocessing.
struct Shape_settings
{
  int number_of_eigenpairs = matching_defaults().number_of_eigenpairs;
  bool use_intrinsic_delaunay = matching_defaults().use_intrinsic_delaunay;
  Descriptor_settings descriptors;
  Distance_oracle_type oracle = matching_defaults().distance_oracle;
  // The refinement only needs exact distances between candidates of neighbouring source vertices
  // (within about 2 r + 1 rings); anything farther costs far more than a mesh edge whatever its
  // exact value, so a smaller radius and a coarse landmark estimate suffice (and build 2-3x faster
  // than a general-purpose oracle).
  double local_radius_in_edge_lengths = matching_defaults().oracle_radius;
  int number_of_landmarks = matching_defaults().oracle_landmarks;
  /// Eigenpairs that the automatic initialisation needs (0: none): the shape solves for the larger
  /// of this and number_of_eigenpairs once, and the refinement's descriptors use the leading ones.
  int initialization_eigenpairs = 0;

  static Shape_settings from(const Matching_settings& m)
  {
    Shape_settings s;
    s.number_of_eigenpairs = m.number_of_eigenpairs;
    s.use_intrinsic_delaunay = m.use_intrinsic_delaunay;
    s.descriptors = Descriptor_settings::from(m);
    s.oracle = m.distance_oracle;
    s.local_radius_in_edge_lengths = m.oracle_radius;
    s.number_of_landmarks = m.oracle_landmarks;
    s.initialization_eigenpairs = m.initialization_number_of_eigenpairs > 0 ? m.initialization_number_of_eigenpairs
                                                                            : m.zoomout_final_size;
    return s;
  }
};

inline double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// Checks that `given` is a spectrum of `mesh` from which the first `k` eigenpairs can be taken
/// for settings `s`: same vertices, same vertex areas (internal::laplacian_mass(), which
/// intrinsic flips do not change), at least `k` eigenpairs, same operator.
inline void check_precomputed_spectrum(const Laplace_beltrami_spectrum& given, const Indexed_mesh& mesh, int k,
                                       const Shape_settings& s)
{
  const int n = mesh.number_of_vertices();
  const std::string what = "precomputed_spectrum: ";
  if(given.number_of_vertices() != n)
    throw Invalid_parameter_error(what + "a spectrum of " + std::to_string(given.number_of_vertices()) +
                                  " vertices for a mesh of " + std::to_string(n));
  if(given.number_of_eigenpairs() < k)
    throw Invalid_parameter_error(what + std::to_string(given.number_of_eigenpairs()) +
                                  " eigenpairs, fewer than the " + std::to_string(k) + " needed");
  if(given.uses_intrinsic_delaunay() != s.use_intrinsic_delaunay)
    throw Invalid_parameter_error(what + (given.uses_intrinsic_delaunay() ? "computed" : "not computed") +
                                  " on the intrinsic Delaunay triangulation, unlike use_intrinsic_delaunay");
  // The operators' own mass: of the mollified tufted cover on a mesh with faces of zero area.
  const Eigen::VectorXd area = internal::laplacian_mass(mesh);
  for(int v = 0; v < n; ++v)
    if(!(std::abs(given.mass()[v] - area[v]) <= 1e-9 * area[v] + 1e-12 * mesh.total_area))
      throw Invalid_parameter_error(what + "not a spectrum of this mesh (vertex " + std::to_string(v) +
                                    " has area " + std::to_string(area[v]) + ", mass " +
                                    std::to_string(given.mass()[v]) + " in the spectrum)");
}

/// Computes everything but the flat mesh, which `d.mesh` already holds. With `given`, the spectrum
/// is its first eigenpairs (check_precomputed_spectrum()) instead of a new eigensolve.
/// `shared_given`, when not null, is `given` owned elsewhere too: kept without a copy.
template <typename ConcurrencyTag>
void prepare_shape_data(Shape_data& d, const Shape_settings& s, const Eigen::MatrixXd& user_descriptors,
                        const Laplace_beltrami_spectrum* given = nullptr,
                        std::shared_ptr<const Laplace_beltrami_spectrum> shared_given = nullptr)
{
  auto t = std::chrono::steady_clock::now();
  const int n = d.mesh.number_of_vertices();
  d.scale = std::sqrt(d.mesh.total_area);
  d.compute_node_order();
  d.nearest.reset(new Nearest_vertex_search(d.mesh));
  d.times.mesh += seconds_since(t);

  t = std::chrono::steady_clock::now();
  const int k = std::min(s.number_of_eigenpairs, n - 1);
  // One eigensolve for the refinement and the initialisation when both use the intrinsic Delaunay
  // operator: the refinement takes the leading eigenpairs.
  const int solved = s.use_intrinsic_delaunay ? std::min(std::max(k, s.initialization_eigenpairs), n - 1) : k;
  if(given)
  {
    check_precomputed_spectrum(*given, d.mesh, k, s);
    d.spectrum.reset(new Laplace_beltrami_spectrum(*given, k));
    if(given->number_of_eigenpairs() > k)
      d.larger_spectrum =
          shared_given ? std::move(shared_given) : std::make_shared<const Laplace_beltrami_spectrum>(*given);
  }
  else if(solved > k)
  {
    d.larger_spectrum = std::make_shared<const Laplace_beltrami_spectrum>(d.mesh, parameters::number_of_eigenpairs(solved));
    d.spectrum.reset(new Laplace_beltrami_spectrum(*d.larger_spectrum, k));
  }
  else
    d.spectrum.reset(new Laplace_beltrami_spectrum(
        d.mesh, parameters::number_of_eigenpairs(k, parameters::use_intrinsic_delaunay(s.use_intrinsic_delaunay))));
  d.times.spectrum = seconds_since(t);

  t = std::chrono::steady_clock::now();
  d.descriptors = descriptor_stack<ConcurrencyTag>(d.mesh, *d.spectrum, s.descriptors, user_descriptors);
  d.times.descriptors = seconds_since(t);

  t = std::chrono::steady_clock::now();
  if(s.oracle == Distance_oracle_type::dense)
    d.oracle = Dense_distance_oracle::build<ConcurrencyTag>(d.mesh);
  else
  {
    const Edge_length_graph graph(d.mesh);
    d.oracle = Local_distance_oracle::build<ConcurrencyTag>(
        d.mesh, s.local_radius_in_edge_lengths * graph.mean_edge_length, s.number_of_landmarks);
  }
  d.times.distances = seconds_since(t);
}

} // namespace internal

namespace internal {

/// The vertex type of a shape's mesh: the FaceGraph's vertex descriptor, or the point index of a
/// Triangle_soup.
template <typename TriangleMesh>
struct Shape_vertex
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor type;
};
template <>
struct Shape_vertex<Triangle_soup>
{
  typedef std::size_t type;
};

/// Whether a shape is prepared for the automatic initialisation too (its spectrum with the
/// initialisation's eigenpairs, its descriptors): match_shapes() on meshes leaves it out when the
/// run does not need it.
struct Shape_preparation
{
  bool for_initialization = true;
};

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The precomputed data of one shape for matching: its flat copy, one Laplace-Beltrami spectrum
/// (the eigenpairs of the automatic initialisation, whose leading ones also make the refinement's
/// descriptors), the refinement's descriptor stack, the initialisation's descriptors, the geodesic
/// distance oracle and search structures. A shape matched against many others is prepared once
/// and passed to match_shapes() for every pair (the Heat_method_3 pattern of a class for the
/// precomputation and a function for the solve). Copies of a shape share all of this; a call with
/// other initialisation descriptor settings computes and keeps those (once, also under concurrent
/// calls).
///
/// Vertices are numbered by the mesh's vertex index map (named parameter `vertex_index_map`);
/// maps between prepared shapes are vectors of such indices (Vertex_index_map_vector).
///
/// \tparam TriangleMesh a model of `FaceListGraph` whose faces are triangles, or Triangle_soup
///   (points and index triples, needing no halfedge data structure: vertex i is point i)
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (descriptors and the
///   distance oracle are computed in parallel)
template <typename TriangleMesh, typename ConcurrencyTag = CGAL::Sequential_tag>
class Correspondence_shape
{
public:
  /// The mesh's vertex descriptor (`std::size_t`, the point index, for a Triangle_soup).
  typedef typename internal::Shape_vertex<TriangleMesh>::type vertex_descriptor;

  /// Prepares `tm`. The mesh must be a connected triangle mesh; boundaries, non-manifold edges
  /// and vertices and faces of zero area are handled (see irregularities()).
  /// \param tm the mesh (its geometry is copied into the shape)
  /// \param np optional named parameters:
  ///   - the settings of stage `preparation` (number_of_eigenpairs, use_intrinsic_delaunay, the
  ///     descriptor weights and parameters, distance_oracle, oracle_radius, oracle_landmarks) and
  ///     those of stage `initialization` that its spectrum and descriptors depend on, with
  ///     `matching_settings` (see Matching_settings and the settings table of the manual); pass the
  ///     same settings to match_shapes();
  ///   - `user_descriptor_map`: a readable property map from the vertices to a fixed-size range of
  ///     numbers, appended to the descriptor stack with `user_descriptor_weight`;
  ///   - `precomputed_spectrum` (a Laplace_beltrami_spectrum of `tm` with at least
  ///     `number_of_eigenpairs` eigenpairs and the same `use_intrinsic_delaunay`, best passed as
  ///     `std::cref(spectrum)` or as a `std::shared_ptr<const Laplace_beltrami_spectrum>`, which is
  ///     shared instead of copied): used instead of a new eigensolve; a spectrum of another mesh
  ///     (vertex count or areas) throws Invalid_parameter_error;
  ///   - `vertex_point_map`, `vertex_index_map` (not for a Triangle_soup).
  /// \param name the mesh's name in error messages (a Triangle_soup's own origin, when it has a
  ///   name, takes precedence)
  /// \throws Invalid_mesh_error (empty, non-triangle, a face repeating a vertex, NaN, isolated
  ///   vertex, several components, faces oriented inconsistently across a manifold edge, too few
  ///   vertices for the initialisation's basis), Invalid_parameter_error, Numerical_error
  template <typename NamedParameters = parameters::Default_named_parameters>
  explicit Correspondence_shape(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values(),
                                const std::string& name = "mesh")
      : Correspondence_shape(tm, np, internal::Shape_preparation(), name)
  {}

  /// As above; `preparation` says whether the shape is prepared for the initialisation.
  template <typename NamedParameters>
  Correspondence_shape(const TriangleMesh& tm, const NamedParameters& np, internal::Shape_preparation preparation,
                       const std::string& name)
      : data_(new internal::Shape_data)
  {
    const Matching_settings settings = Matching_settings::from(np);
    auto t = std::chrono::steady_clock::now();
    const internal::Mesh_requirements req = internal::shape_requirements();
    if constexpr(std::is_same<TriangleMesh, Triangle_soup>::value)
      data_->mesh = internal::make_soup_indexed_mesh(tm, req, name, &vertices_);
    else
      data_->mesh = internal::make_indexed_mesh(tm, np, req, name, &vertices_);
    data_->times.mesh = internal::seconds_since(t);
    internal::Shape_settings s = internal::Shape_settings::from(settings);
    if(!preparation.for_initialization) s.initialization_eigenpairs = 0;
    const internal::Initialization_settings init = internal::initialization_settings(settings);
    if(preparation.for_initialization && data_->mesh.number_of_vertices() <= std::max(init.zoomout_final_size,
                                                                 internal::initialization_number_of_eigenpairs(init)))
      throw Invalid_mesh_error(name + " has " + std::to_string(data_->mesh.number_of_vertices()) +
                               " vertices, too few for the automatic initialisation's basis of " +
                               std::to_string(init.zoomout_final_size) +
                               " eigenfunctions (reduce zoomout_final_size)");
    Eigen::MatrixXd user;
    const auto& user_map = parameters::get_parameter(np, internal_np::user_descriptor_map);
    if constexpr(!std::is_same<typename std::decay<decltype(user_map)>::type,
                               CGAL::internal_np::Param_not_found>::value)
      user = internal::read_user_descriptors(vertices_, user_map);
    const auto& given = parameters::get_parameter_reference(np, internal_np::precomputed_spectrum);
    if constexpr(std::is_same<typename std::decay<decltype(given)>::type, CGAL::internal_np::Param_not_found>::value)
      internal::prepare_shape_data<ConcurrencyTag>(*data_, s, user);
    else if constexpr(std::is_convertible<typename std::decay<decltype(given)>::type,
                                          std::shared_ptr<const Laplace_beltrami_spectrum>>::value)
    {
      if(!given) throw Invalid_parameter_error("precomputed_spectrum: a null pointer");
      internal::prepare_shape_data<ConcurrencyTag>(*data_, s, user, given.get(), given);
    }
    else
    {
      const Laplace_beltrami_spectrum& spectrum = given;
      internal::prepare_shape_data<ConcurrencyTag>(*data_, s, user, &spectrum);
    }
    if(preparation.for_initialization)
    {
      t = std::chrono::steady_clock::now();
      internal::Initialization_mesh_data d;
      internal::prepare_initialization_mesh<ConcurrencyTag>(data_->mesh, &data_->largest_spectrum(), init,
                                                            name.c_str(), d, data_->initialization.get());
      data_->times.initialization = internal::seconds_since(t);
    }
  }

  /// Number of vertices.
  std::size_t number_of_vertices() const { return vertices_.size(); }
  /// The vertex of index `i`.
  vertex_descriptor vertex(std::size_t i) const { return vertices_[i]; }
  /// All vertices, in index order.
  const std::vector<vertex_descriptor>& vertices() const { return vertices_; }
  /// The Laplace-Beltrami spectrum.
  const Laplace_beltrami_spectrum& spectrum() const { return *data_->spectrum; }
  /// The n x D descriptor stack (row i: vertex i), stored row-major.
  const Descriptor_matrix& descriptors() const { return data_->descriptors; }
  /// \f$\sqrt{\mathrm{area}}\f$: the unit in which the algorithms measure distances.
  double scale() const { return data_->scale; }
  /// Seconds spent on each preprocessing stage.
  const Shape_preprocessing_times& preprocessing_times() const { return data_->times; }
  /// What the input check found in the mesh beyond a manifold mesh of well-shaped triangles.
  Mesh_irregularities irregularities() const { return internal::mesh_irregularities(data_->mesh); }
  /// True when the dense distance oracle was built.
  bool has_dense_oracle() const { return std::holds_alternative<Dense_distance_oracle>(data_->oracle); }
  /// The index-based data (for the package's algorithms).
  const internal::Shape_data& data() const { return *data_; }

private:
  std::vector<vertex_descriptor> vertices_;
  std::shared_ptr<internal::Shape_data> data_;
};

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_CORRESPONDENCE_SHAPE_H
