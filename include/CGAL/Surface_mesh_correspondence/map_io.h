// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reading and writing vertex maps and ground-truth correspondence files: one vertex index per
// line, 0- or 1-based as the caller says (the benchmark datasets' .map and .vts files are
// 1-based). Errors name the file and the line.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_MAP_IO_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_MAP_IO_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A point-to-point map between two meshes as vertex indices: `map[i]` is the index of the target
/// vertex matched to source vertex `i`. Ground-truth correspondence lists (.vts) use the same type:
/// entry `k` is the vertex of the mesh that corresponds to sample `k`.
typedef std::vector<std::size_t> Vertex_index_map_vector;

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Reads one vertex index per line from `in` and returns them 0-based.
/// Empty lines and lines starting with `#` are skipped; any other line must hold exactly one
/// integer >= `index_base`.
/// \param in the stream to read
/// \param index_base 0 or 1: the index of the first vertex in the file
/// \param name the file name used in error messages
/// \throws IO_error naming the file and line of the first bad entry
inline Vertex_index_map_vector read_vertex_indices(std::istream& in, int index_base,
                                                   const std::string& name = "input")
{
  if(index_base != 0 && index_base != 1)
    throw Invalid_parameter_error("index base must be 0 or 1, not " + std::to_string(index_base));
  Vertex_index_map_vector result;
  std::string line;
  std::size_t line_number = 0;
  while(std::getline(in, line))
  {
    ++line_number;
    std::size_t b = line.find_first_not_of(" \t\r");
    if(b == std::string::npos || line[b] == '#') continue;
    std::size_t e = line.find_last_not_of(" \t\r");
    const std::string token = line.substr(b, e - b + 1);
    const char* s = token.c_str();
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(s, &end, 10);
    if(end == s || *end != '\0' || errno == ERANGE)
      throw IO_error(name + ":" + std::to_string(line_number) + ": expected one vertex index, found \"" +
                     token + "\"");
    if(value < index_base)
      throw IO_error(name + ":" + std::to_string(line_number) + ": vertex index " + token +
                     " is below the index base " + std::to_string(index_base));
    result.push_back(static_cast<std::size_t>(value - index_base));
  }
  if(in.bad()) throw IO_error(name + ": read error");
  return result;
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Reads a vertex index file (see `read_vertex_indices()`).
/// \throws IO_error when the file cannot be opened or holds a bad entry.
inline Vertex_index_map_vector read_vertex_indices(const std::string& filename, int index_base)
{
  std::ifstream in(filename);
  if(!in) throw IO_error("cannot open " + filename + " for reading");
  return read_vertex_indices(in, index_base, filename);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Writes one vertex index per line, shifted by `index_base` (0 or 1).
inline void write_vertex_indices(std::ostream& out, const Vertex_index_map_vector& indices,
                                 int index_base)
{
  if(index_base != 0 && index_base != 1)
    throw Invalid_parameter_error("index base must be 0 or 1, not " + std::to_string(index_base));
  for(std::size_t v : indices) out << (v + static_cast<std::size_t>(index_base)) << '\n';
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// An output file written atomically: the text goes to a temporary file in the same folder, which
/// `commit()` renames over the file. Until then the file keeps its previous content (or does not
/// exist); a write that fails, throws or is killed never leaves a truncated file. When the object
/// is destroyed without `commit()`, the temporary file is removed. The temporary file's name is
/// hidden and never ends like an output: `DIR/.NAME.tmp-PID-N` for `DIR/NAME`, so a killed run's
/// leftovers are not mistaken for outputs.
///
/// To replace several files together (the two maps of a run), write them all, then commit them
/// one after the other: every file is complete before the first rename.
class Atomic_output_file
{
public:
  /// Opens the temporary file next to `filename`. \throws IO_error when it cannot be created.
  explicit Atomic_output_file(std::string filename) : filename_(std::move(filename))
  {
    static std::atomic<unsigned> counter(0);
    const std::size_t slash = filename_.find_last_of('/');
    const std::string dir = slash == std::string::npos ? std::string() : filename_.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? filename_ : filename_.substr(slash + 1);
    temporary_ = dir + "." + name + ".tmp-" + std::to_string(long(::getpid())) + "-" + std::to_string(counter++);
    out_.open(temporary_, std::ios::out | std::ios::trunc);
    if(!out_) throw IO_error("cannot open " + filename_ + " for writing (temporary file " + temporary_ + "): " +
                             std::strerror(errno));
  }
  Atomic_output_file(const Atomic_output_file&) = delete;
  Atomic_output_file& operator=(const Atomic_output_file&) = delete;
  ~Atomic_output_file()
  {
    if(!committed_)
    {
      if(out_.is_open()) out_.close();
      std::remove(temporary_.c_str());
    }
  }

  /// The stream to write to.
  std::ostream& stream() { return out_; }
  const std::string& filename() const { return filename_; }
  const std::string& temporary_filename() const { return temporary_; }

  /// Flushes and closes the temporary file. \throws IO_error when a write failed.
  void close()
  {
    if(!out_.is_open()) return;
    out_.flush();
    const bool good = bool(out_);
    out_.close();
    if(!good || out_.fail()) throw IO_error("error while writing " + filename_ + " (temporary file " + temporary_ + ")");
  }
  /// Closes the temporary file and renames it over the file. \throws IO_error.
  void commit()
  {
    close();
    if(std::rename(temporary_.c_str(), filename_.c_str()) != 0)
      throw IO_error("cannot rename " + temporary_ + " to " + filename_ + ": " + std::strerror(errno));
    committed_ = true;
  }

private:
  std::string filename_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Writes a vertex index file (see `write_vertex_indices()`), atomically (Atomic_output_file).
/// \throws IO_error when the file cannot be written.
inline void write_vertex_indices(const std::string& filename, const Vertex_index_map_vector& indices,
                                 int index_base)
{
  Atomic_output_file out(filename);
  write_vertex_indices(out.stream(), indices, index_base);
  out.commit();
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Checks that `map` is a map from a mesh with `source_size` vertices to one with `target_size`
/// vertices: one entry per source vertex, every entry below `target_size`.
/// \param map the vertex indices of the target, one per source vertex
/// \param source_size, target_size the numbers of vertices of the source and the target
/// \param what names the map in the message (for example "map 1->2" or a file name)
/// \throws Invalid_map_error naming the problem
inline void check_vertex_map(const Vertex_index_map_vector& map, std::size_t source_size,
                             std::size_t target_size, const std::string& what = "map")
{
  if(map.size() != source_size)
    throw Invalid_map_error(what + " has " + std::to_string(map.size()) + " entries but the source mesh has " +
                            std::to_string(source_size) + " vertices");
  for(std::size_t i = 0; i < map.size(); ++i)
    if(map[i] >= target_size)
      throw Invalid_map_error(what + ": entry " + std::to_string(i) + " is vertex " + std::to_string(map[i]) +
                              " (0-based), out of range for a target mesh of " +
                              std::to_string(target_size) + " vertices");
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Checks that every entry of a correspondence list is a vertex of a mesh with `mesh_size`
/// vertices. \throws Invalid_map_error naming the first bad entry.
inline void check_vertex_indices(const Vertex_index_map_vector& indices, std::size_t mesh_size,
                                 const std::string& what = "correspondences")
{
  for(std::size_t k = 0; k < indices.size(); ++k)
    if(indices[k] >= mesh_size)
      throw Invalid_map_error(what + ": entry " + std::to_string(k) + " is vertex " +
                              std::to_string(indices[k]) + " (0-based), out of range for a mesh of " +
                              std::to_string(mesh_size) + " vertices");
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_MAP_IO_H
