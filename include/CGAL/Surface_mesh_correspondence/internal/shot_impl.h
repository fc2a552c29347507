// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// SHOT (Signature of Histograms of OrienTations) on the vertices of an Indexed_mesh.
// Implemented from F. Tombari, S. Salti, L. Di Stefano, "Unique signatures of histograms for local
// surface description", ECCV 2010, and "SHOT: Unique signatures of histograms for surface and
// texture description", CVIU 2014. The user-level documentation is in shot.h and doc/shot.md.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SHOT_IMPL_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SHOT_IMPL_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/Indexed_mesh.h>
#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>
#include <CGAL/Surface_mesh_correspondence/internal/vertex_normals.h>
#include <CGAL/Surface_mesh_correspondence/matching_settings.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

// ------------------------------------------------------------------------------------ layout

/// Number of azimuth, elevation and radial divisions of the spherical support, and of cosine bins.
constexpr int shot_azimuth_divisions = 8;
constexpr int shot_elevation_divisions = 2;
constexpr int shot_radial_divisions = 2;
constexpr int shot_cosine_bins = 11;
constexpr int shot_number_of_sectors =
    shot_azimuth_divisions * shot_elevation_divisions * shot_radial_divisions;  // 32
/// Length of a SHOT descriptor: 32 sectors x 11 cosine bins.
constexpr int shot_descriptor_size = shot_number_of_sectors * shot_cosine_bins;  // 352

/// Index of a value in the descriptor: the 11 cosine bins of a sector are consecutive, sectors
/// are ordered by radial shell (inner first), then elevation (lower hemisphere first), then
/// azimuth (counter-clockwise around z from -pi).
constexpr int shot_index(int radial, int elevation, int azimuth, int cosine)
{
  return ((radial * shot_elevation_divisions + elevation) * shot_azimuth_divisions + azimuth) *
             shot_cosine_bins +
         cosine;
}

/// Default support radius, relative to the square root of the total surface area.
/// Minimum number of neighbours (other vertices) of the support (see Shot_options).
constexpr int default_shot_minimum_neighbors = 10;
/// Default bound on the number of support points (see Shot_options::maximum_support_points).
constexpr std::size_t default_shot_maximum_support_points = 20000;
/// Area per point of a greedy Poisson-disk sample with spacing h, in units of h^2 (measured).
constexpr double poisson_disk_area_per_point = 1.7;
/// The support is enlarged to this factor times the distance to the k-th nearest vertex.
constexpr double shot_enlargement_factor = 1.25;

/// Parameters of the SHOT computation on an Indexed_mesh.
struct Shot_options
{
  /// Support radius relative to sqrt(total surface area): R = relative_radius * sqrt(area).
  double relative_radius = matching_defaults().shot_radius;
  /// k: the support radius of a vertex is max(R, 1.25 d_k), d_k being the distance to its k-th
  /// nearest other vertex, so that at least k vertices are used (all vertices on meshes with
  /// fewer than k + 1).
  int minimum_neighbors = default_shot_minimum_neighbors;
  /// Meshes with more vertices than this take their support points from a Poisson-disk
  /// subsample of the vertices (see poisson_disk_subsample) of about this size, with spacing
  /// sqrt(area / (1.7 * maximum_support_points)); this bounds the support size, hence the cost
  /// per vertex, on fine meshes. Smaller meshes, or 0, use every vertex.
  std::size_t maximum_support_points = default_shot_maximum_support_points;
};

/// Summary figures of one computation.
struct Shot_statistics
{
  double support_radius = 0;       ///< R, absolute
  double average_neighbors = 0;    ///< mean number of neighbours (other vertices) in the support
  std::size_t enlarged_supports = 0; ///< number of vertices whose support radius exceeds R
  std::size_t support_points = 0;    ///< vertices kept as support points (Poisson-disk sample)
};

// ------------------------------------------------------------------------------ uniform grid

/// Points bucketed in a uniform grid of cubic cells, for fixed-radius ball queries. Cells are
/// stored in CSR form, the points of a cell contiguously (positions copied next to their index).
class Uniform_point_grid
{
public:
  /// Buckets the points `points.row(i)` for i in `subset` (all points when `subset` is null).
  /// Queries report the indices i (rows of `points`).
  Uniform_point_grid(const Indexed_mesh::Points& points, double cell_size,
                     const std::vector<int>* subset = nullptr)
  {
    const std::size_t n = subset ? subset->size() : static_cast<std::size_t>(points.rows());
    auto row = [&](std::size_t k) { return subset ? (*subset)[k] : static_cast<int>(k); };
    lower_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d upper = Eigen::Vector3d::Zero();
    for(std::size_t k = 0; k < n; ++k)
    {
      const Eigen::Vector3d p = points.row(row(k)).transpose();
      if(k == 0) lower_ = upper = p;
      lower_ = lower_.cwiseMin(p);
      upper = upper.cwiseMax(p);
    }
    const Eigen::Vector3d extent = upper - lower_;
    diagonal_ = extent.norm();
    // At most about two cells per point: a tiny radius must not allocate a huge grid.
    const double max_cells = std::max(64.0, 2.0 * static_cast<double>(n));
    cell_ = cell_size > 0 ? cell_size : 1.0;
    auto cells_along = [&](int c) { return std::floor(extent[c] / cell_) + 1.0; };
    while(cells_along(0) * cells_along(1) * cells_along(2) > max_cells) cell_ *= 1.5;
    for(int c = 0; c < 3; ++c) dims_[c] = static_cast<int>(cells_along(c));
    const std::size_t number_of_cells =
        static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) * dims_[2];

    std::vector<int> cell_of(n);
    offsets_.assign(number_of_cells + 1, 0);
    for(std::size_t k = 0; k < n; ++k)
    {
      int c[3];
      for(int a = 0; a < 3; ++a) c[a] = coordinate(points(row(k), a), a);
      cell_of[k] = linear(c[0], c[1], c[2]);
      ++offsets_[static_cast<std::size_t>(cell_of[k]) + 1];
    }
    for(std::size_t c = 0; c < number_of_cells; ++c) offsets_[c + 1] += offsets_[c];
    xyz_.resize(3 * n);
    index_.resize(n);
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for(std::size_t k = 0; k < n; ++k)
    {
      const std::size_t slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[k])]++);
      index_[slot] = row(k);
      for(int a = 0; a < 3; ++a) xyz_[3 * slot + a] = points(row(k), a);
    }
  }

  /// Length of the diagonal of the bounding box of the points.
  double diagonal() const { return diagonal_; }

  /// Number of bucketed points; slots 0..size()-1 hold them in cell order.
  std::size_t size() const { return index_.size(); }
  /// Index (row of the input points) and position of the point in a slot.
  int index(std::size_t slot) const { return index_[slot]; }
  const double* position(std::size_t slot) const { return xyz_.data() + 3 * slot; }

  /// Calls `f(index, squared_distance, slot)` for every point at squared distance < r^2 from q,
  /// in an order that depends only on the points and q.
  template <typename F>
  void for_each_in_ball(const double* q, double r, F&& f) const
  {
    const double r2 = r * r;
    int lo[3], hi[3];
    for(int k = 0; k < 3; ++k)
    {
      lo[k] = coordinate(q[k] - r, k);
      hi[k] = coordinate(q[k] + r, k);
    }
    for(int z = lo[2]; z <= hi[2]; ++z)
      for(int y = lo[1]; y <= hi[1]; ++y)
      {
        // Cells lo[0]..hi[0] of this row are consecutive, so are their points.
        const int begin = offsets_[static_cast<std::size_t>(linear(lo[0], y, z))];
        const int end = offsets_[static_cast<std::size_t>(linear(hi[0], y, z)) + 1];
        const double* p = xyz_.data() + 3 * static_cast<std::size_t>(begin);
        for(int s = begin; s < end; ++s, p += 3)
        {
          const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
          const double d2 = dx * dx + dy * dy + dz * dz;
          if(d2 < r2) f(index_[static_cast<std::size_t>(s)], d2, static_cast<std::size_t>(s));
        }
      }
  }

  /// Whether `stop(index, squared_distance)` returns true for some point at squared distance
  /// < r^2 from q (the search ends at the first such point).
  template <typename F>
  bool any_in_ball(const double* q, double r, F&& stop) const
  {
    const double r2 = r * r;
    int lo[3], hi[3];
    for(int k = 0; k < 3; ++k)
    {
      lo[k] = coordinate(q[k] - r, k);
      hi[k] = coordinate(q[k] + r, k);
    }
    for(int z = lo[2]; z <= hi[2]; ++z)
      for(int y = lo[1]; y <= hi[1]; ++y)
      {
        const int begin = offsets_[static_cast<std::size_t>(linear(lo[0], y, z))];
        const int end = offsets_[static_cast<std::size_t>(linear(hi[0], y, z)) + 1];
        const double* p = xyz_.data() + 3 * static_cast<std::size_t>(begin);
        for(int s = begin; s < end; ++s, p += 3)
        {
          const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
          const double d2 = dx * dx + dy * dy + dz * dz;
          if(d2 < r2 && stop(index_[static_cast<std::size_t>(s)], d2)) return true;
        }
      }
    return false;
  }

private:
  int coordinate(double x, int axis) const
  {
    const double c = std::floor((x - lower_[axis]) / cell_);
    if(!(c > 0)) return 0;  // also catches NaN
    if(c >= dims_[axis] - 1) return dims_[axis] - 1;
    return static_cast<int>(c);
  }
  int linear(int x, int y, int z) const { return (z * dims_[1] + y) * dims_[0] + x; }

  Eigen::Vector3d lower_;
  double cell_ = 1, diagonal_ = 0;
  int dims_[3] = {1, 1, 1};
  std::vector<int> offsets_;
  std::vector<double> xyz_;
  std::vector<int> index_;
};

/// Greedy Poisson-disk subsample: the vertices are visited by increasing index and kept unless a
/// kept vertex lies closer than `spacing`. No two kept vertices are closer than `spacing`, every
/// vertex is closer than `spacing` to a kept one, and the result depends only on the distances
/// and the vertex order (so it is invariant under rigid motions).
inline std::vector<int> poisson_disk_subsample(const Indexed_mesh::Points& points, double spacing)
{
  const int n = static_cast<int>(points.rows());
  std::vector<int> sample;
  if(!(spacing > 0))
  {
    sample.resize(static_cast<std::size_t>(n));
    for(int i = 0; i < n; ++i) sample[static_cast<std::size_t>(i)] = i;
    return sample;
  }
  const Uniform_point_grid grid(points, spacing);
  std::vector<char> kept(static_cast<std::size_t>(n), 0);
  for(int i = 0; i < n; ++i)
  {
    const Eigen::Vector3d p = points.row(i).transpose();
    if(!grid.any_in_ball(p.data(), spacing,
                         [&](int j, double) { return kept[static_cast<std::size_t>(j)] != 0; }))
    {
      kept[static_cast<std::size_t>(i)] = 1;
      sample.push_back(i);
    }
  }
  return sample;
}

// --------------------------------------------------------------------------- one descriptor

/// The support points of a computation: a grid over them, and their unit normals in the grid's
/// slot order (so that gathering a support reads contiguous memory).
struct Shot_support_points
{
  Shot_support_points(const Indexed_mesh::Points& points, const Indexed_mesh::Points& normals,
                      double cell_size, const std::vector<int>& subset)
      : grid(points, cell_size, &subset), slot_normals(3 * grid.size())
  {
    for(std::size_t s = 0; s < grid.size(); ++s)
      for(int c = 0; c < 3; ++c) slot_normals[3 * s + c] = normals(grid.index(s), c);
  }
  Uniform_point_grid grid;
  std::vector<double> slot_normals;
};

/// Buffers reused from one vertex to the next (one per thread). For support point s:
/// neighbors[s] is its vertex, distances[s] its distance d_s to the centre, offsets[3s..3s+3)
/// the vector p_s - p, normals[3s..3s+3) its unit normal.
struct Shot_workspace
{
  std::vector<int> neighbors;
  std::vector<double> distances, offsets, normals;
  std::vector<double> scratch;  // for the k-th distance
  std::array<double, shot_descriptor_size> histogram;
  std::size_t size() const { return neighbors.size(); }
};

constexpr double shot_pi = 3.14159265358979323846;

/// atan(a) for a in [0, 1], to about 1e-16: atan(a) = pi/4 + atan((a - 1) / (a + 1)) brings the
/// argument t into [-tan(pi/8), tan(pi/8)], where atan(t) = t P(t^2) with P the degree-9
/// Chebyshev fit of atan(sqrt(s)) / sqrt(s) on [0, tan(pi/8)^2].
inline double shot_atan_unit(double a)
{
  constexpr double tan_pi_8 = 0.41421356237309504880;
  double t = a, offset = 0;
  if(a > tan_pi_8)
  {
    t = (a - 1) / (a + 1);
    offset = shot_pi / 4;
  }
  const double s = t * t;
  double p = -0.0253164795737764756502;
  p = p * s + 0.0502476211894012803238;
  p = p * s - 0.0650598296717083991575;
  p = p * s + 0.0767353542818328601761;
  p = p * s - 0.0908952995656230735768;
  p = p * s + 0.111110488537512956831;
  p = p * s - 0.142857126616847938371;
  p = p * s + 0.199999999783926620556;
  p = p * s - 0.33333333333221434047;
  p = p * s + 0.999999999999999040803;
  return offset + t * p;
}

/// atan2(y, x) in [-pi, pi] (pi for y = 0, x < 0; 0 for x = y = 0), agreeing with std::atan2 to
/// about 1e-15. The binning calls it twice per support point; it saves about 12% of the SHOT
/// time against std::atan2 (measured with bench_shot's mesh at 5k vertices).
inline double shot_atan2(double y, double x)
{
  const double ax = std::abs(x), ay = std::abs(y);
  if(!(ax > 0) && !(ay > 0)) return 0;
  double r = ay <= ax ? shot_atan_unit(ay / ax) : shot_pi / 2 - shot_atan_unit(ax / ay);
  if(x < 0) r = shot_pi - r;
  return y < 0 ? -r : r;
}

/// Linear ("hat function") interpolation weights of a continuous bin coordinate u whose bin
/// centres are the integers 0..bins-1. Outside [0, bins-1] the whole weight goes to the end bin.
inline void shot_hat_weights(double u, int bins, int& lower, double& w_lower, double& w_upper)
{
  const double f = std::floor(u);
  if(f < 0)
  {
    lower = 0;
    w_lower = 1;
    w_upper = 0;
  }
  else if(f >= bins - 1)
  {
    lower = bins - 2;
    w_lower = 0;
    w_upper = 1;
  }
  else
  {
    lower = static_cast<int>(f);
    w_upper = u - f;
    w_lower = 1 - w_upper;
  }
}

/// Sign of a reference axis by the majority rule of the SHOT LRF: the axis points to the side
/// that holds more support points (projections within 1e-10 R of zero count for neither side).
/// Ties are broken by the sign of the (R - d_i)-weighted sum of the projections; returns 0 when
/// that sum is also negligible.
inline int shot_majority_sign(const Eigen::Vector3d& axis, const Shot_workspace& ws, double radius)
{
  const double tolerance = 1e-10 * radius;
  int positive = 0, negative = 0;
  double weighted_sum = 0, total_weight = 0;
  for(std::size_t k = 0; k < ws.size(); ++k)
  {
    const double* q = &ws.offsets[3 * k];
    const double projection = q[0] * axis[0] + q[1] * axis[1] + q[2] * axis[2];
    if(projection > tolerance) ++positive;
    else if(projection < -tolerance) ++negative;
    const double w = radius - ws.distances[k];
    weighted_sum += w * projection;
    total_weight += w;
  }
  if(positive != negative) return positive > negative ? 1 : -1;
  if(std::abs(weighted_sum) > tolerance * total_weight) return weighted_sum > 0 ? 1 : -1;
  return 0;
}

/// Collects into ws the support points other than vertex `v` at distance < r from `centre`,
/// skipping points that coincide with the centre (their direction is undefined).
inline void shot_collect(const Shot_support_points& sp, int v, const Eigen::Vector3d& centre,
                         double r, Shot_workspace& ws)
{
  ws.neighbors.clear();
  ws.distances.clear();
  ws.offsets.clear();
  ws.normals.clear();
  const double coincident2 = (1e-12 * r) * (1e-12 * r);
  sp.grid.for_each_in_ball(centre.data(), r, [&](int j, double d2, std::size_t slot) {
    if(j == v || d2 <= coincident2) return;
    ws.neighbors.push_back(j);
    ws.distances.push_back(std::sqrt(d2));
    const double* p = sp.grid.position(slot);
    const double* n = &sp.slot_normals[3 * slot];
    for(int c = 0; c < 3; ++c)
    {
      ws.offsets.push_back(p[c] - centre[c]);
      ws.normals.push_back(n[c]);
    }
  });
}

/// The k-th smallest value of ws.distances (the largest when there are fewer than k).
inline double shot_kth_distance(Shot_workspace& ws, int k)
{
  ws.scratch.assign(ws.distances.begin(), ws.distances.end());
  const std::size_t kth = std::min<std::size_t>(static_cast<std::size_t>(k), ws.scratch.size()) - 1;
  std::nth_element(ws.scratch.begin(), ws.scratch.begin() + static_cast<std::ptrdiff_t>(kth),
                   ws.scratch.end());
  return ws.scratch[kth];
}

/// Fills ws with the support of vertex v: the support points other than v within max(R, 1.25 d_k)
/// of it, d_k being the distance to the k-th nearest of them. Returns that support radius.
inline double shot_support(const Indexed_mesh& m, const Shot_support_points& sp, int v,
                           double radius, int minimum_neighbors, Shot_workspace& ws)
{
  const Eigen::Vector3d centre = m.points.row(v).transpose();
  const int k = std::max(1, minimum_neighbors);
  shot_collect(sp, v, centre, radius, ws);
  double support = radius;
  if(static_cast<int>(ws.size()) >= k)
  {
    // d_k matters only when it exceeds R / 1.25: count the points closer than that first.
    const double threshold = radius / shot_enlargement_factor;
    int closer = 0;
    for(double d : ws.distances) closer += d < threshold ? 1 : 0;
    if(closer < k) support = std::max(radius, shot_enlargement_factor * shot_kth_distance(ws, k));
  }
  else
  {
    // Grow a search ball until it holds k points (or all of them).
    double search = radius;
    while(static_cast<int>(ws.size()) < k && search <= sp.grid.diagonal())
    {
      search *= 2;
      shot_collect(sp, v, centre, search, ws);
    }
    if(ws.size() > 0)
      support = std::max(radius, shot_enlargement_factor * shot_kth_distance(ws, k));
  }
  if(support > radius) shot_collect(sp, v, centre, support, ws);
  return support;
}

/// The SHOT local reference frame of a vertex with unit normal `normal` and the (non-empty)
/// support in ws: the rows of the result are the unit axes x, y, z.
inline Eigen::Matrix3d shot_local_reference_frame(const Eigen::Vector3d& normal, double support,
                                                  const Shot_workspace& ws)
{
  // M = sum_i (R - d_i) (p_i - p)(p_i - p)^T / sum_i (R - d_i) (upper triangle).
  double m00 = 0, m01 = 0, m02 = 0, m11 = 0, m12 = 0, m22 = 0, total_weight = 0;
  for(std::size_t s = 0; s < ws.size(); ++s)
  {
    const double* q = &ws.offsets[3 * s];
    const double w = support - ws.distances[s];
    m00 += w * q[0] * q[0];
    m01 += w * q[0] * q[1];
    m02 += w * q[0] * q[2];
    m11 += w * q[1] * q[1];
    m12 += w * q[1] * q[2];
    m22 += w * q[2] * q[2];
    total_weight += w;
  }
  Eigen::Matrix3d covariance;
  covariance << m00, m01, m02, m01, m11, m12, m02, m12, m22;
  if(total_weight > 0) covariance /= total_weight;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  Eigen::Vector3d x_axis = eigen.eigenvectors().col(2);  // largest eigenvalue
  Eigen::Vector3d z_axis = eigen.eigenvectors().col(0);  // smallest eigenvalue
  if(shot_majority_sign(x_axis, ws, support) < 0) x_axis = -x_axis;
  const int z_sign = shot_majority_sign(z_axis, ws, support);
  if(z_sign < 0) z_axis = -z_axis;
  else if(z_sign == 0 && z_axis.dot(normal) < 0)
    z_axis = -z_axis;  // flat support: the mesh orientation decides
  Eigen::Matrix3d frame;
  frame.row(0) = x_axis.transpose();
  frame.row(1) = z_axis.cross(x_axis).transpose();
  frame.row(2) = z_axis.transpose();
  return frame;
}

/// Computes the SHOT descriptor of vertex v into ws.histogram (unit norm). Returns the support
/// radius used; the support is left in ws.
inline double shot_descriptor(const Indexed_mesh& m, const Indexed_mesh::Points& normals,
                              const Shot_support_points& sp, int v, double radius,
                              int minimum_neighbors, Shot_workspace& ws)
{
  const double support = shot_support(m, sp, v, radius, minimum_neighbors, ws);
  const std::size_t count = ws.size();
  if(count == 0)
  {
    // Every other vertex coincides with v: no direction is defined. A constant unit vector.
    ws.histogram.fill(1.0 / std::sqrt(static_cast<double>(shot_descriptor_size)));
    return support;
  }
  const Eigen::Matrix3d frame =
      shot_local_reference_frame(normals.row(v).transpose(), support, ws);
  const Eigen::Vector3d x_axis = frame.row(0).transpose(), y_axis = frame.row(1).transpose(),
                        z_axis = frame.row(2).transpose();
  ws.histogram.fill(0.0);

  // --- histograms with quadrilinear interpolation.
  constexpr double pi = shot_pi;
  constexpr double azimuth_scale = shot_azimuth_divisions / (2 * pi);
  constexpr double elevation_scale = shot_elevation_divisions / pi;
  const double radial_scale = shot_radial_divisions / support;
  constexpr double cosine_scale = shot_cosine_bins / 2.0;
  double* h = ws.histogram.data();
  for(std::size_t s = 0; s < count; ++s)
  {
    const double* q = &ws.offsets[3 * s];
    const double* n = &ws.normals[3 * s];
    const double lx = q[0] * x_axis[0] + q[1] * x_axis[1] + q[2] * x_axis[2];
    const double ly = q[0] * y_axis[0] + q[1] * y_axis[1] + q[2] * y_axis[2];
    const double lz = q[0] * z_axis[0] + q[1] * z_axis[1] + q[2] * z_axis[2];
    const double cosine =
        std::max(-1.0, std::min(1.0, n[0] * z_axis[0] + n[1] * z_axis[1] + n[2] * z_axis[2]));
    // Continuous bin coordinates; bin centres are at the integers.
    const double u_cos = (cosine + 1) * cosine_scale - 0.5;
    const double u_azi = (shot_atan2(ly, lx) + pi) * azimuth_scale - 0.5;
    const double u_ele =
        (shot_atan2(lz, std::sqrt(lx * lx + ly * ly)) + pi / 2) * elevation_scale - 0.5;
    const double u_rad = ws.distances[s] * radial_scale - 0.5;

    int c0, e0, r0;
    double wc[2], we[2], wr[2];
    shot_hat_weights(u_cos, shot_cosine_bins, c0, wc[0], wc[1]);
    shot_hat_weights(u_ele, shot_elevation_divisions, e0, we[0], we[1]);
    shot_hat_weights(u_rad, shot_radial_divisions, r0, wr[0], wr[1]);
    // Azimuth is circular: bins a0 and a0 + 1 (mod 8).
    const double fa = std::floor(u_azi);
    const double wa1 = u_azi - fa, wa[2] = {1 - wa1, wa1};
    int a[2];
    a[0] = (static_cast<int>(fa) + shot_azimuth_divisions) % shot_azimuth_divisions;
    a[1] = (a[0] + 1) % shot_azimuth_divisions;

    for(int ir = 0; ir < 2; ++ir)
      for(int ie = 0; ie < 2; ++ie)
      {
        const double w_re = wr[ir] * we[ie];
        if(w_re == 0) continue;
        for(int ia = 0; ia < 2; ++ia)
        {
          const double w_rea = w_re * wa[ia];
          double* bins = h + shot_index(r0 + ir, e0 + ie, a[ia], c0);
          bins[0] += w_rea * wc[0];
          bins[1] += w_rea * wc[1];
        }
      }
  }

  // --- unit Euclidean norm.
  double norm2 = 0;
  for(double x : ws.histogram) norm2 += x * x;
  if(norm2 > 0)
  {
    const double inverse = 1.0 / std::sqrt(norm2);
    for(double& x : ws.histogram) x *= inverse;
  }
  else
    ws.histogram.fill(1.0 / std::sqrt(static_cast<double>(shot_descriptor_size)));
  return support;
}

// ------------------------------------------------------------------------------- many vertices

/// Throws Invalid_parameter_error unless the options are valid.
inline void check_shot_options(const Shot_options& options)
{
  if(!(options.relative_radius > 0) || !std::isfinite(options.relative_radius))
    throw Invalid_parameter_error("shot_radius must be a finite positive number (got " +
                                  std::to_string(options.relative_radius) + ")");
  if(options.minimum_neighbors < 1)
    throw Invalid_parameter_error("the minimum number of SHOT neighbours must be at least 1 (got " +
                                  std::to_string(options.minimum_neighbors) + ")");
}

/// SHOT descriptors of the vertices `queries[0..number_of_queries)` of `m`: row r of the result
/// (number_of_queries x 352) is the descriptor of vertex queries[r]. Neighbours are taken among
/// all vertices of `m`. Results do not depend on ConcurrencyTag.
template <typename ConcurrencyTag>
Eigen::MatrixXd shot_descriptors(const Indexed_mesh& m, const int* queries,
                                 std::size_t number_of_queries, const Shot_options& options,
                                 Shot_statistics* statistics = nullptr)
{
  check_shot_options(options);
  const int n = m.number_of_vertices();
  for(std::size_t r = 0; r < number_of_queries; ++r)
    if(queries[r] < 0 || queries[r] >= n)
      throw Invalid_parameter_error("SHOT: vertex index " + std::to_string(queries[r]) +
                                    " is out of range [0, " + std::to_string(n) + ")");
  if(!(m.total_area > 0))
    throw Invalid_mesh_error("SHOT: the mesh has no area");
  const double radius = options.relative_radius * std::sqrt(m.total_area);
  if(!(radius > 0) || !std::isfinite(radius))
    throw Invalid_parameter_error("SHOT: the support radius " + std::to_string(radius) +
                                  " is not a finite positive number");

  const Indexed_mesh::Points normals = vertex_normals(m);
  const bool subsample = options.maximum_support_points > 0 &&
                         static_cast<std::size_t>(n) > options.maximum_support_points;
  const std::vector<int> support_points = poisson_disk_subsample(
      m.points, subsample ? std::sqrt(m.total_area / (poisson_disk_area_per_point *
                                                      options.maximum_support_points))
                          : 0.0);
  const Shot_support_points sp(m.points, normals, radius, support_points);
  Eigen::MatrixXd descriptors(static_cast<Eigen::Index>(number_of_queries), shot_descriptor_size);
  std::vector<int> neighbor_counts(number_of_queries, 0);
  std::vector<char> enlarged(number_of_queries, 0);

  parallel_for_ranges<ConcurrencyTag>(
      number_of_queries,
      [&](std::size_t begin, std::size_t end) {
        Shot_workspace ws;
        for(std::size_t r = begin; r < end; ++r)
        {
          const double support =
              shot_descriptor(m, normals, sp, queries[r], radius, options.minimum_neighbors, ws);
          neighbor_counts[r] = static_cast<int>(ws.size());
          enlarged[r] = support > radius;
          const Eigen::Index row = static_cast<Eigen::Index>(r);
          for(int b = 0; b < shot_descriptor_size; ++b) descriptors(row, b) = ws.histogram[b];
        }
      },
      64);

  if(statistics)
  {
    statistics->support_radius = radius;
    statistics->support_points = support_points.size();
    double total = 0;
    std::size_t enlarged_count = 0;
    for(std::size_t r = 0; r < number_of_queries; ++r)
    {
      total += neighbor_counts[r];
      enlarged_count += enlarged[r] ? 1 : 0;
    }
    statistics->average_neighbors = number_of_queries ? total / number_of_queries : 0.0;
    statistics->enlarged_supports = enlarged_count;
  }
  return descriptors;
}

/// SHOT descriptors of all vertices of `m` (n x 352, row i = vertex i).
template <typename ConcurrencyTag>
Eigen::MatrixXd shot_descriptors(const Indexed_mesh& m, const Shot_options& options = Shot_options(),
                                 Shot_statistics* statistics = nullptr)
{
  std::vector<int> all(static_cast<std::size_t>(m.number_of_vertices()));
  for(std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return shot_descriptors<ConcurrencyTag>(m, all.data(), all.size(), options, statistics);
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_SHOT_IMPL_H
