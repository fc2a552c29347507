// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: what every command that matches shares: the progress lines of match_shapes() (a visitor
// of the library's stage events) and the JSON records of its result.

#ifndef SMC_TOOLS_COMAP_PIPELINE_H
#define SMC_TOOLS_COMAP_PIPELINE_H

#include "comap_json.h"
#include "comap_mesh_io.h"
#include "comap_settings.h"

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>

#include <string>

namespace comap {

typedef smc::Correspondence_shape<Mesh, Concurrency> Shape;
typedef smc::Map_evaluator<Concurrency> Evaluator;

typedef Mesh::Property_map<Mesh::Vertex_index, Mesh::Vertex_index> Vertex_vertex_map;

/// A vertex-to-vertex property map of `source` holding `map` (indices of `target`'s vertices).
inline Vertex_vertex_map vertex_property_map(Mesh& source, const std::string& name, const Vertex_map& map)
{
  Vertex_vertex_map p = source.add_property_map<Mesh::Vertex_index, Mesh::Vertex_index>(name).first;
  for(std::size_t i = 0; i < map.size(); ++i) p[Mesh::Vertex_index(Mesh::size_type(i))] = Mesh::Vertex_index(Mesh::size_type(map[i]));
  return p;
}

inline Vertex_map index_map(const Mesh& source, const Vertex_vertex_map& p)
{
  Vertex_map out(num_vertices(source));
  for(Mesh::Vertex_index v : source.vertices()) out[v.idx()] = p[v].idx();
  return out;
}

/// Runs match_shapes() (the overload on meshes) on two meshes read from files, with the initial maps and landmarks of the
/// options when given; the maps are returned as indices.
template <typename Parameters>
smc::Matching_result match_meshes(Mesh& m1, Mesh& m2, const Vertex_map* init_12, const Vertex_map* init_21,
                                  const Parameters& np, Vertex_map& map_12, Vertex_map& map_21)
{
  Vertex_vertex_map out12 = m1.add_property_map<Mesh::Vertex_index, Mesh::Vertex_index>("v:comap_out").first;
  Vertex_vertex_map out21 = m2.add_property_map<Mesh::Vertex_index, Mesh::Vertex_index>("v:comap_out").first;
  smc::Matching_result r;
  if(init_12)
  {
    const Vertex_vertex_map in12 = vertex_property_map(m1, "v:comap_in", *init_12);
    const Vertex_vertex_map in21 = vertex_property_map(m2, "v:comap_in", *init_21);
    r = smc::match_shapes<Concurrency>(m1, m2, out12, out21, smc::parameters::initial_maps(in12, in21, np));
  }
  else
    r = smc::match_shapes<Concurrency>(m1, m2, out12, out21, np);
  map_12 = index_map(m1, out12);
  map_21 = index_map(m2, out21);
  return r;
}

/// The progress lines of a run: one per stage begun and ended, one per refinement solve, and the
/// stages' progress at most every few seconds. Lines are prefixed by `label`.
class Progress_visitor : public smc::Default_matching_visitor
{
public:
  explicit Progress_visitor(const Progress& progress, std::string label = "", bool steps = true)
      : progress_(&progress), label_(std::move(label)), steps_(steps)
  {}
  bool stage_begun(smc::Matching_stage s);
  bool progress(smc::Matching_stage s, double fraction);
  bool stage_ended(smc::Matching_stage s, double seconds);
  bool refinement_step(const smc::Refinement_step& s);

private:
  const Progress* progress_;
  std::string label_;
  bool steps_;
  double last_line_ = -1e9;
};

/// Writes the result of match_shapes() (decisions, stage times, consistency and distortion,
/// refinement solves) as a JSON object named `key`.
void write_result(Json_writer& json, const std::string& key, const smc::Matching_result& r);

/// Mean, median, maximum, fractions within 0.025 / 0.05 / 0.1 and, with `with_curve`, the
/// cumulative curve.
void write_error_statistics(Json_writer& json, const std::string& key, const smc::Error_statistics& e,
                            bool with_curve);

/// Pairs "i j" of vertex indices, one per line ('#' starts a comment), checked against the sizes.
std::vector<std::pair<std::size_t, std::size_t> > read_landmarks(const std::string& file, int index_base,
                                                                 std::size_t n1, std::size_t n2);

} // namespace comap

#endif // SMC_TOOLS_COMAP_PIPELINE_H
