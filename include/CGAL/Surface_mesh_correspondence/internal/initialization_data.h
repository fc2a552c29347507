// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the automatic initialisation needs of one shape besides its flat mesh: its spectrum (when
// the shape's own does not serve) and its descriptors, computed once and kept by a prepared shape
// (Correspondence_shape) for later calls with the same descriptor settings.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DATA_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DATA_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/functional_map_fitting.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <Eigen/Core>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// What the automatic initialisation computes for one shape (its spectrum when the shape's own
/// does not serve, and its descriptors), kept by the shape for later calls with the same
/// descriptor settings (`key`). One entry; the mutex makes concurrent calls on the same shape
/// compute it once.
struct Shape_initialization_cache
{
  std::mutex mutex;
  std::vector<double> key;
  std::shared_ptr<const Laplace_beltrami_spectrum> spectrum;  ///< null: the shape's own spectrum served
  std::shared_ptr<const Eigen::MatrixXd> descriptors;          ///< null: nothing cached yet
};

/// The spectrum and the descriptors of one flat mesh for automatic_initial_maps(): `given` is
/// reused when it has at least the eigenpairs the initialisation needs on the intrinsic Delaunay
/// triangulation (exactly as many: the maps equal those computed from the mesh alone; more: its
/// leading eigenpairs, equal to a new solve's up to the solver's tolerance), else computed.
struct Initialization_mesh_data
{
  std::shared_ptr<const Laplace_beltrami_spectrum> own_spectrum;
  const Laplace_beltrami_spectrum* spectrum = nullptr;
  std::shared_ptr<const Eigen::MatrixXd> descriptors;
  bool reused = false;  ///< `given` served
  bool cached = false;  ///< taken from the shape's cache
};

/// What initialization_descriptors() and the initialisation's spectrum depend on: two settings
/// with the same key give the same spectrum and descriptors on a shape.
inline std::vector<double> initialization_cache_key(const Initialization_settings& s)
{
  const Initialization_descriptor_layout l = initialization_descriptor_layout(s);
  std::vector<double> key{double(initialization_number_of_eigenpairs(s)), double(pass_final_size(s)),
                          double(l.wks), double(l.hks), s.wks_variance, double(s.signed_descriptor_smoothing)};
  for(const auto& p : l.signed_pairs)
  {
    key.push_back(p.first);
    key.push_back(p.second);
  }
  return key;
}

/// Fills `out` for mesh `m`. With a `cache` (a prepared shape's), the spectrum and descriptors
/// kept there for the same settings are taken, else computed and kept.
template <typename ConcurrencyTag>
void prepare_initialization_mesh(const Indexed_mesh& m, const Laplace_beltrami_spectrum* given,
                                        const Initialization_settings& s, const char* name,
                                        Initialization_mesh_data& out, Shape_initialization_cache* cache = nullptr)
{
  const int k = initialization_number_of_eigenpairs(s);
  // Checked before the eigensolver, which would fail with a less helpful message.
  if(m.number_of_vertices() <= s.zoomout_final_size || m.number_of_vertices() <= k)
    throw Invalid_mesh_error(std::string("automatic_initial_maps: ") + name + " has " +
                             std::to_string(m.number_of_vertices()) + " vertices, too few for a basis of " +
                             std::to_string(k) + " eigenfunctions (reduce zoomout_final_size)");
  out.reused = given && given->number_of_eigenpairs() >= k && given->uses_intrinsic_delaunay();
  std::unique_lock<std::mutex> lock;
  std::vector<double> key;
  if(cache)
  {
    lock = std::unique_lock<std::mutex>(cache->mutex);  // held while computing: computed once
    key = initialization_cache_key(s);
    if(cache->descriptors && cache->key == key)
    {
      out.own_spectrum = cache->spectrum;
      out.spectrum = out.own_spectrum ? out.own_spectrum.get() : given;
      out.descriptors = cache->descriptors;
      out.cached = true;
      return;
    }
  }
  if(out.reused && given->number_of_eigenpairs() == k)
    out.spectrum = given;
  else
  {
    out.own_spectrum = out.reused ? std::make_shared<const Laplace_beltrami_spectrum>(*given, k)
                                  : std::make_shared<const Laplace_beltrami_spectrum>(
                                        m, parameters::number_of_eigenpairs(k));
    out.spectrum = out.own_spectrum.get();
  }
  out.descriptors =
      std::make_shared<const Eigen::MatrixXd>(initialization_descriptors<ConcurrencyTag>(m, *out.spectrum, s));
  if(cache)
  {
    cache->key = std::move(key);
    cache->spectrum = out.own_spectrum;
    cache->descriptors = out.descriptors;
  }
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_INITIALIZATION_DATA_H
