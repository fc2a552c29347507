// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Small meshes that the tests build themselves (no data files): subdivided icosahedron spheres,
// flat grids, open and closed tubes, and helpers to bend, scale and move them.

#ifndef SMC_TEST_MESHES_H
#define SMC_TEST_MESHES_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace smc_test {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index Vertex;

inline const double pi = 3.14159265358979323846;
inline const double inf = std::numeric_limits<double>::infinity();

/// Builds a Surface_mesh from a triangle soup (consistently oriented).
inline Mesh mesh_from_soup(const std::vector<Point>& points,
                           const std::vector<std::array<int, 3> >& triangles)
{
  Mesh m;
  std::vector<Vertex> vs;
  vs.reserve(points.size());
  for(const Point& p : points) vs.push_back(m.add_vertex(p));
  for(const auto& t : triangles) m.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
  return m;
}

/// Unit sphere: an icosahedron subdivided `levels` times (4^levels * 20 triangles), vertices
/// projected to the sphere. levels = 0, 1, 2, 3, 4 give 12, 42, 162, 642, 2562 vertices.
inline Mesh icosphere(int levels, double radius = 1.0)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3> > p = {
      {-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3> > f = {
      {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  auto normalize = [](std::array<double, 3>& a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for(double& c : a) c /= l;
  };
  for(auto& a : p) normalize(a);
  for(int level = 0; level < levels; ++level)
  {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      std::pair<int, int> key(std::min(a, b), std::max(a, b));
      auto it = midpoint.find(key);
      if(it != midpoint.end()) return it->second;
      std::array<double, 3> m = {(p[a][0] + p[b][0]) / 2, (p[a][1] + p[b][1]) / 2,
                                 (p[a][2] + p[b][2]) / 2};
      normalize(m);
      p.push_back(m);
      const int id = static_cast<int>(p.size()) - 1;
      midpoint[key] = id;
      return id;
    };
    std::vector<std::array<int, 3> > g;
    for(const auto& tri : f)
    {
      const int a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  std::vector<Point> pts;
  for(const auto& a : p) pts.emplace_back(radius * a[0], radius * a[1], radius * a[2]);
  return mesh_from_soup(pts, f);
}

/// Flat grid of (nx+1) x (ny+1) vertices covering [0, sx] x [0, sy] in the z = 0 plane; each
/// square is split along alternating diagonals.
inline Mesh grid(int nx, int ny, double sx = 1.0, double sy = 1.0)
{
  std::vector<Point> pts;
  for(int j = 0; j <= ny; ++j)
    for(int i = 0; i <= nx; ++i) pts.emplace_back(sx * i / nx, sy * j / ny, 0.0);
  std::vector<std::array<int, 3> > tris;
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for(int j = 0; j < ny; ++j)
    for(int i = 0; i < nx; ++i)
    {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if((i + j) % 2 == 0)
      {
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
      }
      else
      {
        tris.push_back({a, b, d});
        tris.push_back({b, c, d});
      }
    }
  return mesh_from_soup(pts, tris);
}

/// Open cylinder (tube) of radius r and length `length` along z, with `nu` vertices around and
/// `nv` + 1 rings along its axis. Rings are staggered by half a step to make good triangles.
inline Mesh tube(int nu, int nv, double r = 1.0, double length = 4.0)
{
  std::vector<Point> pts;
  for(int j = 0; j <= nv; ++j)
    for(int i = 0; i < nu; ++i)
    {
      const double a = 2 * pi * (i + 0.5 * (j % 2)) / nu;
      pts.emplace_back(r * std::cos(a), r * std::sin(a), length * j / nv);
    }
  std::vector<std::array<int, 3> > tris;
  auto id = [&](int i, int j) { return j * nu + ((i % nu) + nu) % nu; };
  for(int j = 0; j < nv; ++j)
    for(int i = 0; i < nu; ++i)
    {
      if(j % 2 == 0)
      {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
      else
      {
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      }
    }
  return mesh_from_soup(pts, tris);
}

/// Closed capsule: a tube of radius r along z from 0 to `length`, capped with hemispheres,
/// triangulated by latitude/longitude rings (poles are single vertices).
inline Mesh capsule(int nu, int n_cap, int n_body, double r = 1.0, double length = 4.0)
{
  std::vector<double> zs, rs;  // ring heights and radii, from the bottom pole up (poles excluded)
  for(int k = 1; k <= n_cap; ++k)
  {
    const double a = -pi / 2 + (pi / 2) * k / n_cap;
    zs.push_back(r * std::sin(a));
    rs.push_back(r * std::cos(a));
  }
  for(int k = 1; k < n_body; ++k)
  {
    zs.push_back(length * k / n_body);
    rs.push_back(r);
  }
  for(int k = 0; k < n_cap; ++k)
  {
    const double a = (pi / 2) * k / n_cap;
    zs.push_back(length + r * std::sin(a));
    rs.push_back(r * std::cos(a));
  }
  std::vector<Point> pts;
  pts.emplace_back(0, 0, -r);
  const int rings = static_cast<int>(zs.size());
  for(int j = 0; j < rings; ++j)
    for(int i = 0; i < nu; ++i)
    {
      const double a = 2 * pi * (i + 0.5 * (j % 2)) / nu;
      pts.emplace_back(rs[j] * std::cos(a), rs[j] * std::sin(a), zs[j]);
    }
  pts.emplace_back(0, 0, length + r);
  const int top = static_cast<int>(pts.size()) - 1;
  auto id = [&](int i, int j) { return 1 + j * nu + ((i % nu) + nu) % nu; };
  std::vector<std::array<int, 3> > tris;
  for(int i = 0; i < nu; ++i) tris.push_back({0, id(i + 1, 0), id(i, 0)});
  for(int j = 0; j + 1 < rings; ++j)
    for(int i = 0; i < nu; ++i)
    {
      if(j % 2 == 0)
      {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
      else
      {
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      }
    }
  for(int i = 0; i < nu; ++i) tris.push_back({top, id(i, rings - 1), id(i + 1, rings - 1)});
  return mesh_from_soup(pts, tris);
}

/// Applies `f` to every vertex position of `m` (returns a modified copy).
inline Mesh transformed(const Mesh& m, const std::function<Point(const Point&)>& f)
{
  Mesh out = m;
  for(Vertex v : out.vertices()) out.point(v) = f(out.point(v));
  return out;
}

/// Isometric bend of a shape lying along the z axis: the segment z in [0, length] is wrapped
/// onto a circular arc of the given angle in the x-z plane (the x coordinate is kept as the
/// signed distance from the arc). Exactly isometric for a flat strip in the y-z plane (x = 0),
/// near-isometric for thin tubes.
inline Point bend_point(const Point& p, double length, double angle)
{
  if(angle == 0) return p;
  const double R = length / angle;  // radius of the arc the axis is bent onto
  const double theta = p.z() / R;
  const double rr = R - p.x();
  return Point(R - rr * std::cos(theta), p.y(), rr * std::sin(theta));
}

/// Unit icosphere whose vertices are rotated about the z axis by `angle` * z: the surface is
/// still the unit sphere but the triangles are sheared into long, obtuse ones (a mesh on which
/// the plain cotangent Laplacian is inaccurate; used by the intrinsic Delaunay tests).
inline Mesh twisted_sphere(int levels, double angle)
{
  return transformed(icosphere(levels), [angle](const Point& p) {
    const double a = angle * p.z(), c = std::cos(a), s = std::sin(a);
    return Point(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
  });
}

/// Unit icosphere with every vertex moved randomly (a fixed pseudo-random sequence in vertex
/// order, up to `amount` times the edge length in each coordinate) and projected back onto the
/// sphere.
inline Mesh jittered_sphere(int levels, double amount)
{
  const double edge = 1.1 / std::pow(2.0, levels);
  unsigned state = 12345u;
  auto next = [&state]() {  // a small LCG: identical on every platform
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (2.0 / 16777216.0) - 1.0;  // in [-1, 1)
  };
  return transformed(icosphere(levels), [&](const Point& p) {
    const double x = p.x() + amount * edge * next(), y = p.y() + amount * edge * next(),
                 z = p.z() + amount * edge * next();
    const double l = std::sqrt(x * x + y * y + z * z);
    return Point(x / l, y / l, z / l);
  });
}

/// Flat grid of (nx+1) x (ny+1) vertices on [0, sx] x [0, sy] whose squares are all split along
/// the same diagonal: every interior vertex has valence 6 (a regular triangulation up to shear).
/// Vertex (i, j) has index j * (nx + 1) + i. When `hole` is true, the faces of the squares with
/// nx/3 <= i < 2nx/3 and ny/3 <= j < 2ny/3 are left out (a grid with a hole), and the vertices
/// left without a face are dropped (the others keep their order).
inline Mesh regular_grid(int nx, int ny, double sx = 1.0, double sy = 1.0, bool hole = false)
{
  std::vector<Point> pts;
  for(int j = 0; j <= ny; ++j)
    for(int i = 0; i <= nx; ++i) pts.emplace_back(sx * i / nx, sy * j / ny, 0.0);
  std::vector<std::array<int, 3> > tris;
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for(int j = 0; j < ny; ++j)
    for(int i = 0; i < nx; ++i)
    {
      if(hole && 3 * i >= nx && 3 * i < 2 * nx && 3 * j >= ny && 3 * j < 2 * ny) continue;
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::vector<int> used(pts.size(), -1);
  for(const auto& t : tris)
    for(int v : t) used[v] = 0;
  std::vector<Point> kept;
  for(std::size_t v = 0; v < pts.size(); ++v)
    if(used[v] == 0)
    {
      used[v] = static_cast<int>(kept.size());
      kept.push_back(pts[v]);
    }
  for(auto& t : tris)
    for(int& v : t) v = used[v];
  return mesh_from_soup(kept, tris);
}

/// The disjoint union of two meshes (the vertices of `b` come after those of `a`).
inline Mesh disjoint_union(const Mesh& a, const Mesh& b)
{
  Mesh out = a;
  std::map<Vertex, Vertex> to;
  for(Vertex v : b.vertices()) to[v] = out.add_vertex(b.point(v));
  for(auto f : b.faces())
  {
    std::vector<Vertex> vs;
    for(Vertex v : b.vertices_around_face(b.halfedge(f))) vs.push_back(to[v]);
    out.add_face(vs);
  }
  return out;
}

/// The message of the exception of type E (default: any of the package's) that f() throws;
/// "wrong exception: ..." for another exception, "no exception" when it returns.
template <typename E = CGAL::Surface_mesh_correspondence::Error, typename F>
std::string error_of(F&& f)
{
  try
  {
    f();
  }
  catch(const E& e)
  {
    return e.what();
  }
  catch(const std::exception& e)
  {
    return std::string("wrong exception: ") + e.what();
  }
  return "no exception";
}

/// A flat mesh of `points` and `triangles`, non-manifold edges and vertices allowed (and faces of
/// zero area with `allow_degenerate_faces`).
inline CGAL::Surface_mesh_correspondence::internal::Indexed_mesh soup_mesh(const std::vector<Eigen::Vector3d>& points,
                                      const std::vector<std::array<int, 3> >& triangles,
                                      bool allow_degenerate_faces = false)
{
  CGAL::Surface_mesh_correspondence::internal::Indexed_mesh m;
  m.points.resize(Eigen::Index(points.size()), 3);
  for(std::size_t i = 0; i < points.size(); ++i) m.points.row(Eigen::Index(i)) = points[i].transpose();
  m.triangles.resize(Eigen::Index(triangles.size()), 3);
  for(std::size_t f = 0; f < triangles.size(); ++f)
    for(int c = 0; c < 3; ++c) m.triangles(Eigen::Index(f), c) = triangles[f][std::size_t(c)];
  CGAL::Surface_mesh_correspondence::internal::Mesh_requirements req;
  req.allow_non_manifold = true;
  req.allow_degenerate_faces = allow_degenerate_faces;
  CGAL::Surface_mesh_correspondence::internal::finalize_indexed_mesh(m, req, "soup");
  return m;
}

/// An open book: `pages` unit squares sharing the spine {(0, 0, z), z in [0, 1]}, page p at
/// angle 2 pi p / pages about the spine (or at `angles` when given), each an n x n grid split
/// into right triangles. Every spine edge is shared by `pages` triangles. `offset` moves the
/// book along x.
inline void add_book(int pages, int n, std::vector<Eigen::Vector3d>& points, std::vector<std::array<int, 3> >& triangles,
              double offset = 0, std::vector<double> angles = {})
{
  const int first = int(points.size());
  for(int k = 0; k <= n; ++k) points.emplace_back(offset, 0, double(k) / n);  // the spine
  for(int p = 0; p < pages; ++p)
  {
    const double a = angles.empty() ? 2 * CGAL_PI * p / pages : angles[std::size_t(p)];
    const int base = int(points.size());
    for(int r = 1; r <= n; ++r)
      for(int k = 0; k <= n; ++k)
        points.emplace_back(offset + std::cos(a) * r / n, std::sin(a) * r / n, double(k) / n);
    auto vertex = [&](int r, int k) { return r == 0 ? first + k : base + (r - 1) * (n + 1) + k; };
    for(int r = 0; r < n; ++r)
      for(int k = 0; k < n; ++k)
      {
        triangles.push_back({{vertex(r, k), vertex(r + 1, k), vertex(r + 1, k + 1)}});
        triangles.push_back({{vertex(r, k), vertex(r + 1, k + 1), vertex(r, k + 1)}});
      }
  }
}

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

} // namespace smc_test

#endif // SMC_TEST_MESHES_H
