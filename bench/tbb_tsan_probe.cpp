// Issue 43: is oneTBB usable under plumekit's ThreadSanitizer build (PLUMEKIT_TSAN, .ci/run)? A
// race-free loop (each index writes its own element) on Debian's libtbb, which is not built with
// TSan, so every report is a false positive from TBB's unseen synchronisation (docs/own-code.md).
// Not built by CMake (it needs -fsanitize=thread on its own):
//
//   g++ -O1 -g -std=c++17 -fsanitize=thread bench/tbb_tsan_probe.cpp -ltbb -o /tmp/tbb_tsan_probe
//   /tmp/tbb_tsan_probe 2>&1 | grep -c "WARNING: ThreadSanitizer"     # 0 would mean usable
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>
#include <atomic>
#include <cstdio>
#include <vector>
int main() {
  tbb::task_arena a(2);
  for (int rep = 0; rep < 50; ++rep) {
    std::vector<long> out(1000);
    a.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, out.size(), 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            for (auto i = r.begin(); i != r.end(); ++i)
              out[i] = long(i) * 3;
          },
          tbb::simple_partitioner());
    });
    long s = 0;
    for (long v : out)
      s += v;
    if (s != 3L * 999 * 1000 / 2) return 1;
  }
  std::puts("ok");
}
