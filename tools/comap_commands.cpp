// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_commands.h"

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <unistd.h>

namespace comap {

void add_common_options(Option_parser& p, Common_options& o)
{
  p.section("General");
  p.flag("--quiet", "no progress lines on stderr", [&o] { o.quiet = true; });
  p.value("--threads", "N", std::string("threads to use (0: all cores)") + (has_tbb ? "" : "; this build has no TBB"),
          "0", [&o](const std::string& v) { o.threads = parse_int("--threads", v, 0, 4096); });
}

Thread_limit::Thread_limit(int threads)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(threads > 0)
    control_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<std::size_t>(threads));
#else
  (void)threads;
#endif
}

Thread_limit::~Thread_limit() = default;

void check_writable(const std::string& file)
{
  const std::size_t slash = file.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : file.substr(0, slash));
  if(!directory_exists(dir)) throw Input_error("cannot write " + file + ": directory " + dir + " does not exist");
  if(::access(dir.c_str(), W_OK) != 0) throw Input_error("cannot write " + file + ": directory " + dir + " is not writable");
  if(directory_exists(file)) throw Input_error("cannot write " + file + ": it is a directory");
}

} // namespace comap
