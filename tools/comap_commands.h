// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: the subcommands. Each parses argv[2..] and returns the exit code; errors are thrown
// (Usage_error: exit 2; anything else: exit 1) and reported in one line by main().

#ifndef SMC_TOOLS_COMAP_COMMANDS_H
#define SMC_TOOLS_COMAP_COMMANDS_H

#include "comap_options.h"

#include <memory>

namespace comap {

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
