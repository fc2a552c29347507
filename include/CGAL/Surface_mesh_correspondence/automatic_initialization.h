// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Automatic initial point-to-point maps between two meshes, in both directions, without user
// input: an orientation-preserving functional map fitted to descriptors (WKS, HKS), upsampled to
// point maps by a coupled ZoomOut. These maps are the starting point of the coupled refinement.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/extremity_hypotheses.h>
#include <CGAL/Surface_mesh_correspondence/internal/functional_map_fitting.h>
#include <CGAL/Surface_mesh_correspondence/internal/given_maps_comparison.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/tear_repair.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/tags.h>

#include <Eigen/Core>

#include <chrono>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

namespace internal {

/// A flat mesh for on_prepared_meshes(): with a prepared shape's spectrum (to reuse when it
/// serves) and cache, or neither.
struct Initialization_mesh_source
{
  const Indexed_mesh* mesh = nullptr;
  const Laplace_beltrami_spectrum* spectrum = nullptr;
  Shape_initialization_cache* cache = nullptr;
};

inline Initialization_mesh_source initialization_mesh_source(const Shape_data& d)
{
  return {&d.mesh, &d.largest_spectrum(), d.initialization.get()};
}

/// Prepares both meshes for the initialisation (concurrently) and runs `f(shape1, shape2)`; the
/// result gets the preparation time and the total time since `start`.
template <typename ConcurrencyTag, typename F>
Automatic_initialization_result on_prepared_meshes(const Initialization_mesh_source& m1,
                                                   const Initialization_mesh_source& m2,
                                                   const Initialization_settings& s,
                                                   std::chrono::steady_clock::time_point start, const F& f)
{
  Initialization_mesh_data d1, d2;
  invoke_both<ConcurrencyTag>(
      [&] { prepare_initialization_mesh<ConcurrencyTag>(*m1.mesh, m1.spectrum, s, "mesh 1", d1, m1.cache); },
      [&] { prepare_initialization_mesh<ConcurrencyTag>(*m2.mesh, m2.spectrum, s, "mesh 2", d2, m2.cache); });
  const double prepare_seconds = seconds_since(start);
  const Initialization_shape a{m1.mesh, d1.spectrum, d1.descriptors.get()},
      b{m2.mesh, d2.spectrum, d2.descriptors.get()};
  Automatic_initialization_result r = f(a, b);
  r.spectra_seconds = prepare_seconds;
  r.reused_spectra = int(d1.reused) + int(d2.reused);
  r.reused_descriptors = int(d1.cached) + int(d2.cached);
  r.total_seconds = seconds_since(start);
  return r;
}

/// Both public overloads of automatic_initial_maps(): prepares the two flat meshes (in parallel
/// with Parallel_tag) and runs the core; the times count from `start`.
template <typename ConcurrencyTag>
Automatic_initialization_result automatic_initial_maps_of_meshes(const Initialization_mesh_source& m1,
                                                                 const Initialization_mesh_source& m2,
                                                                 const Initialization_settings& s,
                                                                 std::vector<std::size_t>& map_12,
                                                                 std::vector<std::size_t>& map_21,
                                                                 std::chrono::steady_clock::time_point start)
{
  return on_prepared_meshes<ConcurrencyTag>(m1, m2, s, start,
                                            [&](const Initialization_shape& a, const Initialization_shape& b) {
                                              return automatic_initial_maps<ConcurrencyTag>(a, b, s, map_12, map_21);
                                            });
}

/// A connected indexed copy of a mesh for automatic_initial_maps() and repair_torn_maps().
template <typename TriangleMesh, typename NamedParameters>
Indexed_mesh initialization_mesh(const TriangleMesh& tm, const NamedParameters& np, const char* name)
{
  Mesh_requirements req;
  req.allow_several_components = false;
  return make_indexed_mesh(tm, np, req, name);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Computes initial point-to-point maps between two meshes in both directions, automatically.
///
/// Pipeline: the Laplace-Beltrami spectra and WKS descriptors of both meshes; functional maps
/// \f$ C_{12} \f$ and \f$ C_{21} \f$ of size `spectral_basis_size`, each minimising the energy of
/// fit_functional_map() (descriptor preservation, Laplacian and descriptor commutativity, and the
/// orientation-preserving term of Ren et al. 2018, which rules out left/right mirror maps); then a
/// coupled ZoomOut (Melzi et al. 2019) that grows both maps to `zoomout_pass_size`, each step
/// matching every vertex to its nearest neighbour in the joint embedding
/// \f$ [\Phi_1 C_{12}, \Phi_1] \f$ vs. \f$ [\Phi_2, \Phi_2 C_{21}] \f$ (which favours inverse
/// pairs of maps) and refitting. Then the tear repair: maps that swap two parts of a
/// symmetric body (limbs, feet) tear where a swapped part meets the rest; when the regions cut off
/// by the tears exceed 1% of a mesh, the maps are computed again with landmarks sampled in the
/// largest region of each map (see repair_torn_maps()), and kept when they are less torn and at
/// most 5% more distorted (`tear_repair_distortion_tolerance`). Optionally
/// (`number_of_distortion_repair_passes`) the distortion repair: maps that distort the geodesic
/// distances of farthest-point samples by more than 0.035 on average are computed again with
/// landmarks in their isometric core, and kept when they distort at least 20% less. On maps that
/// distort those distances by more than 0.1 (`extremity_hypothesis_threshold`: pairs far from
/// isometric, where every descriptor fit can be wrong as a whole) the extremity hypotheses: passes
/// from assignments of the extremities of both shapes that keep the proportions of their geodesic
/// distances, pinned as anchor landmarks; of their maps, those that best keep the SHOT descriptors
/// and the sample distances are kept. When the first pass's maps are already above that
/// threshold, the hypotheses run before the repairs, which then run only if the first maps are
/// kept. Finally the kept maps grow by the same coupled ZoomOut to `zoomout_final_size`
/// (grow_initial_maps()).
///
/// The meshes must be oriented alike (both outward or both inward); for closed meshes of opposite
/// orientations (signed volumes of opposite signs) the orientation term is reversed
/// automatically. With landmarks, both orientations are fitted and the one of lower total
/// selection score is kept, so landmarks may select a mirror map.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` or `CGAL::Parallel_tag` (TBB: the two spectra
///   and the nearest-neighbour searches in parallel)
/// \tparam TriangleMesh1 a model of `FaceListGraph`
/// \tparam TriangleMesh2 a model of `FaceListGraph`
/// \tparam NamedParameters a sequence of named parameters
/// \param tm1 the first mesh (connected)
/// \param tm2 the second mesh (connected)
/// \param map_12 output: `map_12[i]` is the index of the vertex of `tm2` matched to vertex i of
///   `tm1` (indices of the vertex index maps)
/// \param map_21 output: the same from `tm2` to `tm1`
/// \param np optional named parameters among:
///   - `spectral_basis_size`: \f$ k_0 \f$, the size of the fitted functional maps; type `int`.
///     By default six fits are tried ((k_0, w_o, w_c) = (20, 0.03, 0.3), (15, 0.03, 0.3), (20,
///     0.1, 1), (30, 0.03, 0.3), (40, 0.1, 1), (60, 0.1, 1); those larger than `zoomout_final_size`
///     are skipped), together with the inverses of the fitted maps, and in each direction the one
///     whose map after a short ZoomOut distorts geodesic distances least (between 100
///     farthest-point samples) is kept; giving `spectral_basis_size`, `orientation_weight` or
///     `commutativity_weight` fits a single configuration, the values not given taken from the
///     first one.
///   - `zoomout_final_size`: \f$ k_f \f$, the basis size after ZoomOut; type `int`; default 200.
///   - `zoomout_pass_size`: the basis size at which every pass (the first one and each repair pass)
///     ends its ZoomOut; the tears, the distortions and the choice between passes are measured
///     there, and the kept maps then grow to \f$ k_f \f$; the WKS and HKS descriptors of the
///     initialisation use this many eigenpairs (with `number_of_eigenpairs` not given); type
///     `int`; default 120.
///   - `zoomout_step`: the basis growth per ZoomOut iteration; type `int`; default 5.
///   - `number_of_eigenpairs`: eigenpairs computed, at least \f$ k_f \f$; type `int`; default
///     \f$ k_f \f$.
///   - `orientation_weight`: \f$ w_o \f$; type `double` (0 disables the term).
///   - `commutativity_weight`: \f$ w_c \f$, descriptor commutativity; type `double`.
///   - `wks_weight`, `hks_weight`: weights of the WKS and HKS descriptor columns; type `double`;
///     defaults 1 and 0.
///   - `number_of_wks_energies`, `wks_variance`, `number_of_hks_scales`: the descriptors (defaults
///     100, 7, 16).
///   - `landmarks`: known correspondences, a range of pairs (vertex index in `tm1`, vertex index in
///     `tm2`) (e.g. `std::vector<std::pair<std::size_t, std::size_t>>`); default none.
///   - `landmark_distance_weight`: weight of the geodesic distance fields of the landmarks
///     (divided by the square root of the mesh area) appended to the ZoomOut embeddings of every
///     pass, so that each vertex is matched to one about as far from every landmark; type
///     `double`; default 10 (0: none). The landmarks of the repair passes get no distance field,
///     nor do the extremities of the hypotheses when landmarks are given.
///   - `landmark_orientation_weight`: weight of the orientation-sensitive descriptors appended to
///     the ZoomOut embeddings of the passes with distance fields, so that a limb is not matched to
///     its mirror image about its axis (which the distances alone allow); type `double`; default 3
///     (0: none).
///   - `landmark_chirality_weight`: weight of the chirality features of the passes with two or
///     more anchor landmarks appended to the ZoomOut embeddings: for each two anchors, the turn
///     from the direction away from one to the direction away from the other, seen from the
///     outside (the sine of the angle between the gradients of their distance fields). A part
///     mirrored about a plane (a torso turned front to back) keeps the distances to the anchors
///     and reverses these turns; type `double`; default 10 (0: none).
///   - `number_of_repair_passes`: tear repair passes at most; type `int`; default 2 (0: no
///     repair).
///   - `tear_threshold`: a source edge is torn when its images are at least this far apart,
///     relative to the square root of the target's area (and at least four mean edge lengths);
///     type `double`; default 0.06.
///   - `tear_repair_distortion_tolerance`: a tear repair pass is kept only when it is less torn
///     and its maps distort the geodesic distances of farthest-point samples at most this much
///     more (relatively) than the maps it replaces; type `double`; default 0.05 (negative: no
///     distortion check, the less torn pass is kept).
///   - `number_of_distortion_repair_passes`: distortion repair passes at most (maps continuous but
///     wrong on a large part, e.g. half-body flips; see repair_distorted_maps()); type `int`;
///     default 0 (each pass costs about as much as the first one).
///   - `extremity_hypotheses`, `extremity_hypothesis_threshold`: on maps whose sample distortion is
///     above the threshold (pairs far from isometric, e.g. a gorilla and a man), this many passes
///     from the best assignments of the shapes' extremities (tips of limbs, head, tail) as
///     landmarks; the criterion of their maps is the SHOT disagreement (radius `shot_radius`) plus
///     `extremity_hypothesis_distortion_weight` (2) times their sample distortion, and those within
///     `extremity_hypothesis_repair_margin` (0.05) of the best get their tear repair; among the
///     repaired ones whose maps distort the samples at most `extremity_hypothesis_tolerance` (0.5)
///     more than the descriptor-based maps, the one of lowest criterion is kept (see
///     try_extremity_hypotheses()); types `int` and
///     `double`; defaults 3 and 0.1 (the best assignments are mostly the true one, its mirror
///     twin and assignments with one pair of limbs swapped; each hypothesis pass uses the two fits
///     of the repair passes, and with `Parallel_tag` they run concurrently).
///   - `compare_with_automatic_maps`: repair_torn_maps() only (ignored here): whether the repaired
///     given maps compete with the automatic maps; type `bool`; default true.
///   - `automatic_maps_comparison_threshold`: repair_torn_maps() with the comparison and
///     compare_with_automatic_maps() only (ignored here): the automatic maps are computed and
///     compared only when the given maps' sample distortion is above it; type `double`; default
///     0.035 (0: always).
///   - `verbose`: print progress to `std::cerr`; type `bool`; default false.
///   - `vertex_point_map`, `vertex_index_map`: for both meshes (use the same types); defaults the
///     meshes' own.
/// \returns timings and diagnostics.
/// \pre both meshes are connected triangle meshes with more than \f$ k_f \f$ vertices (else
///   Invalid_mesh_error); parameters in range (else Invalid_parameter_error).
/// \throws Numerical_error if an eigensolver fails.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result automatic_initial_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const internal::Initialization_settings s = internal::initialization_settings(np);
  internal::check_initialization_settings(s);
  const internal::Indexed_mesh m1 = internal::initialization_mesh(tm1, np, "mesh 1");
  const internal::Indexed_mesh m2 = internal::initialization_mesh(tm2, np, "mesh 2");
  return internal::automatic_initial_maps_of_meshes<ConcurrencyTag>({&m1, nullptr, nullptr}, {&m2, nullptr, nullptr}, s,
                                                                    map_12, map_21, start);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// automatic_initial_maps() on two prepared shapes, to be refined with the same shapes. The
/// shapes' flat meshes are reused, and their spectra too when they hold at least the eigenpairs
/// the initialisation needs (200 by default) on the intrinsic Delaunay triangulation: either
/// their own spectrum (prepared with `number_of_eigenpairs(200)`), or a larger
/// `precomputed_spectrum` that they were given (one eigensolve per shape serves both: compute
/// 200 eigenpairs, give them to a shape that uses 100); otherwise the spectrum is computed
/// (`reused_spectra` of the result counts the reused ones). Each shape keeps what the
/// initialisation computed for it (its descriptors, and the spectrum when its own did not serve):
/// later calls on the shape with the same descriptor settings (eigenpairs, WKS, HKS and signed
/// descriptor settings, pass size) take them instead of computing them again
/// (`reused_descriptors` counts those shapes), also from repair_torn_maps() and
/// compare_with_automatic_maps() on shapes. One entry per shape (about 5 MB of descriptors for
/// 5000 vertices, plus 8 MB when the spectrum is kept); concurrent calls on one shape compute it
/// once. With a spectrum of exactly the needed size the maps are exactly those of the mesh-based
/// overload with the same named parameters (`np`: the initialisation's parameters, as there);
/// leading eigenpairs of a larger one equal a new solve's up to the eigensolver's tolerance. The
/// maps can be passed to refine_coupled_maps() with the same shapes.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result automatic_initial_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                       const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const internal::Initialization_settings s = internal::initialization_settings(np);
  internal::check_initialization_settings(s);
  return internal::automatic_initial_maps_of_meshes<ConcurrencyTag>(internal::initialization_mesh_source(shape_1.data()),
                                                                    internal::initialization_mesh_source(shape_2.data()),
                                                                    s, map_12, map_21, start);
}

namespace internal {

/// The settings of the public functions on given maps: repair_torn_maps() (the comparison as the
/// setting `compare_with_automatic_maps` says) and, with `compare` (which overrides the setting),
/// compare_with_automatic_maps(); checked.
template <typename NamedParameters>
Initialization_settings given_maps_settings(const NamedParameters& np, bool compare)
{
  Initialization_settings s = initialization_settings(np);
  s.compare_with_automatic_maps = compare || Matching_settings::from(np).compare_with_automatic_maps;
  check_initialization_settings(s);
  return s;
}

/// The public functions on given maps (`repair`: repair_torn_maps(), else
/// compare_with_automatic_maps()), on flat meshes or prepared shapes; the times count from `start`.
template <typename ConcurrencyTag>
Automatic_initialization_result repair_given_maps_of_sources(const Initialization_mesh_source& m1,
                                                             const Initialization_mesh_source& m2,
                                                             const Initialization_settings& s,
                                                             std::vector<std::size_t>& map_12,
                                                             std::vector<std::size_t>& map_21, bool repair,
                                                             std::chrono::steady_clock::time_point start)
{
  const std::size_t n1 = std::size_t(m1.mesh->number_of_vertices()), n2 = std::size_t(m2.mesh->number_of_vertices());
  check_vertex_map(map_12, n1, n2, "map 1->2");
  check_vertex_map(map_21, n2, n1, "map 2->1");
  return on_prepared_meshes<ConcurrencyTag>(m1, m2, s, start,
                                            [&](const Initialization_shape& a, const Initialization_shape& b) {
                                              return repair_given_maps<ConcurrencyTag>(a, b, s, map_12, map_21,
                                                                                       repair);
                                            });
}

template <typename ConcurrencyTag, typename TriangleMesh1, typename TriangleMesh2, typename NamedParameters>
Automatic_initialization_result repair_given_maps_of_meshes(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np, bool repair, bool compare)
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const Initialization_settings s = given_maps_settings(np, compare);
  const Indexed_mesh m1 = initialization_mesh(tm1, np, "mesh 1");
  const Indexed_mesh m2 = initialization_mesh(tm2, np, "mesh 2");
  return repair_given_maps_of_sources<ConcurrencyTag>({&m1, nullptr, nullptr}, {&m2, nullptr, nullptr}, s, map_12,
                                                      map_21, repair, start);
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Repairs maps that swap parts of the shapes (limbs, feet): the tear repair of
/// automatic_initial_maps() applied to maps computed elsewhere. Each map's source is cut along its
/// tears (edges whose endpoints land at least `tear_threshold` sqrt(area) apart); when the regions
/// cut off from the largest one (the core) exceed `tear_area_fraction` of a mesh, both maps are
/// recomputed by the automatic initialisation with farthest-point samples of the cores (and
/// their images) as landmarks, in the orientation of the given maps, and kept when they are less
/// torn and at most `tear_repair_distortion_tolerance` (5%) more distorted. Maps without tears
/// are returned unchanged. With `number_of_distortion_repair_passes`, the distortion repair
/// follows (see repair_distorted_maps(): maps whose sample distortion is above 0.035 are
/// recomputed from landmarks in their isometric core, and kept when at least 20% less distorted).
/// Unless `compare_with_automatic_maps(false)`, the (repaired) maps then compete with the automatic
/// maps of the pair (automatic_initial_maps(), about the time of one more initialisation): the
/// pair of maps whose farthest-point samples' geodesic distances are less distorted is returned,
/// unless the repaired maps distort them at most `automatic_maps_comparison_threshold` (default
/// 0.035), in which case they are kept without computing the automatic maps. This catches given
/// maps that are wrong as a whole, which their own cores cannot repair.
///
/// \param tm1, tm2 the two meshes
/// \param map_12, map_21 input and output: `map_12[i]` is the vertex of `tm2` matched to vertex i of
///   `tm1` (indices of the vertex index maps), `map_21` the other way round
/// \param np the named parameters of automatic_initial_maps(); `landmarks` are kept in every pass
/// \returns `repair_passes` (0: the maps were kept), the torn fractions before and after,
///   `distortion_repair_passes` and the sample distortions before and after, timings; with
///   `compare_with_automatic_maps`, `automatic_maps_kept` and both distortions compared (when the
///   automatic maps are kept, the other fields describe them, see Automatic_initialization_result)
/// \throws Invalid_map_error for maps of the wrong size or with entries out of range, and the
///   exceptions of automatic_initial_maps()
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result repair_torn_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                 std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                                                 const NamedParameters& np = parameters::default_values())
{
  return internal::repair_given_maps_of_meshes<ConcurrencyTag>(tm1, tm2, map_12, map_21, np, true, false);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// repair_torn_maps() on two prepared shapes (maps indexed as the shapes' vertices): the shapes'
/// flat meshes, spectra and kept initialisation descriptors are used as by
/// automatic_initial_maps() on shapes, with the same maps as the overload on meshes when the
/// shapes' spectra are of the initialisation's size or not used.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result repair_torn_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                 const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                 std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                                                 const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  return internal::repair_given_maps_of_sources<ConcurrencyTag>(
      internal::initialization_mesh_source(shape_1.data()), internal::initialization_mesh_source(shape_2.data()),
      internal::given_maps_settings(np, false), map_12, map_21, true, start);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Keeps maps computed elsewhere, or replaces them by the automatic maps of the pair
/// (automatic_initial_maps() with the same named parameters), whichever distort the geodesic
/// distances between 100 farthest-point samples of each mesh less (mean of both directions; ties
/// keep the given maps). The given maps are not repaired (repair_torn_maps() repairs them first,
/// then compares). A safety net for maps that may be
/// wrong as a whole (symmetry flips, a body turned by 180 degrees), which no local refinement
/// undoes; it costs one automatic initialisation, except on given maps whose sample distortion is
/// at most `automatic_maps_comparison_threshold` (default 0.035; 0: always compare), which are kept
/// without computing the automatic maps (`automatic_maps_computed` false). Sample distortion is not accuracy: on a pair
/// whose deformation stretches the surface, exact maps can distort more than slightly less
/// accurate automatic maps, which then replace them.
///
/// \param tm1, tm2 the two meshes
/// \param map_12, map_21 input and output, as for repair_torn_maps()
/// \param np the named parameters of automatic_initial_maps()
/// \returns the result of the automatic maps when they replaced the given ones, else a result
///   describing the given maps; in both, `compared_with_automatic_maps`, `automatic_maps_computed`,
///   `automatic_maps_kept`, `given_maps_distortion`, `automatic_maps_distortion` and the times of
///   the whole comparison
/// \throws Invalid_map_error for maps of the wrong size or with entries out of range, and the
///   exceptions of automatic_initial_maps()
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename TriangleMesh2,
          typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result compare_with_automatic_maps(const TriangleMesh1& tm1, const TriangleMesh2& tm2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np = parameters::default_values())
{
  return internal::repair_given_maps_of_meshes<ConcurrencyTag>(tm1, tm2, map_12, map_21, np, false, true);
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// compare_with_automatic_maps() on two prepared shapes (maps indexed as the shapes' vertices),
/// using their flat meshes, spectra and kept initialisation descriptors as automatic_initial_maps()
/// on shapes does.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh1, typename Tag1,
          typename TriangleMesh2, typename Tag2, typename NamedParameters = parameters::Default_named_parameters>
Automatic_initialization_result compare_with_automatic_maps(const Correspondence_shape<TriangleMesh1, Tag1>& shape_1,
                                                            const Correspondence_shape<TriangleMesh2, Tag2>& shape_2,
                                                            std::vector<std::size_t>& map_12,
                                                            std::vector<std::size_t>& map_21,
                                                            const NamedParameters& np = parameters::default_values())
{
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  return internal::repair_given_maps_of_sources<ConcurrencyTag>(
      internal::initialization_mesh_source(shape_1.data()), internal::initialization_mesh_source(shape_2.data()),
      internal::given_maps_settings(np, true), map_12, map_21, false, start);
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_AUTOMATIC_INITIALIZATION_H
