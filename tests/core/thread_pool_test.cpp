#include "core/thread_pool.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace plumekit {
namespace {

TEST(ThreadPool, RunsEveryIndexOnceAcrossManyCalls) {
  ThreadPool pool(3);
  EXPECT_EQ(pool.size(), 3);
  for (int call = 0; call < 200; ++call) {
    std::vector<std::atomic<int>> hits(97);
    pool.parallel_for(hits.size(), [&](std::size_t i) { hits[i]++; });
    for (auto& h : hits)
      ASSERT_EQ(h.load(), 1);
  }
}

TEST(ThreadPool, ZeroMeansOnePerCore) {
  EXPECT_GE(resolve_threads(0), 1);
  EXPECT_EQ(resolve_threads(5), 5);
  EXPECT_EQ(ThreadPool(0).size(), resolve_threads(0));
}

TEST(ThreadPool, UsesMoreThanOneThreadAndKeepsThem) {
  ThreadPool pool(2);
  std::set<std::thread::id> first, second;
  std::mutex m;
  std::condition_variable both_seen;
  // Each body waits (up to 10 s, for a loaded machine) until both threads have
  // joined the call, so the count does not depend on scheduling.
  auto record = [&](std::set<std::thread::id>& ids) {
    return [&](std::size_t) {
      std::unique_lock<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
      both_seen.notify_all();
      both_seen.wait_for(lock, std::chrono::seconds(10), [&] { return ids.size() >= 2; });
    };
  };
  pool.parallel_for(8, record(first));
  pool.parallel_for(8, record(second));
  EXPECT_EQ(first.size(), 2u);
  EXPECT_EQ(first, second);  // the same threads: none started per call
}

TEST(ThreadPool, RethrowsTheLowestFailingIndexAndStopsHandingOutWork) {
  ThreadPool pool(2);
  for (int trial = 0; trial < 20; ++trial) {
    std::atomic<int> started{0};
    try {
      pool.parallel_for(1000, [&](std::size_t i) {
        started++;
        if (i == 3 || i == 4) throw std::runtime_error("index " + std::to_string(i));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "index 3");
    }
    EXPECT_LT(started.load(), 1000);
  }
  // The pool still works after a failure.
  std::atomic<int> n{0};
  pool.parallel_for(10, [&](std::size_t) { n++; });
  EXPECT_EQ(n.load(), 10);
}

TEST(ThreadPool, NestedCallsRunInline) {
  ThreadPool pool(2);
  std::atomic<int> n{0};
  pool.parallel_for(4, [&](std::size_t) { pool.parallel_for(5, [&](std::size_t) { n++; }); });
  EXPECT_EQ(n.load(), 20);
}

TEST(ThreadPool, OneThreadRunsOnTheCaller) {
  ThreadPool pool(1);
  const auto caller = std::this_thread::get_id();
  pool.parallel_for(5, [&](std::size_t) { EXPECT_EQ(std::this_thread::get_id(), caller); });
}

}  // namespace
}  // namespace plumekit
