// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Loops that run in parallel with TBB when the caller asks for CGAL::Parallel_tag, sequentially
// with CGAL::Sequential_tag. Asking for Parallel_tag without TBB is a compile-time error, as in
// CGAL.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_PARALLEL_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_PARALLEL_H

#include <CGAL/tags.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <type_traits>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#endif

namespace CGAL {
namespace Surface_mesh_correspondence {
namespace internal {

template <typename ConcurrencyTag>
struct Is_parallel
{
#ifndef CGAL_LINKED_WITH_TBB
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "Parallel_tag is enabled but TBB is unavailable.");
#endif
  static constexpr bool value = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
};

/// Calls `body(begin, end)` on consecutive sub-ranges covering [0, n). With Parallel_tag the
/// sub-ranges run concurrently (each of at least `grain` indices); `body` must then be safe to
/// call from several threads on disjoint ranges.
template <typename ConcurrencyTag, typename Body>
void parallel_for_ranges(std::size_t n, const Body& body, std::size_t grain = 1)
{
  if(n == 0) return;
#ifdef CGAL_LINKED_WITH_TBB
  if(Is_parallel<ConcurrencyTag>::value)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain == 0 ? 1 : grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
    return;
  }
#else
  (void)grain;
  (void)Is_parallel<ConcurrencyTag>::value;
#endif
  body(std::size_t(0), n);
}

/// Calls `body(i)` for every i in [0, n), concurrently with Parallel_tag.
template <typename ConcurrencyTag, typename Body>
void parallel_for(std::size_t n, const Body& body, std::size_t grain = 1)
{
  parallel_for_ranges<ConcurrencyTag>(
      n,
      [&](std::size_t b, std::size_t e) {
        for(std::size_t i = b; i < e; ++i) body(i);
      },
      grain);
}

/// Calls `body(i)` for every i in [0, n), concurrently with Parallel_tag, starting the calls in
/// the order of i: each thread takes the next index when it is free. For a few tasks of very
/// different costs listed from the most to the least costly (the longest-processing-time-first
/// schedule); parallel_for() splits the range in halves instead, which can leave the costliest
/// tasks to one thread. Each call is isolated: a thread waiting inside a body's own parallel work
/// does not take other indices meanwhile. When a body throws, no further index is started and the
/// exception reaches the caller.
template <typename ConcurrencyTag, typename Body>
void parallel_for_in_order(std::size_t n, const Body& body)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(Is_parallel<ConcurrencyTag>::value && n > 1)
  {
    std::atomic<std::size_t> next(0);
    const std::size_t workers =
        std::min(n, static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency())));
    tbb::parallel_for(std::size_t(0), workers, [&](std::size_t) {
      try
      {
        for(std::size_t i = next++; i < n; i = next++) tbb::this_task_arena::isolate([&] { body(i); });
      }
      catch(...)
      {
        next = n;
        throw;
      }
    });
    return;
  }
#else
  (void)Is_parallel<ConcurrencyTag>::value;
#endif
  for(std::size_t i = 0; i < n; ++i) body(i);
}

/// Runs a and b, concurrently with Parallel_tag.
template <typename ConcurrencyTag, typename A, typename B>
void invoke_both(const A& a, const B& b)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(Is_parallel<ConcurrencyTag>::value)
  {
    tbb::parallel_invoke(a, b);
    return;
  }
#else
  (void)Is_parallel<ConcurrencyTag>::value;
#endif
  a();
  b();
}

} // namespace internal
} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_INTERNAL_PARALLEL_H
