// Engine speed on the real architecture (the randomly initialised golden model): ms per sample
// and GFLOP/s at batch 1 and 32, on 1 and 2 threads. The comparison with libtorch, and the GEMM
// peak, are in surrogate_vs_libtorch.cpp (optional target). Arguments: [MODEL.pkcnn [ROWS COLS]];
// a physical-grid model runs at ROWS x COLS, by default 112 x 112 (a 20 x 20 m building at 0.2 m).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "surrogate/network.hpp"

using namespace plumekit::surrogate;

int main(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(PLUMEKIT_TEST_DATA) + "/surrogate/real.pkcnn";
  for (int threads : {1, 2}) {
    const Network net = Network::load(path, EngineOptions{threads});
    const auto& f = net.file().features;
    const int rows = f.physical() ? (argc > 3 ? std::stoi(argv[2]) : 112) : f.rows;
    const int cols = f.physical() ? (argc > 3 ? std::stoi(argv[3]) : 112) : f.cols;
    for (int batch : {1, 32}) {
      Tensor x(batch, net.file().architecture.in_channels, rows, cols);
      std::mt19937 rng(1);
      std::uniform_real_distribution<float> u(0.0f, 4.0f);
      for (float& v : x.data)
        v = u(rng);
      net.predict(x);  // warm-up: workspace, caches
      double best = 1e30;
      for (int rep = 0; rep < 5; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        const int runs = batch == 1 ? 20 : 1;
        for (int r = 0; r < runs; ++r)
          net.predict(x);
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / runs;
        best = std::min(best, s);
      }
      std::printf("%dx%d threads %d  batch %2d: %8.2f ms/batch  %6.2f ms/sample  %6.1f GFLOP/s\n",
                  rows, cols, threads, batch, best * 1e3, best * 1e3 / batch,
                  net.flops_per_sample(rows, cols) * batch / best / 1e9);
    }
  }
  return 0;
}
