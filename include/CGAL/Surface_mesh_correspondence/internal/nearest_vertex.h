// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Euclidean nearest-vertex queries on an Indexed_mesh (CGAL's Kd_tree), used by the inverse-map
// construction of the coupled refinement (the vertex nearest to the mean of the preimages).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_VERTEX_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_VERTEX_H

#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <boost/tuple/tuple.hpp>

#include <memory>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Nearest mesh vertex to a query point. Queries are thread-safe once constructed.
class Nearest_vertex_search
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef K::Point_3 Point;
  typedef boost::tuple<Point, int> Point_and_index;
  typedef CGAL::Search_traits_adapter<Point_and_index, CGAL::Nth_of_tuple_property_map<0, Point_and_index>,
                                      CGAL::Search_traits_3<K> >
      Traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
  typedef Search::Tree Tree;

public:
  explicit Nearest_vertex_search(const Indexed_mesh& m)
  {
    std::vector<Point_and_index> points;
    points.reserve(static_cast<std::size_t>(m.number_of_vertices()));
    for(int v = 0; v < m.number_of_vertices(); ++v)
      if(m.triangle_offsets[v + 1] > m.triangle_offsets[v])  // skip isolated vertices
        points.emplace_back(Point(m.points(v, 0), m.points(v, 1), m.points(v, 2)), v);
    tree_.reset(new Tree(points.begin(), points.end()));
    tree_->build();
  }

  /// Index of the vertex nearest to (x, y, z).
  int nearest(double x, double y, double z) const
  {
    Search search(*tree_, Point(x, y, z), 1);
    return boost::get<1>(search.begin()->first);
  }

private:
  std::unique_ptr<Tree> tree_;
};

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEAREST_VERTEX_H
