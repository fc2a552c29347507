// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: the subcommands and what they share (common options, the thread limit, the library's
// entry point called on index maps). Each subcommand parses argv[2..] and returns the exit code;
// errors are thrown (Usage_error: exit 2; anything else: exit 1) and reported in one line by
// main().

#ifndef SMC_TOOLS_COMAP_COMMANDS_H
#define SMC_TOOLS_COMAP_COMMANDS_H

#include "comap_mesh_io.h"
#include "comap_options.h"

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>

#include <memory>
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

/// Options every subcommand takes.
struct Common_options
{
  bool quiet = false;
  int threads = 0;  ///< 0: all cores
};

void add_common_options(Option_parser& parser, Common_options& options);

/// Limits the number of TBB threads for its lifetime (no effect with 0 or without TBB).
class Thread_limit
{
public:
  explicit Thread_limit(int threads);
  ~Thread_limit();

private:
  std::shared_ptr<void> control_;
};

int run_match(int argc, char** argv);
int run_eval(int argc, char** argv);
int run_transfer(int argc, char** argv);
int run_bench(int argc, char** argv);
int run_demo(int argc, char** argv);

/// Throws Input_error when the directory of `file` does not exist or is not writable (checked
/// before long computations, so they do not end in a write error).
void check_writable(const std::string& file);

} // namespace comap

#endif // SMC_TOOLS_COMAP_COMMANDS_H
