// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exception types of the package. CGAL preconditions vanish under NDEBUG, so every check that
// users rely on (bad meshes, bad maps, bad MRFs, solver failures, unreadable files) throws one of
// these, with a message that names the problem.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_EXCEPTIONS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_EXCEPTIONS_H

#include <stdexcept>
#include <string>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Base class of every exception thrown by the package.
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// A mesh that the called function cannot work with: empty, non-triangle faces, non-manifold,
/// isolated vertices, degenerate faces, non-finite coordinates, or several connected components
/// where one is required.
class Invalid_mesh_error : public Error
{
public:
  explicit Invalid_mesh_error(const std::string& what) : Error(what) {}
};

/// A vertex-to-vertex map of the wrong length or with indices out of range.
class Invalid_map_error : public Error
{
public:
  explicit Invalid_map_error(const std::string& what) : Error(what) {}
};

/// A discrete energy (MRF) that the solver cannot minimise: a node without labels, a cost table
/// of the wrong size, NaN or forbidden costs, self-loops.
class Invalid_energy_error : public Error
{
public:
  explicit Invalid_energy_error(const std::string& what) : Error(what) {}
};

/// A parameter value outside its valid range.
class Invalid_parameter_error : public Error
{
public:
  explicit Invalid_parameter_error(const std::string& what) : Error(what) {}
};

/// A numerical method that did not converge or met a singular system.
class Numerical_error : public Error
{
public:
  explicit Numerical_error(const std::string& what) : Error(what) {}
};

/// A file that cannot be opened, read or written, or whose contents are malformed.
class IO_error : public Error
{
public:
  explicit IO_error(const std::string& what) : Error(what) {}
};

/// match_shapes() was stopped by its visitor (a visitor function returned false). The output
/// maps are left as they were.
class Matching_stopped : public Error
{
public:
  explicit Matching_stopped(const std::string& what) : Error(what) {}
};

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_EXCEPTIONS_H
