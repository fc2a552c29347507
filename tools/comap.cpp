// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: dense, accurate and cycle-consistent maps between two triangle meshes from the command
// line (Azencot, Dubrovina and Guibas 2019, with automatic initial maps).
//
//   comap match SOURCE TARGET --out-12 FILE --out-21 FILE [--init-12 FILE --init-21 FILE] ...
//   comap eval --source S --target T --map FILE --gt-source FILE --gt-target FILE ...
//   comap transfer --source S --target T --map-12 FILE --out FILE.ply [--texture IMAGE.png]
//   comap bench --data DIR --pairs FILE [--init DIR] --out DIR [--jobs N] [--limit N]
//   comap demo [--out DIR]
//
// See doc/cli.md.

#include "comap_commands.h"
#include "comap_settings.h"

#include <iostream>
#include <new>
#include <string>

namespace comap {
namespace {

bool is_command(const std::string& c)
{
  return c == "match" || c == "eval" || c == "transfer" || c == "bench" || c == "demo" || c == "settings";
}

void print_usage(std::ostream& out)
{
  out << "usage: comap COMMAND [options]   (comap COMMAND --help for the options)\n\n"
         "Dense, accurate and cycle-consistent maps between triangle meshes (coupled optimisation of\n"
         "Azencot, Dubrovina and Guibas 2019, with automatic initial maps).\n\n"
         "commands:\n"
         "  match      compute the maps SOURCE -> TARGET and TARGET -> SOURCE\n"
         "  eval       evaluate a map against ground-truth correspondences\n"
         "  transfer   colour the source through a map from the target (PLY with vertex colours)\n"
         "  bench      run and evaluate the refinement on a benchmark dataset (FAUST_r, TOSCA_r layout)\n"
         "  demo       the whole pipeline on a mesh from libcgal-demo and a deformed, remeshed copy\n"
         "  settings   print the settings registry with its defaults as a settings file to edit\n";
}

} // namespace
} // namespace comap

int main(int argc, char** argv)
{
  using namespace comap;
  const std::string command = argc > 1 ? argv[1] : "";
  try
  {
    if(command == "match") return run_match(argc, argv);
    if(command == "eval") return run_eval(argc, argv);
    if(command == "transfer") return run_transfer(argc, argv);
    if(command == "bench") return run_bench(argc, argv);
    if(command == "demo") return run_demo(argc, argv);
    if(command == "settings") return run_settings(argc, argv);
    if(command == "-h" || command == "--help" || command == "help")
    {
      print_usage(std::cout);
      return 0;
    }
    if(command.empty())
    {
      print_usage(std::cerr);
      return 2;
    }
    throw Usage_error("unknown command \"" + command + "\" (commands: match, eval, transfer, bench, demo, settings)");
  }
  catch(const Usage_error& e)
  {
    std::cerr << "comap: " << one_line(e.what())
              << (is_command(command) ? " (see comap " + command + " --help)" : std::string(" (see comap --help)"))
              << std::endl;
    return 2;
  }
  catch(const std::bad_alloc&)
  {
    std::cerr << "comap: out of memory" << std::endl;
    return 1;
  }
  catch(const std::exception& e)
  {
    std::cerr << "comap: error: " << one_line(e.what()) << std::endl;
    return 1;
  }
  catch(...)
  {
    std::cerr << "comap: error: unknown exception" << std::endl;
    return 1;
  }
}
