// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The damage that remeshers and scanners do to a clean triangle mesh, made on purpose: a fin
// triangle on an edge, two touching sheets merged into an edge of four faces, a pinched (bow-tie)
// vertex, faces of zero area. Each function takes a clean mesh as a triangle soup and returns the
// damaged soup with the correspondence between the two vertex sets, so that maps computed on the
// damaged mesh can be evaluated against the clean mesh's ground truth. Used by the unit tests on
// small generated meshes and by benchmark/bench_damaged.cpp on FAUST_r shapes.

#ifndef SMC_TEST_DAMAGED_MESHES_H
#define SMC_TEST_DAMAGED_MESHES_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>

namespace smc_damage {

typedef std::array<double, 3> Vec;

struct Soup
{
  std::vector<Vec> points;
  std::vector<std::array<int, 3> > triangles;
};

/// The soup of anything with points() and triangles() of these types (a Triangle_soup).
template <typename TriangleSoup>
Soup soup_of(const TriangleSoup& s)
{
  Soup out;
  out.points.assign(s.points().begin(), s.points().end());
  out.triangles.assign(s.triangles().begin(), s.triangles().end());
  return out;
}

/// A damaged mesh and its correspondence with the clean one.
struct Damaged
{
  Soup soup;
  std::vector<int> to_clean;    ///< damaged vertex -> clean vertex (a new vertex: a clean one beside it)
  std::vector<int> from_clean;  ///< clean vertex -> damaged vertex (a merged vertex: the one it became)
  std::string what;             ///< a description: which vertices, edges or faces
};

inline Vec sub(const Vec& a, const Vec& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline Vec add(const Vec& a, const Vec& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline Vec mul(double s, const Vec& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
inline double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec cross(const Vec& a, const Vec& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

inline Damaged undamaged(const Soup& clean)
{
  Damaged d;
  d.soup = clean;
  d.to_clean.resize(clean.points.size());
  for(std::size_t v = 0; v < clean.points.size(); ++v) d.to_clean[v] = int(v);
  d.from_clean = d.to_clean;
  return d;
}

/// The vertex neighbours of every vertex (sharing a triangle), sorted.
inline std::vector<std::vector<int> > vertex_neighbors(const Soup& s)
{
  std::vector<std::vector<int> > nb(s.points.size());
  for(const auto& t : s.triangles)
    for(int c = 0; c < 3; ++c)
    {
      nb[std::size_t(t[std::size_t(c)])].push_back(t[std::size_t((c + 1) % 3)]);
      nb[std::size_t(t[std::size_t(c)])].push_back(t[std::size_t((c + 2) % 3)]);
    }
  for(auto& r : nb)
  {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  return nb;
}

/// (a) A fin: a new triangle on the edge (i, j) of `face` (its first edge), standing out of the
/// surface along the edge's normal to a height of the edge's length. The edge is then in three
/// triangles.
inline Damaged add_fin(const Soup& clean, std::size_t face)
{
  Damaged d = undamaged(clean);
  const int i = clean.triangles.at(face)[0], j = clean.triangles.at(face)[1];
  Vec normal{{0, 0, 0}};
  for(const auto& t : clean.triangles)
  {
    const bool has_i = t[0] == i || t[1] == i || t[2] == i, has_j = t[0] == j || t[1] == j || t[2] == j;
    if(has_i && has_j)
      normal = add(normal, cross(sub(clean.points[std::size_t(t[1])], clean.points[std::size_t(t[0])]),
                                 sub(clean.points[std::size_t(t[2])], clean.points[std::size_t(t[0])])));
  }
  const Vec& pi = clean.points[std::size_t(i)];
  const Vec& pj = clean.points[std::size_t(j)];
  const double length = norm(sub(pj, pi));
  const Vec tip = add(mul(0.5, add(pi, pj)), mul(length / norm(normal), normal));
  const int k = int(d.soup.points.size());
  d.soup.points.push_back(tip);
  d.soup.triangles.push_back({{i, j, k}});
  d.to_clean.push_back(i);
  d.what = "fin on the edge (" + std::to_string(i) + ", " + std::to_string(j) + "), new vertex " + std::to_string(k);
  return d;
}

/// The vertex pairs (u, v), u < v, at least `min_hops` edges apart, in increasing Euclidean
/// distance: the `count` closest (brute force, for meshes of a few thousand vertices).
inline std::vector<std::array<int, 2> > close_far_pairs(const Soup& s, int min_hops, std::size_t count)
{
  const auto nb = vertex_neighbors(s);
  const int n = int(s.points.size());
  std::vector<int> hop(std::size_t(n), -1);
  std::vector<std::pair<double, std::array<int, 2> > > best;
  std::vector<int> touched;
  for(int u = 0; u < n; ++u)
  {
    // Breadth-first search to depth min_hops - 1 marks the vertices too close in the graph.
    touched.assign(1, u);
    hop[std::size_t(u)] = 0;
    for(std::size_t q = 0; q < touched.size(); ++q)
    {
      const int x = touched[q];
      if(hop[std::size_t(x)] + 1 >= min_hops) continue;
      for(int y : nb[std::size_t(x)])
        if(hop[std::size_t(y)] < 0)
        {
          hop[std::size_t(y)] = hop[std::size_t(x)] + 1;
          touched.push_back(y);
        }
    }
    for(int v = u + 1; v < n; ++v)
      if(hop[std::size_t(v)] < 0)
      {
        const double dist = norm(sub(s.points[std::size_t(u)], s.points[std::size_t(v)]));
        if(best.size() < count || dist < best.back().first)
        {
          best.push_back({dist, {{u, v}}});
          std::sort(best.begin(), best.end());
          if(best.size() > count) best.pop_back();
        }
      }
    for(int x : touched) hop[std::size_t(x)] = -1;
  }
  std::vector<std::array<int, 2> > out;
  for(const auto& b : best) out.push_back(b.second);
  return out;
}

/// Merges every clean vertex `merged[k][1]` into `merged[k][0]` (placed at their midpoint) and
/// renumbers the vertices left.
inline Damaged merge_vertices(const Soup& clean, const std::vector<std::array<int, 2> >& merged)
{
  const std::size_t n = clean.points.size();
  std::vector<int> into(n);
  for(std::size_t v = 0; v < n; ++v) into[v] = int(v);
  std::vector<Vec> position = clean.points;
  for(const auto& m : merged)
  {
    into[std::size_t(m[1])] = m[0];
    position[std::size_t(m[0])] = mul(0.5, add(clean.points[std::size_t(m[0])], clean.points[std::size_t(m[1])]));
  }
  Damaged d;
  std::vector<int> number(n, -1);
  for(std::size_t v = 0; v < n; ++v)
    if(into[v] == int(v))
    {
      number[v] = int(d.soup.points.size());
      d.soup.points.push_back(position[v]);
      d.to_clean.push_back(int(v));
    }
  d.from_clean.resize(n);
  for(std::size_t v = 0; v < n; ++v) d.from_clean[v] = number[std::size_t(into[v])];
  for(const auto& t : clean.triangles)
    d.soup.triangles.push_back({{d.from_clean[std::size_t(t[0])], d.from_clean[std::size_t(t[1])],
                                 d.from_clean[std::size_t(t[2])]}});
  return d;
}

/// (b) Two touching sheets: the edge (c, d) merged into the edge (a, b) where a and c are the
/// closest vertices at least `min_hops` edges apart (b and d: the closest pair of their
/// neighbours). The merged edge is then in four triangles.
inline Damaged merge_touching_edges(const Soup& clean, int min_hops)
{
  const auto nb = vertex_neighbors(clean);
  double best = std::numeric_limits<double>::infinity();
  std::array<int, 4> chosen{{-1, -1, -1, -1}};
  for(const auto& p : close_far_pairs(clean, min_hops, 32))
    for(int b : nb[std::size_t(p[0])])
      for(int d : nb[std::size_t(p[1])])
      {
        const double score = norm(sub(clean.points[std::size_t(p[0])], clean.points[std::size_t(p[1])])) +
                             norm(sub(clean.points[std::size_t(b)], clean.points[std::size_t(d)]));
        if(score < best)
        {
          best = score;
          chosen = {{p[0], b, p[1], d}};
        }
      }
  if(chosen[0] < 0) throw std::runtime_error("merge_touching_edges: no vertices far enough apart");
  Damaged out = merge_vertices(clean, {{{chosen[0], chosen[2]}}, {{chosen[1], chosen[3]}}});
  out.what = "edge (" + std::to_string(chosen[2]) + ", " + std::to_string(chosen[3]) + ") merged into (" +
             std::to_string(chosen[0]) + ", " + std::to_string(chosen[1]) + "), now (" +
             std::to_string(out.from_clean[std::size_t(chosen[0])]) + ", " +
             std::to_string(out.from_clean[std::size_t(chosen[1])]) + ")";
  return out;
}

/// (c) A bow-tie: the closest vertices at least `min_hops` edges apart merged into one, which then
/// joins two separate fans of triangles.
inline Damaged pinch_vertices(const Soup& clean, int min_hops)
{
  const auto pairs = close_far_pairs(clean, min_hops, 1);
  if(pairs.empty()) throw std::runtime_error("pinch_vertices: no vertices far enough apart");
  Damaged out = merge_vertices(clean, {pairs[0]});
  out.what = "vertex " + std::to_string(pairs[0][1]) + " merged into " + std::to_string(pairs[0][0]) + ", now " +
             std::to_string(out.from_clean[std::size_t(pairs[0][0])]);
  return out;
}

/// (d) Faces of zero area: in `fraction` of the faces, spread over the mesh, the vertex nearest to
/// the line of its opposite edge is moved onto that line (the three vertices stay distinct). The
/// faces around a moved vertex are left alone, so that each chosen face stays exactly flat. With
/// `amount` < 1 the vertices move only that fraction of the way: the same displacements without
/// faces of zero area (a control).
inline Damaged collapse_faces(const Soup& clean, double fraction, double amount = 1.0)
{
  Damaged d = undamaged(clean);
  const std::size_t nf = clean.triangles.size();
  const std::size_t wanted = std::max<std::size_t>(1, std::size_t(std::lround(fraction * double(nf))));
  const std::size_t stride = std::max<std::size_t>(1, nf / wanted);
  const auto nb = vertex_neighbors(clean);
  std::vector<char> locked(clean.points.size(), 0);
  std::vector<std::size_t> collapsed;
  for(std::size_t offset = 0; offset < stride && collapsed.size() < wanted; ++offset)
    for(std::size_t f = offset; f < nf && collapsed.size() < wanted; f += stride)
    {
      const auto& t = clean.triangles[f];
      if(locked[std::size_t(t[0])] || locked[std::size_t(t[1])] || locked[std::size_t(t[2])]) continue;
      int corner = 0;
      double lowest = std::numeric_limits<double>::infinity();
      Vec foot{{0, 0, 0}};
      for(int c = 0; c < 3; ++c)
      {
        const Vec& p = d.soup.points[std::size_t(t[std::size_t(c)])];
        const Vec& a = d.soup.points[std::size_t(t[std::size_t((c + 1) % 3)])];
        const Vec e = sub(d.soup.points[std::size_t(t[std::size_t((c + 2) % 3)])], a);
        const Vec q = add(a, mul(dot(sub(p, a), e) / dot(e, e), e));
        const double height = norm(sub(p, q));
        if(height < lowest)
        {
          lowest = height;
          corner = c;
          foot = q;
        }
      }
      const int v = t[std::size_t(corner)];
      const Vec& p = d.soup.points[std::size_t(v)];
      d.soup.points[std::size_t(v)] = amount == 1.0 ? foot : add(p, mul(amount, sub(foot, p)));
      for(int c = 0; c < 3; ++c) locked[std::size_t(t[std::size_t(c)])] = 1;
      for(int w : nb[std::size_t(v)]) locked[std::size_t(w)] = 1;
      collapsed.push_back(f);
    }
  d.what = std::to_string(collapsed.size()) + " faces of zero area (of " + std::to_string(nf) + ")";
  return d;
}

/// Writes `s` as an OFF file (full double precision).
inline void write_off(const std::string& file, const Soup& s)
{
  std::ofstream out(file);
  out.precision(17);
  out << "OFF\n" << s.points.size() << " " << s.triangles.size() << " 0\n";
  for(const auto& p : s.points) out << p[0] << " " << p[1] << " " << p[2] << "\n";
  for(const auto& t : s.triangles) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  if(!out) throw std::runtime_error("cannot write " + file);
}

} // namespace smc_damage

#endif // SMC_TEST_DAMAGED_MESHES_H
