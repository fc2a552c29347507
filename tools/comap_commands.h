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

typedef smc::Correspondence_shape<smc::Triangle_soup, Concurrency> Shape;
typedef smc::Map_evaluator<Concurrency> Evaluator;

/// Runs match_shapes() (the overload on triangle soups) on two meshes read from files, with the
/// initial maps of the options when given (the landmarks are in `np`).
template <typename Parameters>
smc::Matching_result match_soups(const smc::Triangle_soup& m1, const smc::Triangle_soup& m2, const Vertex_map* init_12,
                                 const Vertex_map* init_21, const Parameters& np, Vertex_map& map_12,
                                 Vertex_map& map_21)
{
  if(init_12)
    return smc::match_shapes<Concurrency>(m1, m2, map_12, map_21, smc::parameters::initial_maps(*init_12, *init_21, np));
  return smc::match_shapes<Concurrency>(m1, m2, map_12, map_21, np);
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
