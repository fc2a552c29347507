// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The min-plus (min-sum) kernels of the TRW-S solver (trws.h) and a finiteness scan.
//
// A pairwise table of edge (s, t) is stored row-major, K_s rows (labels of s) times K_t columns
// (labels of t). TRW-S sends messages both ways along the same table:
//
//   to the target:  out[l] = min_k ( a[k] + T[k * K_t + l] ),   l < K_t   (column-wise minimum)
//   to the source:  out[k] = min_l ( b[l] + T[k * K_t + l] ),   k < K_s   (row-wise minimum)
//
// Both read the table row by row, contiguously, so a single copy of each table serves both
// directions. The first kernel keeps chunks of W columns in registers while it reads the rows;
// the second is a minimum reduction inside each row, which compilers do not vectorise for floating
// point without -ffast-math (a reduction changes the order of operations), so it keeps W partial
// minima in a register and ends with a horizontal minimum. Both are written with GCC's generic
// vector types (plain IEEE lane-wise operations, mapped to the SIMD instructions of the target),
// with portable loops for other compilers. The last, partial chunk of a row is handled by one
// more chunk that ends at the row's end and overlaps the previous one: the minimum is idempotent,
// so counting some entries twice changes nothing, and no scalar tail loop is needed. Both kernels
// also normalise the message (subtract its first entry) before storing it, so no load has to wait
// for the overlapping stores.
//
// The project is not built with -march=native, so the entry points are compiled for AVX2 and for
// the baseline with GCC's function multi-versioning (target_clones); the best one is picked at
// load time (ifunc). Define CGAL_SMC_TRWS_NO_TARGET_CLONES to compile one version only.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_KERNELS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_KERNELS_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__GNUC__) && !defined(__clang__) && (defined(__x86_64__) || defined(__i386__)) &&      \
    defined(__gnu_linux__) && !defined(CGAL_SMC_TRWS_NO_TARGET_CLONES)
#define CGAL_SMC_TRWS_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CGAL_SMC_TRWS_TARGET_CLONES
#endif

#if defined(__GNUC__)
#define CGAL_SMC_TRWS_RESTRICT __restrict__
#else
#define CGAL_SMC_TRWS_RESTRICT
#endif

// The helpers are forced inline into the multi-versioned entry points, so that they are compiled
// for the instruction set of each clone.
#if defined(__GNUC__)
#define CGAL_SMC_TRWS_INLINE inline __attribute__((always_inline))
#else
#define CGAL_SMC_TRWS_INLINE inline
#endif

// GCC's generic vector extensions give explicit SIMD code; other compilers get the portable
// loops. Define CGAL_SMC_TRWS_NO_VECTOR_EXTENSIONS to use the portable loops with GCC too.
#if defined(__GNUC__) && !defined(__clang__) && !defined(CGAL_SMC_TRWS_NO_VECTOR_EXTENSIONS)
#define CGAL_SMC_TRWS_VECTOR_EXTENSIONS 1
#endif

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {
namespace trws_kernels {

template <typename FT>
CGAL_SMC_TRWS_INLINE FT min_of(FT a, FT b)
{
  return b < a ? b : a;
}

// Portable loops: out[l] = min_k a[k] + T[k * kt + l] - c, c = the minimum for l = 0 (returned).
// Compilers vectorise the inner loops over l.
template <typename FT>
CGAL_SMC_TRWS_INLINE FT to_target_scalar(const FT* CGAL_SMC_TRWS_RESTRICT a,
                                         const FT* CGAL_SMC_TRWS_RESTRICT table, std::size_t ks,
                                         std::size_t kt, FT* CGAL_SMC_TRWS_RESTRICT out)
{
  for(std::size_t l = 0; l < kt; ++l) out[l] = a[0] + table[l];
  for(std::size_t k = 1; k < ks; ++k)
  {
    const FT ak = a[k];
    const FT* CGAL_SMC_TRWS_RESTRICT row = table + k * kt;
    for(std::size_t l = 0; l < kt; ++l) out[l] = min_of(out[l], ak + row[l]);
  }
  const FT c = out[0];
  for(std::size_t l = 0; l < kt; ++l) out[l] -= c;
  return c;
}

// Portable loops: out[k] = min_l b[l] + T[k * kt + l] - c, c = the minimum for k = 0 (returned).
// The row minimum is a reduction: not vectorised.
template <typename FT>
CGAL_SMC_TRWS_INLINE FT to_source_scalar(const FT* CGAL_SMC_TRWS_RESTRICT b,
                                         const FT* CGAL_SMC_TRWS_RESTRICT table, std::size_t ks,
                                         std::size_t kt, FT* CGAL_SMC_TRWS_RESTRICT out)
{
  FT c = 0;
  for(std::size_t k = 0; k < ks; ++k)
  {
    const FT* CGAL_SMC_TRWS_RESTRICT row = table + k * kt;
    FT m = b[0] + row[0];
    for(std::size_t l = 1; l < kt; ++l) m = min_of(m, b[l] + row[l]);
    if(k == 0) c = m;
    out[k] = m - c;
  }
  return c;
}

#ifdef CGAL_SMC_TRWS_VECTOR_EXTENSIONS

// GCC's generic vector types: W lanes of FT. Arithmetic and comparisons act lane by lane with IEEE
// semantics, and the compiler maps them to the SIMD instructions of the target being compiled
// (one AVX2 register, two SSE registers for 8 floats).
template <typename FT, int W>
struct Lanes
{
  typedef FT type __attribute__((vector_size(W * sizeof(FT))));
};

// Minimum of the W values at p (a local array), by halving: W/2 lanes, W/4 lanes, ...
template <int W, typename FT>
CGAL_SMC_TRWS_INLINE FT horizontal_min(const FT* p)
{
  if constexpr(W <= 2)
    return W == 1 ? p[0] : min_of(p[0], p[1]);
  else
  {
    typedef typename Lanes<FT, W / 2>::type H;
    H lo, hi;
    std::memcpy(&lo, p, sizeof(H));
    std::memcpy(&hi, p + W / 2, sizeof(H));
    const H m = hi < lo ? hi : lo;
    FT q[W / 2];
    std::memcpy(q, &m, sizeof(H));
    return horizontal_min<W / 2>(q);
  }
}

// Columns offsets[0 .. NV) + [0, W) of out[l] = min_k a[k] + T[k * kt + l] - c: NV chunks of W
// columns kept in registers while the rows are read in order. The first block sets c (its
// column 0, which is column 0 of the table); the result is normalised in registers and stored
// once, so that no load has to wait for overlapping stores.
template <int NV, int W, typename FT>
CGAL_SMC_TRWS_INLINE void to_target_block(const FT* CGAL_SMC_TRWS_RESTRICT a,
                                          const FT* CGAL_SMC_TRWS_RESTRICT table, std::size_t ks,
                                          std::size_t kt, const std::size_t* offsets,
                                          bool first_block, FT& c, FT* CGAL_SMC_TRWS_RESTRICT out)
{
  typedef typename Lanes<FT, W>::type V;
  V acc[NV];
  for(int j = 0; j < NV; ++j)
  {
    std::memcpy(&acc[j], table + offsets[j], sizeof(V));
    acc[j] += a[0];
  }
  for(std::size_t k = 1; k < ks; ++k)
  {
    const FT* CGAL_SMC_TRWS_RESTRICT row = table + k * kt;
    const FT ak = a[k];
    for(int j = 0; j < NV; ++j)
    {
      V x;
      std::memcpy(&x, row + offsets[j], sizeof(V));
      x += ak;
      acc[j] = x < acc[j] ? x : acc[j];
    }
  }
  if(first_block) c = acc[0][0];
  for(int j = 0; j < NV; ++j)
  {
    acc[j] -= c;
    std::memcpy(out + offsets[j], &acc[j], sizeof(V));
  }
}

// out[l] = min_k a[k] + T[k * kt + l] - c, kt >= W: blocks of up to 8 chunks of W columns; the
// last chunk ends at the last column and may overlap the previous one (the minimum is
// idempotent, and both write the same values).
template <int W, typename FT>
CGAL_SMC_TRWS_INLINE FT to_target_lanes(const FT* CGAL_SMC_TRWS_RESTRICT a,
                                        const FT* CGAL_SMC_TRWS_RESTRICT table, std::size_t ks,
                                        std::size_t kt, FT* CGAL_SMC_TRWS_RESTRICT out)
{
  FT c = 0;
  std::size_t col = 0, offsets[8];
  for(; col + 8 * W <= kt; col += 8 * W)
  {
    for(int j = 0; j < 8; ++j) offsets[j] = col + j * W;
    to_target_block<8, W>(a, table, ks, kt, offsets, col == 0, c, out);
  }
  if(col == kt) return c;
  const std::size_t chunks = (kt - col + W - 1) / W; // 1 to 8
  for(std::size_t j = 0; j + 1 < chunks; ++j) offsets[j] = col + j * W;
  offsets[chunks - 1] = kt - W;
  const bool first = (col == 0);
  switch(chunks)
  {
  case 1: to_target_block<1, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 2: to_target_block<2, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 3: to_target_block<3, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 4: to_target_block<4, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 5: to_target_block<5, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 6: to_target_block<6, W>(a, table, ks, kt, offsets, first, c, out); break;
  case 7: to_target_block<7, W>(a, table, ks, kt, offsets, first, c, out); break;
  default: to_target_block<8, W>(a, table, ks, kt, offsets, first, c, out); break;
  }
  return c;
}

// out[k] = min_l b[l] + T[k * kt + l] - c, kt >= W: W partial minima per row, then a horizontal
// minimum; the last chunk of a row ends at its end and may overlap the previous one.
template <int W, typename FT>
CGAL_SMC_TRWS_INLINE FT to_source_lanes(const FT* CGAL_SMC_TRWS_RESTRICT b,
                                        const FT* CGAL_SMC_TRWS_RESTRICT table, std::size_t ks,
                                        std::size_t kt, FT* CGAL_SMC_TRWS_RESTRICT out)
{
  typedef typename Lanes<FT, W>::type V;
  const std::size_t last = kt - W;
  FT c = 0;
  for(std::size_t k = 0; k < ks; ++k)
  {
    const FT* CGAL_SMC_TRWS_RESTRICT row = table + k * kt;
    V acc, x, y;
    std::memcpy(&acc, row + last, sizeof(V));
    std::memcpy(&y, b + last, sizeof(V));
    acc += y;
    for(std::size_t l = 0; l < last; l += W)
    {
      std::memcpy(&x, row + l, sizeof(V));
      std::memcpy(&y, b + l, sizeof(V));
      x += y;
      acc = x < acc ? x : acc;
    }
    FT lanes[W];
    std::memcpy(lanes, &acc, sizeof(V));
    const FT m = horizontal_min<W>(lanes);
    if(k == 0) c = m;
    out[k] = m - c;
  }
  return c;
}

#endif // CGAL_SMC_TRWS_VECTOR_EXTENSIONS

// 32-byte chunks (8 floats, 4 doubles: one AVX2 register) for rows that are long enough,
// 16-byte ones for shorter rows, the portable loops for the shortest.
template <typename FT>
CGAL_SMC_TRWS_INLINE FT to_target(const FT* a, const FT* table, std::size_t ks, std::size_t kt,
                                  FT* out)
{
#ifdef CGAL_SMC_TRWS_VECTOR_EXTENSIONS
  constexpr int W = 32 / sizeof(FT);
  if(kt >= std::size_t(W)) return to_target_lanes<W>(a, table, ks, kt, out);
  if(kt >= std::size_t(W / 2)) return to_target_lanes<W / 2>(a, table, ks, kt, out);
#endif
  return to_target_scalar(a, table, ks, kt, out);
}

template <typename FT>
CGAL_SMC_TRWS_INLINE FT to_source(const FT* b, const FT* table, std::size_t ks, std::size_t kt,
                                  FT* out)
{
#ifdef CGAL_SMC_TRWS_VECTOR_EXTENSIONS
  constexpr int W = 32 / sizeof(FT);
  if(kt >= std::size_t(W)) return to_source_lanes<W>(b, table, ks, kt, out);
  if(kt >= std::size_t(W / 2)) return to_source_lanes<W / 2>(b, table, ks, kt, out);
#endif
  return to_source_scalar(b, table, ks, kt, out);
}

// Index of the first entry of p[0 .. n) that is NaN or infinite, or n. Reads the exponent bits
// (no floating-point comparison, so no exception is raised by NaNs).
template <typename FT>
CGAL_SMC_TRWS_INLINE std::size_t first_non_finite(const FT* p, std::size_t n)
{
  typedef typename std::conditional<sizeof(FT) == 4, std::uint32_t, std::uint64_t>::type Bits;
  const Bits exponent = sizeof(FT) == 4 ? Bits(0x7f800000u) : Bits(0x7ff0000000000000ull);
  const std::size_t block = 64;
  std::size_t i = 0;
  for(; i + block <= n; i += block)
  {
    Bits bad = 0;
    for(std::size_t j = 0; j < block; ++j)
    {
      Bits u;
      std::memcpy(&u, p + i + j, sizeof(u));
      bad |= Bits((u & exponent) == exponent);
    }
    if(bad) break;
  }
  for(; i < n; ++i)
  {
    Bits u;
    std::memcpy(&u, p + i, sizeof(u));
    if((u & exponent) == exponent) return i;
  }
  return n;
}

} // namespace trws_kernels

// The multi-versioned entry points, one per floating-point type. Each writes the normalised
// message out[.] - c and returns the normalisation constant c (the unnormalised out[0]).
CGAL_SMC_TRWS_TARGET_CLONES inline float trws_min_plus_to_target(const float* a, const float* table,
                                                                 std::size_t ks, std::size_t kt,
                                                                 float* out)
{
  return trws_kernels::to_target(a, table, ks, kt, out);
}
CGAL_SMC_TRWS_TARGET_CLONES inline double trws_min_plus_to_target(const double* a,
                                                                  const double* table,
                                                                  std::size_t ks, std::size_t kt,
                                                                  double* out)
{
  return trws_kernels::to_target(a, table, ks, kt, out);
}
CGAL_SMC_TRWS_TARGET_CLONES inline float trws_min_plus_to_source(const float* b, const float* table,
                                                                 std::size_t ks, std::size_t kt,
                                                                 float* out)
{
  return trws_kernels::to_source(b, table, ks, kt, out);
}
CGAL_SMC_TRWS_TARGET_CLONES inline double trws_min_plus_to_source(const double* b,
                                                                  const double* table,
                                                                  std::size_t ks, std::size_t kt,
                                                                  double* out)
{
  return trws_kernels::to_source(b, table, ks, kt, out);
}
CGAL_SMC_TRWS_TARGET_CLONES inline std::size_t trws_first_non_finite(const float* p, std::size_t n)
{
  return trws_kernels::first_non_finite(p, n);
}
CGAL_SMC_TRWS_TARGET_CLONES inline std::size_t trws_first_non_finite(const double* p, std::size_t n)
{
  return trws_kernels::first_non_finite(p, n);
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_TRWS_KERNELS_H
