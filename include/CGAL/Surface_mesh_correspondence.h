// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Convenience header: the whole public API of Surface_mesh_correspondence (dense, accurate and
// cycle-consistent point-to-point maps between triangle meshes). Include the individual headers
// of CGAL/Surface_mesh_correspondence/ instead to compile less.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_H

#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>
#include <CGAL/Surface_mesh_correspondence/settings_io.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/trws.h>
#include <CGAL/Surface_mesh_correspondence/laplacian.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/shot.h>
#include <CGAL/Surface_mesh_correspondence/descriptor_stack.h>
#include <CGAL/Surface_mesh_correspondence/geodesic_distances.h>
#include <CGAL/Surface_mesh_correspondence/distance_oracle.h>
#include <CGAL/Surface_mesh_correspondence/neighborhoods.h>
#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>
#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/zoomout.h>
#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/mesh_io.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>
#include <CGAL/Surface_mesh_correspondence/triangle_soup.h>

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_H
