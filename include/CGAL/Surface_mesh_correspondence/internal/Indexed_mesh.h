// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A flat, index-based copy of a triangle mesh (vertex positions, triangles, one-ring adjacency,
// vertex-face incidence, edges, components), built once from any CGAL FaceGraph and validated.
// All numerical code of the package runs on this structure: contiguous arrays are fast, and the
// generic layer (FaceGraph + property maps) only has to translate at the entry and exit points.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INDEXED_MESH_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INDEXED_MESH_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// What a caller accepts from a mesh beyond the basic requirements (non-empty, triangles of three
/// distinct vertices, finite coordinates), which are always checked. By default the mesh must also
/// be manifold, without isolated vertices or faces of zero area.
struct Mesh_requirements
{
  bool allow_isolated_vertices = false;
  bool allow_several_components = true;
  bool allow_boundary = true;
  /// Edges in more than two triangles and vertices joining several fans of triangles (what the
  /// tufted Laplacian handles); the neighbours are then the vertices sharing an edge.
  bool allow_non_manifold = false;
  /// Faces of (nearly) zero area with three distinct vertices, e.g. collinear ones (what the
  /// mollified tufted Laplacian handles); their area is then kept as computed.
  bool allow_degenerate_faces = false;
};

/// Flat copy of a triangle mesh. Vertex indices are those of the mesh's vertex index map.
struct Indexed_mesh
{
  typedef Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Points;
  typedef Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> Triangles;

  Points points;       ///< n x 3 vertex positions
  Triangles triangles; ///< f x 3 vertex indices, counter-clockwise as in the input mesh

  /// One-ring neighbours of vertex v: neighbors[neighbor_offsets[v] .. neighbor_offsets[v+1]),
  /// sorted by increasing index.
  std::vector<int> neighbor_offsets, neighbors;
  /// Triangles incident to vertex v: incident_triangles[triangle_offsets[v] .. triangle_offsets[v+1]).
  std::vector<int> triangle_offsets, incident_triangles;
  /// Undirected edges (i < j), sorted lexicographically.
  std::vector<std::array<int, 2> > edges;
  /// Connected component of each vertex (0-based), and their number.
  std::vector<int> component;
  int number_of_components = 0;
  /// Number of boundary edges (edges with a single incident triangle).
  int number_of_boundary_edges = 0;
  /// Total surface area and the area of each triangle.
  double total_area = 0;
  std::vector<double> triangle_areas;
  /// What the mesh has beyond a manifold mesh of well-shaped triangles, when its requirements
  /// allow it (Mesh_requirements): edges in more than two triangles (i < j, sorted), vertices
  /// joining several separate fans of triangles (sorted), and faces of (nearly) zero area.
  std::vector<std::array<int, 2> > non_manifold_edges;
  std::vector<int> non_manifold_vertices;
  std::vector<int> degenerate_faces;

  int number_of_vertices() const { return static_cast<int>(points.rows()); }
  int number_of_triangles() const { return static_cast<int>(triangles.rows()); }
  int number_of_edges() const { return static_cast<int>(edges.size()); }
  int degree(int v) const { return neighbor_offsets[v + 1] - neighbor_offsets[v]; }
  const int* neighbors_begin(int v) const { return neighbors.data() + neighbor_offsets[v]; }
  const int* neighbors_end(int v) const { return neighbors.data() + neighbor_offsets[v + 1]; }
  Eigen::Vector3d point(int v) const { return points.row(v).transpose(); }
  bool has_boundary() const { return number_of_boundary_edges > 0; }
  /// Whether the mesh is manifold (no non-manifold edge or vertex).
  bool is_manifold() const { return non_manifold_edges.empty() && non_manifold_vertices.empty(); }
  /// Whether the operators need the tufted cover (non-manifold) or mollification (degenerate
  /// faces): see tufted_laplace_beltrami_matrices().
  bool needs_tufted_cover() const { return !is_manifold() || !degenerate_faces.empty(); }
};

inline std::string mesh_label(const std::string& name)
{
  return name.empty() ? std::string("mesh") : name;
}

/// The root of x in a union-find forest, with path halving.
inline int union_find_root(std::vector<int>& parent, int x)
{
  while(parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/// Checks that the mesh has vertices and faces and that all coordinates are finite.
inline void check_indexed_mesh_points(const Indexed_mesh& m, const std::string& label)
{
  const int n = m.number_of_vertices();
  const int nf = m.number_of_triangles();
  if(n == 0 || nf == 0)
    throw Invalid_mesh_error(label + " is empty (" + std::to_string(n) + " vertices, " +
                             std::to_string(nf) + " faces)");
  for(int v = 0; v < n; ++v)
    for(int c = 0; c < 3; ++c)
      if(!std::isfinite(m.points(v, c)))
        throw Invalid_mesh_error(label + ": vertex " + std::to_string(v) +
                                 " has a non-finite coordinate (NaN or infinity)");
}

/// Fills the incident triangles of the vertices (CSR), checking the faces' vertex indices.
inline void fill_incident_triangles(Indexed_mesh& m, const std::string& label)
{
  const int n = m.number_of_vertices();
  const int nf = m.number_of_triangles();
  m.triangle_offsets.assign(n + 1, 0);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int v = m.triangles(f, c);
      if(v < 0 || v >= n)
        throw Invalid_mesh_error(label + ": face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + ", out of range");
      ++m.triangle_offsets[v + 1];
    }
  std::partial_sum(m.triangle_offsets.begin(), m.triangle_offsets.end(), m.triangle_offsets.begin());
  m.incident_triangles.resize(m.triangle_offsets[n]);
  std::vector<int> fill(m.triangle_offsets.begin(), m.triangle_offsets.end() - 1);
  for(int f = 0; f < nf; ++f)
    for(int c = 0; c < 3; ++c)
      m.incident_triangles[fill[m.triangles(f, c)]++] = f;
}

/// Fills the triangle areas and the total area, rejecting faces that repeat a vertex or have zero
/// area.
inline void fill_triangle_areas(Indexed_mesh& m, const std::string& label, bool allow_degenerate = false)
{
  const int nf = m.number_of_triangles();
  m.triangle_areas.resize(nf);
  m.degenerate_faces.clear();
  m.total_area = 0;
  for(int f = 0; f < nf; ++f)
  {
    const int a = m.triangles(f, 0), b = m.triangles(f, 1), c = m.triangles(f, 2);
    if(a == b || b == c || a == c)
      throw Invalid_mesh_error(label + ": face " + std::to_string(f) + " repeats a vertex");
    const Eigen::Vector3d e1 = m.point(b) - m.point(a), e2 = m.point(c) - m.point(a),
                          e3 = m.point(c) - m.point(b);
    const double twice_area = e1.cross(e2).norm();
    const double longest2 = std::max(e1.squaredNorm(), std::max(e2.squaredNorm(), e3.squaredNorm()));
    if(!(twice_area > 1e-12 * longest2))
    {
      if(!allow_degenerate)
        throw Invalid_mesh_error(label + ": face " + std::to_string(f) + " is degenerate (zero area)");
      m.degenerate_faces.push_back(f);
    }
    m.triangle_areas[f] = 0.5 * twice_area;
    m.total_area += m.triangle_areas[f];
  }
}

/// The number of connected groups into which the link edges of a vertex (the opposite edges of
/// its triangles) join its neighbours `unique_ring` (sorted): 1 unless the vertex is pinched.
inline int link_groups(const std::vector<std::array<int, 2> >& link, const std::vector<int>& unique_ring)
{
  const int degree = static_cast<int>(unique_ring.size());
  std::vector<int> parent(degree);
  std::iota(parent.begin(), parent.end(), 0);
  auto local = [&](int w) {
    return static_cast<int>(std::lower_bound(unique_ring.begin(), unique_ring.end(), w) -
                            unique_ring.begin());
  };
  int groups = degree;
  for(const auto& e : link)
  {
    const int ra = union_find_root(parent, local(e[0])), rb = union_find_root(parent, local(e[1]));
    if(ra != rb)
    {
      parent[ra] = rb;
      --groups;
    }
  }
  return groups;
}

/// Throws unless the link edges of vertex v join all its neighbours `unique_ring` (sorted) into
/// one path or cycle: else v is a pinched, non-manifold vertex.
inline void check_link_connected(int v, const std::vector<std::array<int, 2> >& link,
                                 const std::vector<int>& unique_ring, const std::string& label)
{
  if(link_groups(link, unique_ring) != 1)
    throw Invalid_mesh_error(label + " is not manifold: vertex " + std::to_string(v) +
                             " joins several separate fans of faces");
}

/// The neighbours of vertex v (not isolated), sorted, into `unique_ring`, checked for
/// manifoldness: each appears once (boundary edge, counted in `boundary_edges2`) or twice
/// (interior edge) in the link of v, and the link is connected. With `non_manifold` (the mesh whose
/// requirements allow non-manifold meshes), what fails these checks is recorded there instead:
/// the edges (v, w > v) in more than two triangles and v when its link is not connected. `ring`
/// and `link` are workspaces.
inline void vertex_one_ring(const Indexed_mesh& m, int v, const std::string& label, std::vector<int>& ring,
                            std::vector<std::array<int, 2> >& link, std::vector<int>& unique_ring,
                            int& boundary_edges2, Indexed_mesh* non_manifold = nullptr)
{
  ring.clear();
  link.clear();
  for(int k = m.triangle_offsets[v]; k < m.triangle_offsets[v + 1]; ++k)
  {
    const int f = m.incident_triangles[k];
    int c = 0;
    while(m.triangles(f, c) != v) ++c;
    const int a = m.triangles(f, (c + 1) % 3), b = m.triangles(f, (c + 2) % 3);
    link.push_back({a, b});
    ring.push_back(a);
    ring.push_back(b);
  }
  std::sort(ring.begin(), ring.end());
  // Each neighbour appears once (boundary) or twice (interior) in the link.
  for(std::size_t k = 0; k < ring.size();)
  {
    std::size_t e = k;
    while(e < ring.size() && ring[e] == ring[k]) ++e;
    const std::size_t multiplicity = e - k;
    if(multiplicity > 2 && non_manifold)
    {
      if(v < ring[k]) non_manifold->non_manifold_edges.push_back({v, ring[k]});
    }
    else if(multiplicity > 2)
      throw Invalid_mesh_error(label + " is not manifold: the edge (" + std::to_string(v) + ", " +
                               std::to_string(ring[k]) + ") is shared by " + std::to_string(multiplicity) +
                               " faces");
    if(multiplicity == 1) ++boundary_edges2;
    unique_ring.push_back(ring[k]);
    k = e;
  }
  // The link must be connected (else v is a pinched, non-manifold vertex).
  if(!non_manifold)
    check_link_connected(v, link, unique_ring, label);
  else if(link_groups(link, unique_ring) != 1)
    non_manifold->non_manifold_vertices.push_back(v);
}

/// Fills the one-ring neighbours (CSR) and the number of boundary edges. Manifoldness: around
/// every vertex, the opposite edges of its triangles (its link) must form a single path or cycle
/// in which no vertex appears more than twice.
inline void fill_neighbors(Indexed_mesh& m, const Mesh_requirements& req, const std::string& label)
{
  const int n = m.number_of_vertices();
  m.neighbor_offsets.assign(n + 1, 0);
  m.non_manifold_edges.clear();
  m.non_manifold_vertices.clear();
  std::vector<int> ring;                    // neighbours of v, with multiplicity
  std::vector<std::array<int, 2> > link;    // link edges of v
  std::vector<std::vector<int> > rings(n);
  int boundary_edges2 = 0;                  // counts each boundary edge twice (once per endpoint)
  for(int v = 0; v < n; ++v)
  {
    if(m.triangle_offsets[v] == m.triangle_offsets[v + 1])
    {
      if(!req.allow_isolated_vertices)
        throw Invalid_mesh_error(label + ": vertex " + std::to_string(v) +
                                 " is isolated (it belongs to no face)");
      continue;
    }
    vertex_one_ring(m, v, label, ring, link, rings[v], boundary_edges2, req.allow_non_manifold ? &m : nullptr);
    m.neighbor_offsets[v + 1] = static_cast<int>(rings[v].size());
  }
  std::partial_sum(m.neighbor_offsets.begin(), m.neighbor_offsets.end(), m.neighbor_offsets.begin());
  m.neighbors.resize(m.neighbor_offsets[n]);
  for(int v = 0; v < n; ++v)
    std::copy(rings[v].begin(), rings[v].end(), m.neighbors.begin() + m.neighbor_offsets[v]);
  m.number_of_boundary_edges = boundary_edges2 / 2;
  if(!req.allow_boundary && m.number_of_boundary_edges > 0)
    throw Invalid_mesh_error(label + " has a boundary (" + std::to_string(m.number_of_boundary_edges) +
                             " boundary edges) but a closed mesh is required");
}

/// Fills the undirected edges (i < j), sorted lexicographically.
inline void fill_edges(Indexed_mesh& m)
{
  const int n = m.number_of_vertices();
  m.edges.clear();
  m.edges.reserve(m.neighbors.size() / 2);
  for(int v = 0; v < n; ++v)
    for(const int* w = m.neighbors_begin(v); w != m.neighbors_end(v); ++w)
      if(v < *w) m.edges.push_back({v, *w});
}

/// Fills the connected components (union-find over the edges, numbered by their first vertex).
inline void fill_components(Indexed_mesh& m, const Mesh_requirements& req, const std::string& label)
{
  const int n = m.number_of_vertices();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for(const auto& e : m.edges)
  {
    const int a = union_find_root(parent, e[0]), b = union_find_root(parent, e[1]);
    if(a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  m.component.assign(n, -1);
  m.number_of_components = 0;
  std::vector<int> root_label(n, -1);
  for(int v = 0; v < n; ++v)
  {
    const int r = union_find_root(parent, v);
    if(root_label[r] < 0) root_label[r] = m.number_of_components++;
    m.component[v] = root_label[r];
  }
  if(!req.allow_several_components && m.number_of_components > 1)
    throw Invalid_mesh_error(label + " has " + std::to_string(m.number_of_components) +
                             " connected components but a connected mesh is required (keep the "
                             "largest one, e.g. with "
                             "CGAL::Polygon_mesh_processing::keep_largest_connected_components)");
}

/// Fills adjacency, incidence, edges, areas and components from `points` and `triangles`, and
/// checks the mesh. Throws Invalid_mesh_error naming the first problem found.
inline void finalize_indexed_mesh(Indexed_mesh& m, const Mesh_requirements& req,
                                  const std::string& name = "mesh")
{
  const std::string label = mesh_label(name);
  check_indexed_mesh_points(m, label);
  fill_incident_triangles(m, label);
  fill_triangle_areas(m, label, req.allow_degenerate_faces);
  fill_neighbors(m, req, label);
  fill_edges(m);
  fill_components(m, req, label);
}

/// For every triangle, whether it has a well-defined orientation and gradient: not degenerate
/// (zero area) and no edge shared with more than one other triangle (the side of a fin, or of two
/// sheets touching along an edge, is arbitrary). Orientation-aware operators leave out the others.
inline std::vector<char> oriented_triangles(const Indexed_mesh& m)
{
  std::vector<char> oriented(std::size_t(m.number_of_triangles()), 1);
  for(int f : m.degenerate_faces) oriented[std::size_t(f)] = 0;
  if(!m.non_manifold_edges.empty())
    for(int f = 0; f < m.number_of_triangles(); ++f)
      for(int c = 0; c < 3; ++c)
      {
        const int a = m.triangles(f, c), b = m.triangles(f, (c + 1) % 3);
        const std::array<int, 2> e{{std::min(a, b), std::max(a, b)}};
        if(std::binary_search(m.non_manifold_edges.begin(), m.non_manifold_edges.end(), e))
          oriented[std::size_t(f)] = 0;
      }
  return oriented;
}

/// Builds and checks the flat copy of `tm`. Vertex i of the copy is the vertex whose index in the
/// vertex index map (named parameter `vertex_index_map`, default the mesh's own, initialised if
/// needed) is i; positions come from `vertex_point_map`. When `vertices_out` is given it receives
/// the vertex descriptors in index order.
template <typename TriangleMesh, typename NamedParameters = CGAL::parameters::Default_named_parameters>
Indexed_mesh make_indexed_mesh(
    const TriangleMesh& tm, const NamedParameters& np = CGAL::parameters::default_values(),
    const Mesh_requirements& req = Mesh_requirements(), const std::string& name = "mesh",
    std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>* vertices_out = nullptr)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;

  const std::string label = mesh_label(name);
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                              get_const_property_map(CGAL::vertex_point, tm));
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);

  Indexed_mesh m;
  const std::size_t n = static_cast<std::size_t>(num_vertices(tm));
  m.points.resize(static_cast<Eigen::Index>(n), 3);
  std::vector<vertex_descriptor> order(n);
  std::vector<char> seen(n, 0);
  for(vertex_descriptor v : vertices(tm))
  {
    const std::size_t i = static_cast<std::size_t>(get(vim, v));
    if(i >= n || seen[i])
      throw Invalid_mesh_error(label + ": the vertex index map is not a bijection onto [0, " +
                               std::to_string(n) + ")");
    seen[i] = 1;
    order[i] = v;
    const auto& p = get(vpm, v);
    m.points(static_cast<Eigen::Index>(i), 0) = CGAL::to_double(p.x());
    m.points(static_cast<Eigen::Index>(i), 1) = CGAL::to_double(p.y());
    m.points(static_cast<Eigen::Index>(i), 2) = CGAL::to_double(p.z());
  }
  std::vector<std::array<int, 3> > tris;
  tris.reserve(static_cast<std::size_t>(num_faces(tm)));
  std::size_t face_number = 0;
  for(auto f : faces(tm))
  {
    std::array<int, 3> t{{0, 0, 0}};
    std::size_t k = 0;
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, tm), tm))
    {
      if(k < 3) t[k] = static_cast<int>(get(vim, target(h, tm)));
      ++k;
    }
    if(k != 3)
      throw Invalid_mesh_error(label + ": face " + std::to_string(face_number) + " has " +
                               std::to_string(k) +
                               " vertices; only triangle meshes are supported (triangulate it "
                               "first, e.g. with CGAL::Polygon_mesh_processing::triangulate_faces)");
    tris.push_back(t);
    ++face_number;
  }
  m.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for(std::size_t f = 0; f < tris.size(); ++f)
    for(int c = 0; c < 3; ++c) m.triangles(static_cast<Eigen::Index>(f), c) = tris[f][c];
  finalize_indexed_mesh(m, req, label);
  if(vertices_out) vertices_out->swap(order);
  return m;
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INDEXED_MESH_H
