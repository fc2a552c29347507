// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The shape pairs of test_pairs.h that need CGAL's isotropic remeshing and AABB tree: compiled
// once into the tests' support library instead of in every test file that includes the header.

#include "test_pairs.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

namespace smc_test {

Shape_pair deformed_pair(const Mesh& m1, const std::function<Point(const Point&)>& deform, bool remesh,
                         double target_edge)
{
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_traits<Kernel, Primitive> Traits;
  typedef CGAL::AABB_tree<Traits> Tree;
  Shape_pair p;
  p.m1 = m1;
  const Mesh bent = transformed(m1, deform);
  p.m2 = bent;
  if(remesh)
  {
    double edge = target_edge;
    if(edge <= 0)
    {
      double sum = 0;
      for(auto e : edges(bent)) sum += std::sqrt(CGAL::squared_distance(bent.point(source(e, bent)), bent.point(target(e, bent))));
      edge = sum / num_edges(bent);
    }
    CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(p.m2), edge, p.m2,
                                                       CGAL::parameters::number_of_iterations(3));
    p.m2.collect_garbage();
  }
  // gt_21: locate each vertex of M2 on the bent copy of M1, take the nearest corner of its face.
  Tree tree(faces(bent).first, faces(bent).second, bent);
  tree.accelerate_distance_queries();
  p.gt_21.resize(num_vertices(p.m2));
  for(Vertex w : p.m2.vertices())
  {
    const auto loc = CGAL::Polygon_mesh_processing::locate_with_AABB_tree(p.m2.point(w), tree, bent);
    Mesh::Halfedge_index h = halfedge(loc.first, bent);
    int best = 0;
    for(int c = 1; c < 3; ++c)
      if(loc.second[c] > loc.second[best]) best = c;
    for(int c = 0; c < best; ++c) h = next(h, bent);
    // locate's barycentric coordinates follow source(halfedge(f)), target(.), target(next(.))
    p.gt_21[w.idx()] = source(h, bent).idx();
  }
  // gt_12: the vertex of M2 nearest to the image of each vertex of M1 (brute force is fine at
  // test sizes).
  p.gt_12.resize(num_vertices(p.m1));
  for(Vertex v : p.m1.vertices())
  {
    const Point q = bent.point(v);
    double best = 1e300;
    for(Vertex w : p.m2.vertices())
    {
      const double d = CGAL::squared_distance(q, p.m2.point(w));
      if(d < best)
      {
        best = d;
        p.gt_12[v.idx()] = w.idx();
      }
    }
  }
  return p;
}

} // namespace smc_test
