// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One pass of the automatic initialisation: the candidate fits, their short ZoomOut and scores,
// the choice of the best ones and the ZoomOut of the chosen maps to the pass size
// (single_pass_initial_maps()), and the growth of the kept maps to the final size.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CANDIDATE_MAPS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CANDIDATE_MAPS_H

#include <CGAL/Surface_mesh_correspondence/Automatic_initialization_result.h>
#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/functional_map_fitting.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_distortion.h>
#include <CGAL/Surface_mesh_correspondence/internal/initialization_settings.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/zoomout.h>

#include <CGAL/tags.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

/// ZoomOut of both functional maps of a pair (unit-area bases and masses), coupled or one
/// direction at a time as `coupled_zoomout` says: C12 and C21 are replaced by the final maps,
/// t12 and t21 receive the point maps of all vertices.
template <typename ConcurrencyTag>
void zoomout_pair(const Eigen::MatrixXd& basis1, const Eigen::VectorXd& mass1, const Eigen::MatrixXd& basis2,
                  const Eigen::VectorXd& mass2, const Initialization_settings& s, const Zoomout_settings& zs,
                  const std::vector<int>& rows1, const std::vector<int>& rows2,
                  const std::vector<std::pair<int, int> >& landmarks, Eigen::MatrixXd& C12, Eigen::MatrixXd& C21,
                  std::vector<int>& t12, std::vector<int>& t21, const Zoomout_features& features12 = Zoomout_features(),
                  const Zoomout_features& features21 = Zoomout_features())
{
  if(s.coupled_zoomout)
  {
    coupled_zoomout_refine<ConcurrencyTag>(basis1, mass1, basis2, mass2, C12, C21, zs, rows1, rows2, landmarks, t12,
                                           t21, features12);
    return;
  }
  std::vector<std::pair<int, int> > landmarks21;
  for(const auto& l : landmarks) landmarks21.emplace_back(l.second, l.first);
  C12 = zoomout_refine<ConcurrencyTag>(basis1, mass1, basis2, C12, zs, rows1, landmarks, t12, features12);
  C21 = zoomout_refine<ConcurrencyTag>(basis2, mass2, basis1, C21, zs, rows2, landmarks21, t21, features21);
}

/// Mean normalised Euclidean cycle error and fixed-point fraction of x -> back(forth(x)).
inline void cycle_statistics(const Indexed_mesh& m, const std::vector<int>& forth,
                             const std::vector<int>& back, double& error, double& fixed)
{
  const double scale = 1.0 / std::sqrt(m.total_area);
  double e = 0;
  std::size_t f = 0;
  for(std::size_t x = 0; x < forth.size(); ++x)
  {
    const int y = back[forth[x]];
    if(y == int(x)) ++f;
    e += (m.points.row(x) - m.points.row(y)).norm() * scale;
  }
  error = e / double(forth.size());
  fixed = double(f) / double(forth.size());
}

/// The area-weighted fraction of the triangles of `source` (with three distinct images) whose
/// image under `map` has the orientation of `target` (its vertex normals): about 1 for an
/// orientation-preserving map, 0 for a mirror map, 1/2 for a scrambled one.
inline double orientation_agreement(const Indexed_mesh& source, const Indexed_mesh& target,
                                    const Indexed_mesh::Points& target_normals, const std::vector<int>& map)
{
  double agree = 0, total = 0;
  for(int t = 0; t < source.number_of_triangles(); ++t)
  {
    const int orientation = image_orientation(source, target, target_normals, map, t);
    if(orientation < 0) continue;
    const double w = source.triangle_areas[t];
    total += w;
    if(orientation == 1) agree += w;
  }
  return total > 0 ? agree / total : 0.5;
}

/// Stores the final maps of a pass (or of grow_initial_maps()) and their cycle statistics,
/// orientation agreement and functional maps in `result`.
inline void set_initial_maps(const Indexed_mesh& m1, const Indexed_mesh& m2, const std::vector<int>& t12,
                             const std::vector<int>& t21, const Eigen::MatrixXd& C12, const Eigen::MatrixXd& C21,
                             std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                             Automatic_initialization_result& result)
{
  const double n1 = double(m1.number_of_vertices()), n2 = double(m2.number_of_vertices());
  double e1, f1, e2, f2;
  cycle_statistics(m1, t12, t21, e1, f1);
  cycle_statistics(m2, t21, t12, e2, f2);
  result.cycle_error = (e1 * n1 + e2 * n2) / (n1 + n2);
  result.cycle_fixed_fraction = (f1 * n1 + f2 * n2) / (n1 + n2);
  result.orientation_agreement = 0.5 * (orientation_agreement(m1, m2, vertex_normals(m2), t12) +
                                        orientation_agreement(m2, m1, vertex_normals(m1), t21));
  result.functional_map_12 = C12;
  result.functional_map_21 = C21;
  map_12.assign(t12.begin(), t12.end());
  map_21.assign(t21.begin(), t21.end());
}

/// The data that the steps of single_pass_initial_maps() share: the unit-area bases, masses and
/// eigenvalues, the normalised descriptors (with the landmark maps) and their column weights, the
/// reduced terms at the largest candidate size, the samplings and the ZoomOut features.
struct Initialization_pass_data
{
  const Indexed_mesh* m1 = nullptr;
  const Indexed_mesh* m2 = nullptr;
  int kf = 0, kmax = 0;  ///< zoomout_final_size and largest_candidate_size()
  std::vector<std::pair<int, int> > landmarks, landmarks21;  ///< (mesh 1, mesh 2) and reversed
  double A1 = 0, A2 = 0;
  Eigen::MatrixXd basis1, basis2;
  Eigen::VectorXd mass1, mass2, values1, values2;
  Eigen::MatrixXd D1, D2;
  Eigen::VectorXd column_weights;
  /// -1 for meshes of opposite orientations (see signed_volume()).
  int orientation_sign = 1;
  std::vector<Eigen::Index> operator_columns;
  Eigen::Index signed_begin = 0, signed_count = 0;  ///< the signed descriptor columns
  Functional_map_shape_terms T1, T2;
  const Initialization_pass_cache* cache = nullptr;
  Eigen::VectorXd feature_weights;
  Eigen::MatrixXd features1, features2;  ///< ZoomOut descriptor features (see prepare_pass_features())
  /// ZoomOut features: the weighted distance fields of the anchor landmarks (see
  /// prepare_landmark_distances()).
  Eigen::MatrixXd distances1, distances2;
  /// The chirality columns among them (see prepare_landmark_distances()).
  Eigen::Index chirality_begin = 0, chirality_count = 0;
  Zoomout_settings select_settings;      ///< the short ZoomOut to the selection size
};

/// One candidate of single_pass_initial_maps(): a fit configuration in one orientation hypothesis
/// (or the inverses of the maps of such a fit), its maps after the short ZoomOut and its scores.
struct Initialization_candidate
{
  Fit_candidate config;
  int sign;
  int inverse_of;               // -1: a fit; else the index of the fit whose maps it inverts
  Eigen::MatrixXd C12, C21;     // after the short ZoomOut
  std::vector<int> images12, images21;  // of the distortion samples
  double score12 = 0, score21 = 0;
};

/// Checks that the descriptors of both shapes have the columns of `layout` and finite values.
inline void check_pass_descriptors(const Initialization_shape& shape1, const Initialization_shape& shape2,
                                   const Initialization_descriptor_layout& layout)
{
  for(const Initialization_shape* shape : {&shape1, &shape2})
    if(shape->descriptors->cols() != layout.total() || !shape->descriptors->allFinite())
      throw Invalid_parameter_error("automatic_initial_maps: the descriptors have " +
                                    std::to_string(shape->descriptors->cols()) + " columns, " +
                                    std::to_string(layout.total()) +
                                    " expected (compute them with initialization_descriptors() and "
                                    "the same settings), or non-finite values");
}

/// The landmarks of the settings as pairs of vertices, checked against the numbers of vertices.
inline std::vector<std::pair<int, int> > pass_landmarks(const Initialization_settings& s, int n1, int n2)
{
  std::vector<std::pair<int, int> > landmarks;
  for(const auto& l : s.landmarks)
  {
    if(l.first >= std::size_t(n1) || l.second >= std::size_t(n2))
      throw Invalid_parameter_error("automatic_initial_maps: landmark (" + std::to_string(l.first) +
                                    ", " + std::to_string(l.second) + ") is not a pair of vertices of "
                                    "mesh 1 (" + std::to_string(n1) + " vertices) and mesh 2 (" +
                                    std::to_string(n2) + " vertices)");
    landmarks.emplace_back(int(l.first), int(l.second));
  }
  return landmarks;
}

/// Unit-area bases, masses and eigenvalues of both shapes.
inline void prepare_pass_bases(const Initialization_shape& shape1, const Initialization_shape& shape2,
                               Initialization_pass_data& p)
{
  const Laplace_beltrami_spectrum& S1 = *shape1.spectrum;
  const Laplace_beltrami_spectrum& S2 = *shape2.spectrum;
  p.A1 = S1.total_area();
  p.A2 = S2.total_area();
  p.basis1 = unit_area_basis(S1, p.kf);
  p.basis2 = unit_area_basis(S2, p.kf);
  p.mass1 = unit_area_mass(S1);
  p.mass2 = unit_area_mass(S2);
  p.values1 = S1.eigenvalues().head(p.kf) * p.A1;
  p.values2 = S2.eigenvalues().head(p.kf) * p.A2;
}

/// Appends the landmark wave kernel maps (normalised, of weight landmark_descriptor_weight) to the
/// descriptors of both shapes.
template <typename ConcurrencyTag>
void append_landmark_descriptors(const Initialization_settings& s, Initialization_pass_data& p)
{
  std::vector<int> points1, points2;
  for(const auto& l : p.landmarks)
  {
    points1.push_back(l.first);
    points2.push_back(l.second);
  }
  Eigen::MatrixXd L1, L2;
  invoke_both<ConcurrencyTag>(
      [&] { L1 = landmark_wave_kernel_maps(p.basis1, p.values1, points1, s.number_of_landmark_energies); },
      [&] { L2 = landmark_wave_kernel_maps(p.basis2, p.values2, points2, s.number_of_landmark_energies); });
  normalize_descriptor_columns(L1, p.mass1);
  normalize_descriptor_columns(L2, p.mass2);
  const Eigen::Index d = p.D1.cols(), dl = L1.cols();
  p.D1.conservativeResize(Eigen::NoChange, d + dl);
  p.D2.conservativeResize(Eigen::NoChange, d + dl);
  p.D1.rightCols(dl) = L1;
  p.D2.rightCols(dl) = L2;
  p.column_weights.conservativeResize(d + dl);
  p.column_weights.tail(dl).setConstant(s.landmark_descriptor_weight);
}

/// The descriptors of a pass: columns normalised to unit L2(M') norm on each shape, the operator
/// columns, the landmark maps, and the signed columns of mesh 2 negated for meshes of opposite
/// orientations.
template <typename ConcurrencyTag>
void prepare_pass_descriptors(const Initialization_shape& shape1, const Initialization_shape& shape2,
                              const Initialization_settings& s, const Initialization_descriptor_layout& layout,
                              Initialization_pass_data& p)
{
  p.D1 = *shape1.descriptors;
  p.D2 = *shape2.descriptors;
  p.column_weights = initialization_descriptor_weights(s);
  normalize_descriptor_columns(p.D1, p.mass1);
  normalize_descriptor_columns(p.D2, p.mass2);
  // Meshes of opposite orientations (closed, signed volumes of opposite signs): the map reverses
  // the orientation of the embedding, so the signed descriptors of mesh 2 change sign.
  p.orientation_sign = (signed_volume(*p.m1) * signed_volume(*p.m2) < 0) ? -1 : 1;
  // Operators for evenly spread plain descriptor columns with positive weight.
  p.operator_columns = operator_descriptor_columns(p.column_weights, layout.plain(), s.number_of_operator_descriptors);
  if(!p.landmarks.empty()) append_landmark_descriptors<ConcurrencyTag>(s, p);
  p.signed_begin = layout.plain();
  p.signed_count = Eigen::Index(layout.signed_pairs.size());
  if(p.orientation_sign < 0) p.D2.middleCols(p.signed_begin, p.signed_count) *= -1.0;
}

/// Reduced terms at the largest candidate size (smaller ones are leading blocks).
template <typename ConcurrencyTag>
void prepare_pass_terms(const Initialization_settings& s, Initialization_pass_data& p)
{
  invoke_both<ConcurrencyTag>(
      [&] {
        p.T1 = initialization_terms<ConcurrencyTag>(*p.m1, p.basis1.leftCols(p.kmax), p.mass1, p.values1.head(p.kmax),
                                                    p.A1, p.D1, p.operator_columns, s);
      },
      [&] {
        p.T2 = initialization_terms<ConcurrencyTag>(*p.m2, p.basis2.leftCols(p.kmax), p.mass2, p.values2.head(p.kmax),
                                                    p.A2, p.D2, p.operator_columns, s);
      });
}

/// The ZoomOut features of descriptors `D`: the columns of positive feature weight, scaled by it.
inline Eigen::MatrixXd zoomout_feature_columns(const Eigen::MatrixXd& D, const Eigen::VectorXd& feature_weights)
{
  std::vector<Eigen::Index> used;
  for(Eigen::Index c = 0; c < feature_weights.size(); ++c)
    if(feature_weights[c] > 0) used.push_back(c);
  Eigen::MatrixXd F(D.rows(), Eigen::Index(used.size()));
  for(std::size_t i = 0; i < used.size(); ++i) F.col(Eigen::Index(i)) = feature_weights[used[i]] * D.col(used[i]);
  return F;
}

/// The ZoomOut feature weights and features of both shapes, and the settings of the short ZoomOut.
inline void prepare_pass_features(const Initialization_settings& s, Initialization_pass_data& p)
{
  // Feature weights: sqrt(w_c / sum w) times the ZoomOut descriptor weight, for all columns or the
  // signed ones only. Without it, the signed columns in the passes with anchor landmarks (see
  // Initialization_settings::landmark_orientation_weight).
  const bool anchored = std::min(s.anchor_landmarks, p.landmarks.size()) > 0 && s.landmark_distance_weight > 0;
  const double weight = s.zoomout_descriptor_weight > 0      ? s.zoomout_descriptor_weight
                        : anchored && p.signed_count > 0 ? s.landmark_orientation_weight
                                                         : 0.0;
  p.feature_weights = p.column_weights;
  if((s.zoomout_signed_features_only || s.zoomout_descriptor_weight <= 0) && p.signed_count > 0)
  {
    p.feature_weights.setZero();
    p.feature_weights.segment(p.signed_begin, p.signed_count) = p.column_weights.segment(p.signed_begin, p.signed_count);
  }
  if(p.feature_weights.sum() > 0)
    p.feature_weights = (p.feature_weights / p.feature_weights.sum()).cwiseSqrt() * weight;
  if(weight > 0)
  {
    p.features1 = zoomout_feature_columns(p.D1, p.feature_weights);
    p.features2 = zoomout_feature_columns(p.D2, p.feature_weights);
  }
  p.select_settings = initialization_zoomout_settings(s, s.zoomout_step, selection_basis_size(s));
}

/// The geodesic distance fields of `sources` on the mesh of `g` (fast marching), times
/// `weight / scale`: column l is the field of sources[l].
template <typename ConcurrencyTag>
Eigen::MatrixXd landmark_distance_fields(const Fast_marching_geometry& g, const std::vector<int>& sources,
                                         double scale, double weight)
{
  const int n = g.number_of_vertices();
  Eigen::MatrixXd F(n, Eigen::Index(sources.size()));
  parallel_for_ranges<ConcurrencyTag>(sources.size(), [&](std::size_t begin, std::size_t end) {
    Fast_marching_workspace w(g);
    for(std::size_t l = begin; l < end; ++l)
    {
      w.run(sources[l]);
      for(int v = 0; v < n; ++v) F(v, Eigen::Index(l)) = weight * w.distance(v) / scale;
    }
  });
  return F;
}

/// The chirality features of landmarks on `mesh`: from the distance fields `fields` (n x L, column
/// l the geodesic distance to landmark l divided by the square root of the area), one column per
/// pair l < l' (in the order (0, 1), (0, 2), ..., (1, 2), ...): at each vertex the turn from the
/// direction away from landmark l to the direction away from landmark l', seen from the normal,
/// <n, grad d_l x grad d_l'> = the sine of the angle between them (gradient_cross_products(),
/// on the mesh scaled to unit area), smoothed by projection on the first `smoothing` eigenfunctions
/// of `spectrum` (none for 0), times `weight` / sqrt(number of pairs). The distance fields keep
/// the mirror image of a part about a plane of symmetry (a torso turned front to back, a limb
/// about its axis); these change sign there, and correspond wherever the landmarks do.
inline Eigen::MatrixXd landmark_chirality_fields(const Indexed_mesh& mesh, const Laplace_beltrami_spectrum& spectrum,
                                                 const Eigen::MatrixXd& fields, int smoothing, double weight)
{
  std::vector<std::pair<int, int> > pairs;
  for(int i = 0; i < int(fields.cols()); ++i)
    for(int j = i + 1; j < int(fields.cols()); ++j) pairs.emplace_back(i, j);
  if(pairs.empty()) return Eigen::MatrixXd(fields.rows(), 0);
  const Eigen::MatrixXd g = gradient_cross_products(mesh, fields, pairs, 1.0 / std::sqrt(spectrum.total_area()));
  return smooth_on_eigenfunctions(spectrum, g, smoothing) * (weight / std::sqrt(double(pairs.size())));
}

/// The ZoomOut features of the anchor landmarks (the first `anchor_landmarks` landmarks, with
/// `landmark_distance_weight` > 0): their geodesic distance fields on both meshes, divided by the
/// square root of the mesh area and weighted. A vertex and its image are then near in the
/// embeddings only when they are about as far from each landmark. The descriptor fits and the
/// pinned landmark rows do not ensure that on pairs far from isometric: from the true extremities
/// of the TOSCA_nonIso pairs, whole limbs were still mirrored.
template <typename ConcurrencyTag>
void prepare_landmark_distances(const Initialization_shape& shape1, const Initialization_shape& shape2,
                                const Initialization_settings& s, Initialization_pass_data& p)
{
  const std::size_t anchors = std::min(s.anchor_landmarks, p.landmarks.size());
  if(anchors == 0 || s.landmark_distance_weight <= 0) return;
  std::vector<int> sources1, sources2;
  for(std::size_t l = 0; l < anchors; ++l)
  {
    sources1.push_back(p.landmarks[l].first);
    sources2.push_back(p.landmarks[l].second);
  }
  // The fast marching geometry of the distortion samples when there is one.
  auto fields = [&](const Initialization_shape& shape, const Initialization_sampling& sampling,
                    const std::vector<int>& sources, Eigen::MatrixXd& out) {
    const double scale = std::sqrt(shape.spectrum->total_area());
    if(sampling.geodesics.mesh == shape.mesh)
      out = landmark_distance_fields<ConcurrencyTag>(sampling.geodesics, sources, scale, s.landmark_distance_weight);
    else
      out = landmark_distance_fields<ConcurrencyTag>(Fast_marching_geometry(*shape.mesh), sources, scale,
                                                     s.landmark_distance_weight);
  };
  invoke_both<ConcurrencyTag>([&] { fields(shape1, p.cache->first, sources1, p.distances1); },
                              [&] { fields(shape2, p.cache->second, sources2, p.distances2); });
  if(s.landmark_chirality_weight <= 0 || anchors < 2) return;
  // The chirality features (scaled back from the weighted fields: their gradients are
  // landmark_distance_weight times unit vectors), appended to the distance fields.
  const double field_weight = s.landmark_distance_weight;
  auto chirality = [&](const Initialization_shape& shape, Eigen::MatrixXd& fields) {
    Eigen::MatrixXd g = landmark_chirality_fields(*shape.mesh, *shape.spectrum, fields / field_weight,
                                                  s.signed_descriptor_smoothing, s.landmark_chirality_weight);
    fields.conservativeResize(Eigen::NoChange, fields.cols() + g.cols());
    fields.rightCols(g.cols()) = g;
  };
  invoke_both<ConcurrencyTag>([&] { chirality(shape1, p.distances1); }, [&] { chirality(shape2, p.distances2); });
  p.chirality_begin = Eigen::Index(anchors);
  p.chirality_count = p.distances1.cols() - p.chirality_begin;
  // Meshes of opposite orientations: the turns of mesh 2 change sign.
  if(p.orientation_sign < 0) p.distances2.middleCols(p.chirality_begin, p.chirality_count) *= -1.0;
}

/// The candidates: every configuration (and, with landmarks, both orientations unless
/// landmark_orientation fixes one), each to be fitted in both directions, refined by a short
/// ZoomOut to the selection size and scored.
inline std::vector<Initialization_candidate> pass_candidates(const Initialization_settings& s,
                                                             const Initialization_pass_data& p)
{
  std::vector<Initialization_candidate> candidates;
  const std::vector<int> signs = p.landmarks.empty()           ? std::vector<int>{1}
                                 : s.landmark_orientation != 0 ? std::vector<int>{s.landmark_orientation}
                                                               : std::vector<int>{1, -1};
  for(int sign : signs)
    for(const Fit_candidate& c : s.candidates)
      if(c.basis_size <= p.kf) candidates.push_back({c, sign, -1, {}, {}, {}, {}});
  return candidates;
}

/// The weighted descriptor distance between matched sample vertices: row `rows[r]` of `Da` (row
/// r when `rows` is empty) against row `map_rows[r]` of `Db`, averaged.
inline double descriptor_match_score(const Eigen::MatrixXd& Da, const Eigen::MatrixXd& Db, const std::vector<int>& rows,
                                     const std::vector<int>& map_rows, const Eigen::VectorXd& column_weights)
{
  double total = 0;
  for(std::size_t r = 0; r < map_rows.size(); ++r)
    total += (Da.row(rows.empty() ? int(r) : rows[r]) - Db.row(map_rows[r])).cwiseAbs2().dot(column_weights);
  return total / (double(map_rows.size()) * column_weights.sum());
}

/// Short ZoomOut of both maps of a candidate on the samples, then the descriptor scores of the
/// sample matches (or the images of the distortion samples, scored once all candidates are known).
inline void zoom_and_score_candidate(const Initialization_settings& s, const Initialization_pass_data& p,
                                     Initialization_candidate& c, const Eigen::MatrixXd& C12,
                                     const Eigen::MatrixXd& C21)
{
  const Initialization_samples& samples1 = p.cache->first.samples;
  const Initialization_samples& samples2 = p.cache->second.samples;
  std::vector<int> t12, t21;
  c.C12 = zoomout_refine<CGAL::Sequential_tag>(p.basis1, p.mass1, p.basis2, C12, p.select_settings, samples1.rows,
                                               p.landmarks, t12, Zoomout_features(), true);
  c.C21 = zoomout_refine<CGAL::Sequential_tag>(p.basis2, p.mass2, p.basis1, C21, p.select_settings, samples2.rows,
                                               p.landmarks21, t21, Zoomout_features(), true);
  if(s.select_by_distortion)
  {
    for(int r : samples1.distortion_rows) c.images12.push_back(t12[r]);
    for(int r : samples2.distortion_rows) c.images21.push_back(t21[r]);
  }
  else
  {
    Eigen::MatrixXd F2 = p.D2;
    if(c.sign < 0) F2.middleCols(p.signed_begin, p.signed_count) *= -1.0;
    c.score12 = descriptor_match_score(p.D1, F2, samples1.rows, t12, p.column_weights);
    c.score21 = descriptor_match_score(F2, p.D1, samples2.rows, t21, p.column_weights);
  }
}

/// The fits of all candidates, one task per candidate and direction, the largest bases first (a
/// fit's cost grows steeply with k0, k0 = 60 is solved iteratively, so this keeps the threads busy
/// to the end), then the short ZoomOut and scores of each candidate.
template <typename ConcurrencyTag>
void fit_pass_candidates(const Initialization_settings& s, const Initialization_pass_data& p,
                         std::vector<Initialization_candidate>& candidates)
{
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd> > fitted(candidates.size());
  std::vector<std::size_t> fit_order(2 * candidates.size());
  std::iota(fit_order.begin(), fit_order.end(), std::size_t(0));
  std::stable_sort(fit_order.begin(), fit_order.end(), [&](std::size_t x, std::size_t y) {
    return candidates[x / 2].config.basis_size > candidates[y / 2].config.basis_size;
  });
  parallel_for_in_order<ConcurrencyTag>(fit_order.size(), [&](std::size_t t) {
    const std::size_t i = fit_order[t] / 2;
    const bool forward = fit_order[t] % 2 == 0;
    const Initialization_candidate& c = candidates[i];
    (forward ? fitted[i].first : fitted[i].second) =
        fit_candidate_map(p.T1, p.T2, c.config, c.sign, p.orientation_sign, p.signed_begin, p.signed_count,
                          p.column_weights, s, forward);
  });
  parallel_for<ConcurrencyTag>(candidates.size(), [&](std::size_t i) {
    zoom_and_score_candidate(s, p, candidates[i], fitted[i].first, fitted[i].second);
  });
}

/// The inverses of the fitted maps (C_21^T for 1 -> 2 and C_12^T for 2 -> 1, the maps being nearly
/// orthogonal) as candidates too, after their short ZoomOut: one direction often finds the right
/// map when the other does not.
template <typename ConcurrencyTag>
void add_inverse_candidates(const Initialization_settings& s, const Initialization_pass_data& p,
                            std::vector<Initialization_candidate>& candidates)
{
  const std::size_t fits = candidates.size();
  for(std::size_t i = 0; i < fits; ++i)
    candidates.push_back({candidates[i].config, candidates[i].sign, int(i), {}, {}, {}, {}});
  parallel_for<ConcurrencyTag>(fits, [&](std::size_t i) {
    Initialization_candidate& c = candidates[fits + i];
    zoom_and_score_candidate(s, p, c, candidates[i].C21.transpose(), candidates[i].C12.transpose());
  });
}

/// The distortion scores of all candidates: geodesic distances between all the images of the
/// distortion samples, then lookups (map_distortion()).
template <typename ConcurrencyTag>
void score_candidates_by_distortion(const Initialization_settings& s, const Initialization_pass_data& p,
                                    std::vector<Initialization_candidate>& candidates)
{
  const Initialization_pass_cache& cache = *p.cache;
  std::vector<int> all12, all21;
  for(const Initialization_candidate& c : candidates)
  {
    all12.insert(all12.end(), c.images12.begin(), c.images12.end());
    all21.insert(all21.end(), c.images21.begin(), c.images21.end());
  }
  Vertex_set_distances distances2, distances1;
  distances2.compute<ConcurrencyTag>(cache.second.geodesics, std::move(all12), std::sqrt(p.A2), &cache.second.rows);
  distances1.compute<ConcurrencyTag>(cache.first.geodesics, std::move(all21), std::sqrt(p.A1), &cache.first.rows);
  for(Initialization_candidate& c : candidates)
  {
    c.score12 = map_distortion(cache.first.sample_distances, distances2, c.images12);
    c.score21 = map_distortion(cache.second.sample_distances, distances1, c.images21);
  }
  if(s.verbose)
    std::cerr << "  distortion scores: " << distances2.size() << " and " << distances1.size()
              << " distinct sample images\n";
}

/// The candidate of orientation `sign` of lowest score in one direction (`forward`: 1 -> 2), the
/// first on ties; candidates.size() when there is none.
inline std::size_t best_candidate_with_sign(const std::vector<Initialization_candidate>& candidates, int sign,
                                            bool forward)
{
  std::size_t b = candidates.size();
  for(std::size_t i = 0; i < candidates.size(); ++i)
    if(candidates[i].sign == sign &&
       (b == candidates.size() ||
        (forward ? candidates[i].score12 < candidates[b].score12 : candidates[i].score21 < candidates[b].score21)))
      b = i;
  return b;
}

/// The candidates kept for 1 -> 2 and for 2 -> 1: the lowest scores (the first on ties). With
/// landmarks, both directions must agree on the orientation: when they do not, the orientation of
/// lower total score is kept.
inline std::pair<std::size_t, std::size_t> best_candidates(const std::vector<Initialization_candidate>& candidates,
                                                           bool with_landmarks)
{
  std::size_t best12 = 0, best21 = 0;
  for(std::size_t i = 1; i < candidates.size(); ++i)
  {
    if(candidates[i].score12 < candidates[best12].score12) best12 = i;
    if(candidates[i].score21 < candidates[best21].score21) best21 = i;
  }
  if(with_landmarks && candidates[best12].sign != candidates[best21].sign)
  {
    // Both directions must agree on the orientation: keep the one of lower total score.
    const std::size_t p12 = best_candidate_with_sign(candidates, 1, true);
    const std::size_t p21 = best_candidate_with_sign(candidates, 1, false);
    const std::size_t q12 = best_candidate_with_sign(candidates, -1, true);
    const std::size_t q21 = best_candidate_with_sign(candidates, -1, false);
    if(candidates[p12].score12 + candidates[p21].score21 <= candidates[q12].score12 + candidates[q21].score21)
    {
      best12 = p12;
      best21 = p21;
    }
    else
    {
      best12 = q12;
      best21 = q21;
    }
  }
  return {best12, best21};
}

/// Prints the configuration and the scores of every candidate to std::cerr.
inline void print_candidates(const std::vector<Initialization_candidate>& candidates)
{
  for(std::size_t i = 0; i < candidates.size(); ++i)
    std::cerr << "  candidate " << i << ": k0 " << candidates[i].config.basis_size << ", w_o "
              << candidates[i].config.orientation_weight << ", w_c " << candidates[i].config.commutativity_weight
              << ", sign " << candidates[i].sign
              << (candidates[i].inverse_of >= 0 ? " (inverse maps)" : "") << ": scores " << candidates[i].score12 << " "
              << candidates[i].score21 << "\n";
}

/// One pass of automatic_initial_maps() on precomputed shapes (flat mesh, spectrum with at least
/// zoomout_final_size eigenpairs, descriptors from initialization_descriptors() with the same
/// settings): fits, selection and coupled ZoomOut, without the tear repair.
template <typename ConcurrencyTag>
Automatic_initialization_result single_pass_initial_maps(const Initialization_shape& shape1,
                                                       const Initialization_shape& shape2,
                                                       const Initialization_settings& s,
                                                       std::vector<std::size_t>& map_12,
                                                       std::vector<std::size_t>& map_21,
                                                       Initialization_pass_cache* pass_cache = nullptr)
{
  typedef std::chrono::steady_clock Clock;
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  const Clock::time_point start = Clock::now();
  check_initialization_settings(s);
  Initialization_pass_data p;
  p.kf = s.zoomout_final_size;
  p.kmax = largest_candidate_size(s);
  check_initialization_shape(shape1, p.kf, "mesh 1");
  check_initialization_shape(shape2, p.kf, "mesh 2");
  p.m1 = shape1.mesh;
  p.m2 = shape2.mesh;
  const Initialization_descriptor_layout layout = initialization_descriptor_layout(s);
  check_pass_descriptors(shape1, shape2, layout);
  p.landmarks = pass_landmarks(s, p.m1->number_of_vertices(), p.m2->number_of_vertices());
  for(const auto& l : p.landmarks) p.landmarks21.emplace_back(l.second, l.first);

  Automatic_initialization_result result;
  result.passes = 1;
  prepare_pass_bases(shape1, shape2, p);

  // Descriptors, landmark maps and reduced terms.
  const Clock::time_point fit_start = Clock::now();
  prepare_pass_descriptors<ConcurrencyTag>(shape1, shape2, s, layout, p);
  prepare_pass_terms<ConcurrencyTag>(s, p);

  // Samples for the ZoomOut iterations and the distortion score (shared by all passes).
  Initialization_pass_cache own_cache;
  Initialization_pass_cache& cache = pass_cache ? *pass_cache : own_cache;
  prepare_pass_cache<ConcurrencyTag>(shape1, shape2, s, cache);
  p.cache = &cache;
  prepare_pass_features(s, p);
  prepare_landmark_distances<ConcurrencyTag>(shape1, shape2, s, p);

  // Candidates: fits of both directions for every configuration (and, with landmarks, for both
  // orientations), each refined by a short ZoomOut to the selection size and scored by the
  // geodesic distortion of its sample maps or the weighted descriptor distance between matched
  // sample vertices.
  std::vector<Initialization_candidate> candidates = pass_candidates(s, p);
  fit_pass_candidates<ConcurrencyTag>(s, p, candidates);
  s.notify_step();
  if(s.select_by_distortion)
  {
    add_inverse_candidates<ConcurrencyTag>(s, p, candidates);
    score_candidates_by_distortion<ConcurrencyTag>(s, p, candidates);
  }
  s.notify_step();
  const std::pair<std::size_t, std::size_t> best = best_candidates(candidates, !p.landmarks.empty());
  const std::size_t best12 = best.first, best21 = best.second;
  if(s.verbose) print_candidates(candidates);
  const int sign = candidates[best12].sign;
  result.orientation_sign = p.orientation_sign * sign;
  result.initial_basis_size = candidates[best12].config.basis_size;
  Eigen::MatrixXd C12 = candidates[best12].C12, C21 = candidates[best21].C21;
  result.selection_score = 0.5 * (candidates[best12].score12 + candidates[best21].score21);
  if(sign < 0)
  {
    p.D2.middleCols(p.signed_begin, p.signed_count) *= -1.0;
    if(p.features2.cols() > 0) p.features2 = zoomout_feature_columns(p.D2, p.feature_weights);
    p.distances2.middleCols(p.chirality_begin, p.chirality_count) *= -1.0;
  }
  result.functional_map_seconds = seconds_since(fit_start);
  if(s.verbose)
    std::cerr << "automatic_initial_maps: " << candidates.size() << " candidates in "
              << result.functional_map_seconds << " s; chosen " << best12 << " and " << best21
              << " (scores " << candidates[best12].score12 << ", " << candidates[best21].score21
              << "), orientation " << result.orientation_sign << "\n";

  // ZoomOut from the selection size to the pass size (grow_initial_maps() goes on to the final
  // size once the pass is chosen).
  const Clock::time_point zoom_start = Clock::now();
  const Zoomout_settings zs = initialization_zoomout_settings(s, s.zoomout_step, pass_final_size(s));
  // The descriptor features and the landmark distances.
  const Eigen::MatrixXd F1 = append_features(p.features1, &p.distances1, 1.0);
  const Eigen::MatrixXd F2 = append_features(p.features2, &p.distances2, 1.0);
  Zoomout_features features12, features21;
  if(F1.cols() > 0)
  {
    features12.source = features21.target = &F1;
    features12.target = features21.source = &F2;
  }
  std::vector<int> t12, t21;
  zoomout_pair<ConcurrencyTag>(p.basis1, p.mass1, p.basis2, p.mass2, s, zs, cache.first.samples.rows,
                               cache.second.samples.rows, p.landmarks, C12, C21, t12, t21, features12, features21);
  result.zoomout_seconds = seconds_since(zoom_start);
  result.final_basis_size = zs.final_size;
  set_initial_maps(*p.m1, *p.m2, t12, t21, C12, C21, map_12, map_21, result);
  s.notify_step();
  result.total_seconds = seconds_since(start);
  if(s.verbose)
    std::cerr << "automatic_initial_maps: ZoomOut to " << zs.final_size << " in " << result.zoomout_seconds
              << " s, cycle error " << result.cycle_error << ", fixed " << result.cycle_fixed_fraction
              << ", orientation agreement " << result.orientation_agreement << "\n";
  return result;
}

/// The last step of automatic_initial_maps(): the maps that were kept (computed by a pass with a
/// ZoomOut to pass_final_size()) grow on to zoomout_final_size by the same ZoomOut, started from
/// the pass's final functional maps, with the user's landmarks (not those of a repair pass: the
/// maps already follow them) and without descriptor features (zoomout_descriptor_weight, 0 by
/// default, applies to the passes only). Nothing happens when the maps are already of the final
/// size. The torn fraction and the sample distortion of the result stay those of the kept pass.
template <typename ConcurrencyTag>
void grow_initial_maps(const Initialization_shape& shape1, const Initialization_shape& shape2,
                       const Initialization_settings& s, const Initialization_pass_cache& cache,
                       std::vector<std::size_t>& map_12, std::vector<std::size_t>& map_21,
                       Automatic_initialization_result& result)
{
  const int kf = s.zoomout_final_size, k = int(result.functional_map_12.rows());
  if(k == 0 || k >= kf || result.functional_map_21.rows() != k) return;
  const auto start = std::chrono::steady_clock::now();
  const Indexed_mesh& m1 = *shape1.mesh;
  const Indexed_mesh& m2 = *shape2.mesh;
  const Eigen::MatrixXd basis1 = unit_area_basis(*shape1.spectrum, kf), basis2 = unit_area_basis(*shape2.spectrum, kf);
  const Eigen::VectorXd mass1 = unit_area_mass(*shape1.spectrum), mass2 = unit_area_mass(*shape2.spectrum);
  std::vector<std::pair<int, int> > landmarks;
  for(const auto& l : s.landmarks) landmarks.emplace_back(int(l.first), int(l.second));
  Eigen::MatrixXd C12 = result.functional_map_12, C21 = result.functional_map_21;
  std::vector<int> t12, t21;
  zoomout_pair<ConcurrencyTag>(basis1, mass1, basis2, mass2, s, initialization_zoomout_settings(s, s.zoomout_growth_step, kf),
                               cache.first.samples.rows, cache.second.samples.rows, landmarks, C12, C21, t12, t21);
  set_initial_maps(m1, m2, t12, t21, C12, C21, map_12, map_21, result);
  result.final_basis_size = kf;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.zoomout_seconds += seconds;
  if(s.verbose)
    std::cerr << "automatic_initial_maps: ZoomOut from " << k << " to " << kf << " in " << seconds
              << " s, cycle error " << result.cycle_error << ", fixed " << result.cycle_fixed_fraction << "\n";
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_CANDIDATE_MAPS_H
