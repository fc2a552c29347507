// SPDX-License-Identifier: GPL-3.0-or-later
// The parallel loops of internal/parallel.h: every index once, and parallel_for_in_order()'s
// schedule (each thread takes the next index), which the initialisation relies on to start its
// costliest fits together.

#include <CGAL/Surface_mesh_correspondence/internal/parallel.h>

#include <boost/test/unit_test.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace smc_internal = CGAL::Surface_mesh_correspondence::internal;

BOOST_AUTO_TEST_SUITE(parallel_loops)

template <typename Tag>
std::vector<int> calls_in_order(std::size_t n, std::vector<std::size_t>* order = nullptr)
{
  std::vector<int> calls(n, 0);
  std::mutex mutex;
  smc_internal::parallel_for_in_order<Tag>(n, [&](std::size_t i) {
    std::lock_guard<std::mutex> lock(mutex);
    ++calls[i];
    if(order) order->push_back(i);
  });
  return calls;
}

BOOST_AUTO_TEST_CASE(in_order_calls_every_index_once)
{
  for(std::size_t n : {0u, 1u, 2u, 3u, 37u})
  {
    std::vector<std::size_t> order;
    const std::vector<int> sequential = calls_in_order<CGAL::Sequential_tag>(n, &order);
    BOOST_TEST(sequential == std::vector<int>(n, 1), "n = " << n);
    for(std::size_t i = 0; i < order.size(); ++i) BOOST_TEST(order[i] == i);  // sequential: 0, 1, ...
#ifdef CGAL_LINKED_WITH_TBB
    BOOST_TEST(calls_in_order<CGAL::Parallel_tag>(n) == std::vector<int>(n, 1), "n = " << n);
#endif
  }
}

BOOST_AUTO_TEST_CASE(in_order_stops_at_an_exception)
{
  // Index 3 throws: the exception reaches the caller and the other threads stop taking indices
  // (each call takes 1 ms: without the stop they would run all 1000).
  for(int parallel = 0; parallel < 2; ++parallel)
  {
    std::atomic<std::size_t> calls(0);
    auto body = [&](std::size_t i) {
      ++calls;
      if(i == 3) throw std::runtime_error("task 3");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    };
    bool thrown = false;
    try
    {
#ifdef CGAL_LINKED_WITH_TBB
      if(parallel)
        smc_internal::parallel_for_in_order<CGAL::Parallel_tag>(1000, body);
      else
#endif
        smc_internal::parallel_for_in_order<CGAL::Sequential_tag>(1000, body);
    }
    catch(const std::runtime_error& e)
    {
      thrown = std::string(e.what()) == "task 3";
    }
    BOOST_TEST(thrown);
    BOOST_TEST(calls.load() < 100u, "calls " << calls.load());
  }
}

#ifdef CGAL_LINKED_WITH_TBB
BOOST_AUTO_TEST_CASE(in_order_starts_the_first_tasks_together)
{
  if(tbb::this_task_arena::max_concurrency() < 2)
  {
    BOOST_TEST_MESSAGE("one thread: nothing to check");
    return;
  }
  // On two threads (with more, an idle third thread would start task 1 whatever the schedule):
  // tasks 0 and 1 each wait (at most 5 s) until both have started; tasks 2 and 3 wait until 0 and
  // 1 have finished. With each thread taking the next index, 0 and 1 start together and then 2
  // and 3 run. parallel_for() splits the range in halves instead: one thread takes 0 and 1, the
  // other 2 and 3, and task 0 waits for 1 alone until it times out.
  tbb::task_arena two_threads(2);
  std::atomic<int> started(0), finished(0);
  std::atomic<bool> together[2] = {{false}, {false}};
  auto wait_for = [](const std::atomic<int>& counter) {
    const auto start = std::chrono::steady_clock::now();
    while(counter.load() < 2 && std::chrono::steady_clock::now() - start < std::chrono::seconds(5))
      std::this_thread::yield();
  };
  two_threads.execute([&] {
    smc_internal::parallel_for_in_order<CGAL::Parallel_tag>(4, [&](std::size_t i) {
      if(i >= 2)
      {
        wait_for(finished);
        return;
      }
      ++started;
      wait_for(started);
      together[i] = started.load() >= 2;
      ++finished;
    });
  });
  BOOST_TEST(together[0].load());
  BOOST_TEST(together[1].load());
}
#endif

BOOST_AUTO_TEST_SUITE_END()
