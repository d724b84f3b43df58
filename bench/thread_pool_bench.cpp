// Issue 43 ("Own less"): core/thread_pool against oneTBB (libtbb-dev) doing the same job under the
// same contract: a task_arena of the pool's size and tbb::parallel_for over single indices
// (simple_partitioner, grain 1, as the pool hands out one index at a time), each body wrapped so
// that the lowest failing index's exception is the one rethrown. Here our pool is the baseline and
// TBB the candidate library ("library"): docs/own-code.md says which stays and why.
//
//   build/bench/thread_pool_bench [--benchmark_repetitions=5] [--threads=N]   # N: default 2
//
// Work per index is a fixed amount of arithmetic (~0.4 us, ~20 us, ~1.5 ms on the build machine),
// counts as plumekit's callers use them: the engine's decoders (a few per layer), a dataset's or an
// evaluation's runs. Each loop's sum is checked equal on both sides. Times are wall times
// (UseRealTime).
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <vector>

#include "bench/baseline_ratio.hpp"
#include "core/thread_pool.hpp"

namespace {

int g_threads = 2;

// ThreadPool's contract on oneTBB: `threads` slots, the caller's included.
class TbbPool {
 public:
  explicit TbbPool(int threads) : arena_(plumekit::resolve_threads(threads)) {}

  // TBB steals work in no fixed order, so after index i fails the indices below i must still run
  // (our pool has handed them all out already); those above are skipped.
  void parallel_for(std::size_t count, const std::function<void(std::size_t)>& body) {
    std::atomic<std::size_t> lowest{count};  // the lowest failed index so far; count: none
    std::mutex m;
    std::exception_ptr error;
    arena_.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, count, 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
              if (i > lowest.load(std::memory_order_relaxed)) return;
              try {
                body(i);
              } catch (...) {
                std::lock_guard<std::mutex> lock(m);
                if (i < lowest) lowest = i, error = std::current_exception();
              }
            }
          },
          tbb::simple_partitioner());
    });
    if (error) std::rethrow_exception(error);
  }

 private:
  tbb::task_arena arena_;
};

// Deterministic arithmetic the compiler cannot drop: `units` rounds of a xorshift.
std::uint64_t work(std::size_t index, int units) {
  std::uint64_t x = 0x9e3779b97f4a7c15ull ^ index;
  for (int k = 0; k < units; ++k)
    for (int j = 0; j < 256; ++j) {
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
    }
  return x;
}

template <class Pool>
std::uint64_t loop(Pool& pool, std::size_t count, int units) {
  std::vector<std::uint64_t> out(count);
  pool.parallel_for(count, [&](std::size_t i) { out[i] = work(i, units); });
  std::uint64_t sum = 0;
  for (std::uint64_t v : out)
    sum += v;
  return sum;
}

template <class Pool>
void run(benchmark::State& state) {
  Pool pool(g_threads);
  const auto count = static_cast<std::size_t>(state.range(0));
  const int units = static_cast<int>(state.range(1));
  for (auto _ : state)
    benchmark::DoNotOptimize(loop(pool, count, units));
  state.counters["threads"] = g_threads;
}

// Units: 1 ~ 0.4 us, 50 ~ 20 us, 2000 ~ 1.5 ms of work per index (the build machine).
void cases(benchmark::internal::Benchmark* b) {
  b->Args({1000, 1})->Args({64, 50})->Args({4, 50})->Args({16, 2000})->UseRealTime();
}

}  // namespace

BENCHMARK(run<plumekit::ThreadPool>)->Name("pool/baseline")->Apply(cases);
BENCHMARK(run<TbbPool>)->Name("pool/library")->Apply(cases);

int main(int argc, char** argv) {
  for (int k = 1; k < argc; ++k)
    if (std::strncmp(argv[k], "--threads=", 10) == 0) g_threads = std::atoi(argv[k] + 10);
  std::vector<char*> rest;
  for (int k = 0; k < argc; ++k)
    if (std::strncmp(argv[k], "--threads=", 10) != 0) rest.push_back(argv[k]);
  // The same results from both, and the same lowest failing index.
  plumekit::ThreadPool ours(g_threads);
  TbbPool tbb_pool(g_threads);
  if (loop(ours, 1000, 3) != loop(tbb_pool, 1000, 3)) {
    std::fprintf(stderr, "thread_pool_bench: results differ\n");
    return 1;
  }
  try {
    tbb_pool.parallel_for(1000, [](std::size_t i) {
      if (i == 3 || i == 700) throw static_cast<int>(i);
    });
    return std::fprintf(stderr, "thread_pool_bench: TBB rethrew nothing\n"), 1;
  } catch (int i) {
    if (i != 3) return std::fprintf(stderr, "thread_pool_bench: TBB rethrew index %d\n", i), 1;
  }
  int rest_argc = static_cast<int>(rest.size());
  return plumekit_bench::run_with_ratios(rest_argc, rest.data());
}
