// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Vertex neighbourhoods on the flat mesh copy, with reusable workspaces (the coupled refinement
// asks for them for every source vertex of every step):
//  - K_ring_workspace: the k-ring of a vertex or of a set of vertices (breadth-first search);
//  - geodesic_ball(): the vertices within a geodesic radius (truncated fast marching).

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEIGHBORHOOD_SEARCH_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEIGHBORHOOD_SEARCH_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/dijkstra.h>
#include <CGAL/Surface_mesh_correspondence/internal/fast_marching.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// Breadth-first k-rings. The k-ring of a set S is the set of vertices joined to S by a path of
/// at most k edges (S itself is the 0-ring). One object per thread; no allocation once warm.
class K_ring_workspace
{
public:
  K_ring_workspace() = default;
  explicit K_ring_workspace(const Indexed_mesh& m) { attach(m); }

  void attach(const Indexed_mesh& m)
  {
    mesh_ = &m;
    level_.assign(static_cast<std::size_t>(m.number_of_vertices()), -1);
    last_.clear();
  }

  /// Writes into `out` (cleared first) the k-ring of the seeds, in breadth-first order: the
  /// distinct seeds in the given order, then the vertices of ring 1, ring 2, ... (within a ring
  /// in discovery order, deterministic). Throws Invalid_parameter_error for k < 0 or a seed out
  /// of range.
  void k_ring(const int* seeds, std::size_t number_of_seeds, int k, std::vector<int>& out)
  {
    clear();
    out.clear();
    if(k < 0)
      throw Invalid_parameter_error("k-ring neighborhood: the number of rings must be >= 0 (got " +
                                    std::to_string(k) + ")");
    const Indexed_mesh& m = *mesh_;
    const int n = m.number_of_vertices();
    for(std::size_t i = 0; i < number_of_seeds; ++i)
    {
      const int s = seeds[i];
      if(s < 0 || s >= n)
      {
        last_ = out;
        clear();
        check_vertex_index(s, n, "k-ring neighborhood (seed)");
      }
      if(level_[s] >= 0) continue;
      level_[s] = 0;
      out.push_back(s);
    }
    for(std::size_t head = 0; head < out.size(); ++head)
    {
      const int v = out[head];
      const int next = level_[v] + 1;
      if(next > k) break;  // breadth-first: every later vertex is at level k too
      for(const int* w = m.neighbors_begin(v); w != m.neighbors_end(v); ++w)
        if(level_[*w] < 0)
        {
          level_[*w] = next;
          out.push_back(*w);
        }
    }
    last_.assign(out.begin(), out.end());
  }

  /// Ring number of `v` in the last call (-1 if outside the k-ring).
  int level(int v) const { return level_[v]; }

private:
  void clear()
  {
    for(int v : last_) level_[v] = -1;
    last_.clear();
  }

  const Indexed_mesh* mesh_ = nullptr;
  std::vector<int> level_;
  std::vector<int> last_;
};

/// Writes into `out` (cleared first) the vertices whose fast-marching distance to the seeds is at
/// most `radius`, by increasing distance (the seeds first). Uses the workspace `ws` (truncated
/// run; its distances stay available through ws.distance()). Throws Invalid_parameter_error for a
/// negative or NaN radius, no seed or a seed out of range.
inline void geodesic_ball(Fast_marching_workspace& ws, const int* seeds, std::size_t number_of_seeds,
                          double radius, std::vector<int>& out)
{
  if(!(radius >= 0))
    throw Invalid_parameter_error("geodesic ball: the radius must be >= 0 (got " +
                                  std::to_string(radius) + ")");
  ws.run(seeds, number_of_seeds, radius);
  out.assign(ws.accepted().begin(), ws.accepted().end());
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_NEIGHBORHOOD_SEARCH_H
