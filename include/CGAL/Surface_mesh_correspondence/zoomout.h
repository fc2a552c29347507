// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// ZoomOut: spectral upsampling of a functional map (Melzi, Ren, Rodola, Sharma, Wonka and
// Ovsjanikov, "ZoomOut: spectral upsampling for efficient shape correspondence", SIGGRAPH Asia
// 2019), alone or on a pair of maps coupled by a bijectivity term in the embedding.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_ZOOMOUT_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_ZOOMOUT_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/functional_map.h>
#include <CGAL/Surface_mesh_correspondence/internal/nearest_neighbors.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>

#include <CGAL/assertions.h>
#include <CGAL/tags.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

namespace internal {

/// Defaults of the ZoomOut schedule.
constexpr int default_zoomout_final_size = 100;
constexpr int default_zoomout_step = 5;

/// The ZoomOut schedule and options.
struct Zoomout_settings
{
  int final_size = default_zoomout_final_size;  ///< k_final
  int step = default_zoomout_step;              ///< basis growth per iteration
  /// Weight of the landmark rows in the least-squares fits (relative to the unit total mass).
  double landmark_weight = 1.0;
  /// Coupled mode only: weight alpha^2 of the bijectivity coordinates of the joint embedding.
  double bijectivity_weight = 1.0;
  /// Multiplier of the feature coordinates at the last step relative to the first (linear in
  /// between); 1 keeps them constant.
  double feature_final_ratio = 1.0;
};

/// Per-vertex features appended to the spectral embeddings of ZoomOut (e.g. weighted
/// descriptors): the nearest neighbour of [Phi_S(x) C, F_S(x)] among [Phi_T(y), F_T(y)].
struct Zoomout_features
{
  const Eigen::MatrixXd* source = nullptr;  ///< n_S x d, or null
  const Eigen::MatrixXd* target = nullptr;  ///< n_T x d, or null
  bool empty() const { return source == nullptr || target == nullptr || source->cols() == 0; }
};

/// The feature multiplier at step s of `steps` (0-based, the last one is steps - 1).
inline double zoomout_feature_scale(const Zoomout_settings& settings, std::size_t s, std::size_t steps)
{
  if(steps <= 1) return 1.0;
  const double t = double(s) / double(steps - 1);
  return (1.0 - t) + t * settings.feature_final_ratio;
}

/// [left, scale * features] (either may be empty).
inline Eigen::MatrixXd append_features(Eigen::MatrixXd left, const Eigen::MatrixXd* features, double scale)
{
  if(!features || features->cols() == 0 || scale == 0) return left;
  if(left.cols() == 0) return scale * (*features);
  const Eigen::Index c = left.cols();
  left.conservativeResize(Eigen::NoChange, c + features->cols());
  left.rightCols(features->cols()) = scale * (*features);
  return left;
}

/// The basis sizes visited by ZoomOut from `initial_size`: initial, initial + step, ..., final.
inline std::vector<int> zoomout_sizes(int initial_size, const Zoomout_settings& settings)
{
  std::vector<int> sizes{initial_size};
  while(sizes.back() < settings.final_size)
    sizes.push_back(std::min(settings.final_size, sizes.back() + std::max(1, settings.step)));
  return sizes;
}

/// Least-squares functional map (k_S x k_T) of a point map known on `rows` of the source: minimises
/// sum_x w_x |Phi_S(x) C - Phi_T(map(x))|^2 with w_x = `row_weights` (when all vertices are rows and
/// w = M', C = Phi_S^T M' Pi Phi_T) plus `landmark_weight` times the same on the landmark rows.
class Zoomout_fitter
{
public:
  /// `rows`: the source vertices where the map is evaluated (all vertices when empty).
  Zoomout_fitter(const Eigen::MatrixXd& source_basis, const Eigen::VectorXd& source_mass,
                 const std::vector<int>& rows, const std::vector<std::pair<int, int> >& landmarks,
                 double landmark_weight)
      : basis_(source_basis), rows_(rows), landmarks_(landmarks), landmark_weight_(landmark_weight)
  {
    const Eigen::Index n = source_basis.rows();
    if(rows_.empty())
    {
      weights_ = source_mass;
      all_rows_ = true;
    }
    else
    {
      // Samples stand for equal shares of the (unit) total area.
      weights_ = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(rows_.size()),
                                           source_mass.sum() / double(rows_.size()));
      all_rows_ = false;
    }
    (void)n;
  }

  /// The number of rows where the map must be known.
  std::size_t number_of_rows() const { return all_rows_ ? std::size_t(basis_.rows()) : rows_.size(); }
  /// The source vertex of row r.
  int row_vertex(std::size_t r) const { return all_rows_ ? static_cast<int>(r) : rows_[r]; }

  /// C (k_s x k_t) from the targets `map_rows[r]` of the rows.
  Eigen::MatrixXd fit(const std::vector<int>& map_rows, const Eigen::MatrixXd& target_basis, int ks,
                      int kt) const
  {
    const std::size_t m = number_of_rows();
    Eigen::MatrixXd sampled(m, ks), pulled(m, kt);
    for(std::size_t r = 0; r < m; ++r)
    {
      sampled.row(r) = basis_.row(row_vertex(r)).head(ks);
      pulled.row(r) = target_basis.row(map_rows[r]).head(kt);
    }
    const Eigen::MatrixXd weighted = weights_.asDiagonal() * sampled;
    Eigen::MatrixXd rhs = weighted.transpose() * pulled;
    const bool orthonormal = all_rows_ && landmarks_.empty();
    if(orthonormal) return rhs;  // Phi^T M Phi = I
    Eigen::MatrixXd gram(ks, ks);
    if(all_rows_)
      gram.setIdentity();
    else
      gram.noalias() = sampled.transpose() * weighted;
    for(const auto& l : landmarks_)
    {
      const Eigen::RowVectorXd phi = basis_.row(l.first).head(ks);
      gram.noalias() += landmark_weight_ * phi.transpose() * phi;
      rhs.noalias() += landmark_weight_ * phi.transpose() * target_basis.row(l.second).head(kt);
    }
    gram.diagonal().array() += 1e-10;
    return gram.llt().solve(rhs);
  }

private:
  const Eigen::MatrixXd& basis_;
  std::vector<int> rows_;
  std::vector<std::pair<int, int> > landmarks_;
  double landmark_weight_;
  Eigen::VectorXd weights_;
  bool all_rows_ = true;
};

/// Nearest neighbours of the rows `rows` (all when empty) of `query_embedding` among
/// `data_embedding`; landmark rows are then forced to their targets.
template <typename ConcurrencyTag>
void zoomout_nearest(const Eigen::MatrixXd& query_embedding, const Nearest_neighbor_search& search,
                     const Zoomout_fitter& fitter, const std::vector<std::pair<int, int> >& landmarks,
                     std::vector<int>& map_rows)
{
  const std::size_t m = fitter.number_of_rows();
  map_rows.resize(m);
  if(m == std::size_t(query_embedding.rows()))
    search.query<ConcurrencyTag>(query_embedding, map_rows.data());
  else
  {
    Eigen::MatrixXd q(m, query_embedding.cols());
    for(std::size_t r = 0; r < m; ++r) q.row(r) = query_embedding.row(fitter.row_vertex(r));
    search.query<ConcurrencyTag>(q, map_rows.data());
  }
  if(!landmarks.empty())
  {
    // Landmark rows (only where the landmark is one of the rows).
    for(std::size_t r = 0; r < m; ++r)
      for(const auto& l : landmarks)
        if(fitter.row_vertex(r) == l.first) map_rows[r] = l.second;
  }
}

/// The same among the rows of `data_embedding`.
template <typename ConcurrencyTag>
void zoomout_nearest(const Eigen::MatrixXd& query_embedding, const Eigen::MatrixXd& data_embedding,
                     const Zoomout_fitter& fitter, const std::vector<std::pair<int, int> >& landmarks,
                     std::vector<int>& map_rows)
{
  zoomout_nearest<ConcurrencyTag>(query_embedding, Nearest_neighbor_search(data_embedding), fitter, landmarks,
                                  map_rows);
}

/// One-direction ZoomOut on unit-area bases (n x K, K >= final size): from the k0 x k0 map
/// `initial`, alternates T = NN(Phi_S C, Phi_T) on the rows and C = fit(T) with the basis grown by
/// `step`, and returns the final C (k_final x k_final); `map` receives the point map of all
/// source vertices, or with `final_on_rows` only of the rows (map[r] for row r).
template <typename ConcurrencyTag>
Eigen::MatrixXd zoomout_refine(const Eigen::MatrixXd& source_basis, const Eigen::VectorXd& source_mass,
                               const Eigen::MatrixXd& target_basis, const Eigen::MatrixXd& initial,
                               const Zoomout_settings& settings, const std::vector<int>& rows,
                               const std::vector<std::pair<int, int> >& landmarks, std::vector<int>& map,
                               const Zoomout_features& features = Zoomout_features(),
                               bool final_on_rows = false)
{
  const int k0 = static_cast<int>(initial.rows());
  const std::vector<int> sizes = zoomout_sizes(k0, settings);
  const Zoomout_fitter fitter(source_basis, source_mass, rows, landmarks, settings.landmark_weight);
  const Zoomout_fitter full(source_basis, source_mass, std::vector<int>(), landmarks, settings.landmark_weight);
  Eigen::MatrixXd C = initial;
  std::vector<int> map_rows;
  for(std::size_t s = 0; s < sizes.size(); ++s)
  {
    const bool last = s + 1 == sizes.size();
    const double f = features.empty() ? 0.0 : zoomout_feature_scale(settings, s, sizes.size());
    const Eigen::MatrixXd query = append_features(source_basis.leftCols(C.rows()) * C, features.source, f);
    const Eigen::MatrixXd data = append_features(target_basis.leftCols(C.cols()), features.target, f);
    if(last)
    {
      zoomout_nearest<ConcurrencyTag>(query, data, final_on_rows ? fitter : full, landmarks, map);
      break;
    }
    zoomout_nearest<ConcurrencyTag>(query, data, fitter, landmarks, map_rows);
    C = fitter.fit(map_rows, target_basis, sizes[s + 1], sizes[s + 1]);
  }
  return C;
}

/// Coupled ZoomOut of the two maps of a pair: the map 1 -> 2 is the nearest neighbour in the joint
/// embedding [Phi_1 C_12, a Phi_1] among [Phi_2, a Phi_2 C_21] (a^2 = bijectivity_weight), which
/// favours maps that the current 2 -> 1 map inverts, and symmetrically; both functional maps are
/// then refitted one size up. `C12` (k1 x k2) and `C21` (k2 x k1) are replaced by the final maps.
/// Features (F_1 for mesh 1, F_2 for mesh 2) are appended to both embeddings.
///
/// The search does not form the joint embeddings: the inner product of a query [Phi_1(x) C_12,
/// a Phi_1(x)] with a data point [Phi_2(y), a Phi_2(y) C_21] is Phi_1(x) (C_12 + a^2 C_21^T)
/// Phi_2(y)^T, so the nearest y is found among the rows Phi_2(y) (k2 coordinates instead of
/// k2 + k1) for the query Phi_1(x) (C_12 + a^2 C_21^T), with the data norms |Phi_2(y)|^2 +
/// a^2 |Phi_2(y) C_21|^2 (Nearest_neighbor_search::build() with extra norms). This halves the
/// products that dominate the cost; the maps are those of the joint embeddings up to the
/// rounding of near ties.
template <typename ConcurrencyTag>
void coupled_zoomout_refine(const Eigen::MatrixXd& basis1, const Eigen::VectorXd& mass1,
                            const Eigen::MatrixXd& basis2, const Eigen::VectorXd& mass2,
                            Eigen::MatrixXd& C12, Eigen::MatrixXd& C21, const Zoomout_settings& settings,
                            const std::vector<int>& rows1, const std::vector<int>& rows2,
                            const std::vector<std::pair<int, int> >& landmarks, std::vector<int>& map12,
                            std::vector<int>& map21, const Zoomout_features& features = Zoomout_features())
{
  const int k0 = static_cast<int>(C12.rows());
  const std::vector<int> sizes = zoomout_sizes(k0, settings);
  std::vector<std::pair<int, int> > landmarks21;
  for(const auto& l : landmarks) landmarks21.emplace_back(l.second, l.first);
  const Zoomout_fitter fitter1(basis1, mass1, rows1, landmarks, settings.landmark_weight);
  const Zoomout_fitter fitter2(basis2, mass2, rows2, landmarks21, settings.landmark_weight);
  const Zoomout_fitter full1(basis1, mass1, std::vector<int>(), landmarks, settings.landmark_weight);
  const Zoomout_fitter full2(basis2, mass2, std::vector<int>(), landmarks21, settings.landmark_weight);
  const double a2 = std::max(0.0, settings.bijectivity_weight);
  std::vector<int> rows_map12, rows_map21;
  for(std::size_t s = 0;; ++s)
  {
    const bool last = s + 1 == sizes.size();
    const double f = features.empty() ? 0.0 : zoomout_feature_scale(settings, s, sizes.size());
    // Per mesh, the query Phi (C + a^2 C'^T) (on the rows only, but in the last iteration) and
    // the data norms of the joint embedding's bijectivity part, a^2 |Phi C|^2, for both meshes
    // concurrently.
    Eigen::MatrixXd q1, q2;
    Nearest_neighbor_search search1, search2;
    auto prepare = [a2, f, last](const Eigen::MatrixXd& basis, const std::vector<int>& rows, const Eigen::MatrixXd& C,
                                 const Eigen::MatrixXd& C_back, const Eigen::MatrixXd* own_features,
                                 Eigen::MatrixXd& query, Nearest_neighbor_search& search) {
      const Eigen::Index k = C.rows();
      const Eigen::MatrixXd combined = C + a2 * C_back.transpose();
      if(last || rows.empty())
        query = append_features(basis.leftCols(k) * combined, own_features, f);
      else
      {
        const Eigen::Index m = Eigen::Index(rows.size());
        const bool with_features = own_features && own_features->cols() > 0;
        Eigen::MatrixXd sampled(m, k), sampled_features(m, with_features ? own_features->cols() : 0);
        for(Eigen::Index r = 0; r < m; ++r)
        {
          sampled.row(r) = basis.row(rows[std::size_t(r)]).head(k);
          if(with_features) sampled_features.row(r) = own_features->row(rows[std::size_t(r)]);
        }
        query = append_features(sampled * combined, &sampled_features, f);
      }
      // The data side of this mesh (queried by the other one): [Phi, f F] with the norms of a Phi C.
      const Eigen::VectorXd extra = a2 * (basis.leftCols(k) * C).rowwise().squaredNorm();
      search.build(append_features(basis.leftCols(k), own_features, f), extra);
    };
    invoke_both<ConcurrencyTag>([&] { prepare(basis1, rows1, C12, C21, features.source, q1, search1); },
                                [&] { prepare(basis2, rows2, C21, C12, features.target, q2, search2); });
    CGAL_assertion(q1.cols() == search2.dimension() && q2.cols() == search1.dimension());
    if(last)
    {
      zoomout_nearest<ConcurrencyTag>(q1, search2, full1, landmarks, map12);
      zoomout_nearest<ConcurrencyTag>(q2, search1, full2, landmarks21, map21);
      return;
    }
    zoomout_nearest<ConcurrencyTag>(q1, search2, fitter1, landmarks, rows_map12);
    zoomout_nearest<ConcurrencyTag>(q2, search1, fitter2, landmarks21, rows_map21);
    invoke_both<ConcurrencyTag>([&] { C12 = fitter1.fit(rows_map12, basis2, sizes[s + 1], sizes[s + 1]); },
                                [&] { C21 = fitter2.fit(rows_map21, basis1, sizes[s + 1], sizes[s + 1]); });
  }
}

} // namespace internal

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_ZOOMOUT_H
