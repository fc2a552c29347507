// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: reading meshes (every format of CGAL::IO::read_polygon_soup) with checks whose
// messages name the file and the problem, reading and writing vertex maps, reading landmark
// files, and writing vertex-coloured PLY files.

#ifndef SMC_TOOLS_COMAP_MESH_IO_H
#define SMC_TOOLS_COMAP_MESH_IO_H

#include "comap_common.h"

#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

namespace comap {

typedef CGAL::Surface_mesh_correspondence::Vertex_index_map_vector Vertex_map;

/// An RGB colour with components in [0, 1].
typedef std::array<double, 3> Color;

/// Reads a connected, manifold, consistently oriented triangle mesh from an OFF, PLY, OBJ or STL
/// file. Vertex i of the result is the i-th point of the file (maps refer to it).
/// \throws CGAL::Surface_mesh_correspondence::IO_error (missing, unreadable or empty file,
///   unknown format) or Invalid_mesh_error (non-triangle faces, degenerate faces, non-manifold
///   or inconsistently oriented faces, isolated vertices, several connected components), each
///   with a message that starts with the file name.
Mesh read_triangle_mesh(const std::string& file);

/// Reads a mesh file as a triangle soup (point i is the file's i-th point), checked for what a soup
/// itself can get wrong; the shape made from it checks the surface.
/// \throws CGAL::Surface_mesh_correspondence::IO_error or Invalid_mesh_error, naming the file
///   (and the line for OFF and OBJ text files).
CGAL::Surface_mesh_correspondence::Triangle_soup read_mesh_soup(const std::string& file);

/// Reads a vertex map (one index per line) and checks it against the vertex counts of its
/// source and target meshes. \throws IO_error, Invalid_map_error naming the file.
Vertex_map read_vertex_map(const std::string& file, int index_base, std::size_t source_vertices,
                           std::size_t target_vertices);

/// Reads a ground-truth correspondence list and checks every entry is a vertex of a mesh of
/// `mesh_vertices` vertices.
Vertex_map read_correspondences(const std::string& file, int index_base, std::size_t mesh_vertices);

/// Pairs "i j" of vertex indices, one per line ('#' starts a comment), checked against the sizes.
std::vector<std::pair<std::size_t, std::size_t> > read_landmarks(const std::string& file, int index_base,
                                                                 std::size_t n1, std::size_t n2);

/// A file named on the command line: what named it (an option, or SOURCE / TARGET) and its path.
struct Named_file
{
  std::string name, path;
};

/// Whether two paths name the same file: the same device and inode when both exist (through
/// symbolic links, hard links or different spellings of the path), else the same absolute path
/// once the existing part of each is resolved.
bool same_file(const std::string& a, const std::string& b);

/// Checked before any work: throws Usage_error naming both when an output names an input or
/// another output of the same run (empty paths are skipped).
void check_outputs_are_new(const std::vector<Named_file>& inputs, const std::vector<Named_file>& outputs);

/// Renames completed temporary files over their outputs, in order: every file is written before
/// the first rename. The environment variable COMAP_TEST_KILL_BEFORE_COMMIT (a test hook) kills
/// the process here, between the writing and the renaming, to show that the outputs then keep
/// their previous content.
void commit_outputs(std::initializer_list<CGAL::Surface_mesh_correspondence::Atomic_output_file*> files);

/// Writes a vertex map, one index per line, atomically.
void write_vertex_map(const std::string& file, const Vertex_map& map, int index_base);

/// Writes the two maps of a run atomically, both complete before either replaces its file.
void write_vertex_maps(const std::string& file_12, const Vertex_map& map_12, const std::string& file_21,
                       const Vertex_map& map_21, int index_base);

/// Writes `mesh` as an ASCII PLY with one colour per vertex (red, green, blue as uchar), which
/// MeshLab, Blender and ParaView display directly.
void write_colored_ply(const std::string& file, const CGAL::Surface_mesh_correspondence::Triangle_soup& mesh,
                       const std::vector<Color>& colors);

/// Writes `mesh` as OFF.
void write_off(const std::string& file, const Mesh& mesh);

} // namespace comap

#endif // SMC_TOOLS_COMAP_MESH_IO_H
