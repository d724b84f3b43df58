// The engine against libtorch on the same weights, in one process: ms per sample, GFLOP/s and the
// ratio, at batch 1 and 32 on 1 and 2 threads; and the machine's GEMM peak measured with Eigen, so
// the engine's GFLOP/s can be read as a fraction of it (each repeat times the GEMM, the engine and
// libtorch back to back, so all three see the same machine load).
//
// libtorch gets the weights from the same .pkcnn: read_model_file() gives every tensor in PyTorch's
// own layout, which this program copies into torch::nn::Conv2d / ConvTranspose2d modules wired like
// train/model.py (relu after each encoder conv, max-pool with indices, max-unpool, cat [skip, up]).
// Its output is checked against the engine's before anything is timed.
//
// The two engines are timed alternately, repeat by repeat, so a change in the machine's load hits
// both; medians of the repeats are printed. Build: scripts/install-deps.sh libtorch-dev, then the
// target surrogate_vs_libtorch appears (it is built only when CMake finds Torch).
#include <torch/torch.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/statistics.hpp"
#include "surrogate/model_file.hpp"
#include "surrogate/network.hpp"

using namespace plumekit::surrogate;
using plumekit::median;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds of the whole process, all threads: on a machine shared with other work, the cost of
// the code itself, much less disturbed than wall time by how often the scheduler lets it run.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// Wall and CPU seconds of one call of f.
template <class F>
std::pair<double, double> timed(F&& f) {
  const double c0 = cpu_seconds();
  const auto t0 = Clock::now();
  f();
  return {seconds_since(t0), cpu_seconds() - c0};
}

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// train/model.py's PlumeUNet, built from a model file's layer table and tensors.
class TorchUNet {
 public:
  explicit TorchUNet(const ModelFile& f) : arch_(f.architecture), outputs_(f.outputs) {
    torch::NoGradGuard no_grad;
    for (std::size_t i = 0; i < f.layers.size(); ++i) {
      const LayerSpec& l = f.layers[i];
      const auto k = l.kernel;
      auto weight = torch::from_blob(const_cast<float*>(f.weights[i].data()),
                                     {l.op == LayerOp::kConv2d ? l.out : l.in,
                                      l.op == LayerOp::kConv2d ? l.in : l.out, k, k})
                        .clone();
      auto bias = torch::from_blob(const_cast<float*>(f.biases[i].data()), {l.out}).clone();
      if (l.op == LayerOp::kConv2d) {
        torch::nn::Conv2d c(torch::nn::Conv2dOptions(l.in, l.out, k).padding(l.padding));
        c->weight.copy_(weight);
        c->bias.copy_(bias);
        c->eval();
        encoder_.push_back(c);
      } else {
        torch::nn::ConvTranspose2d c(
            torch::nn::ConvTranspose2dOptions(l.in, l.out, k).padding(l.padding));
        c->weight.copy_(weight);
        c->bias.copy_(bias);
        c->eval();
        decoder_.push_back(c);
      }
      relu_.push_back(l.relu);
    }
  }

  torch::Tensor forward(torch::Tensor x) {
    const int levels = static_cast<int>(arch_.filters.size()), n = arch_.convs_per_block;
    std::vector<torch::Tensor> skips, indices;
    for (int b = 0; b < levels; ++b) {
      for (int j = 0; j < n; ++j)
        x = torch::relu(encoder_[b * n + j]->forward(x));
      skips.push_back(x);
      auto [pooled, index] = torch::max_pool2d_with_indices(x, {2, 2}, {2, 2});
      x = pooled;
      indices.push_back(index);
    }
    std::vector<torch::Tensor> outs;
    std::size_t k = 0;
    for (int o = 0; o < arch_.out_channels; ++o) {
      torch::Tensor y = x;
      for (int b = levels - 1; b >= 0; --b) {
        y = torch::max_unpool2d(y, indices[b], {skips[b].size(2), skips[b].size(3)});
        y = torch::cat({skips[b], y}, 1);
        for (int j = 0; j < n; ++j, ++k) {
          y = decoder_[k]->forward(y);
          if (relu_[encoder_.size() + k]) y = torch::relu(y);
        }
      }
      outs.push_back(y * outputs_[o].scale);
    }
    return torch::cat(outs, 1);
  }

 private:
  Architecture arch_;
  std::vector<OutputSpec> outputs_;
  std::vector<torch::nn::Conv2d> encoder_;
  std::vector<torch::nn::ConvTranspose2d> decoder_;
  std::vector<bool> relu_;
};

// Eigen's single-precision GEMM at n^3 on `threads` threads (one independent product each), GFLOP/s
// summed over threads: the machine's practical peak for the kind of code the engine runs.
struct Gemm {
  int n, threads;
  std::vector<RowMatrix> a, b, c;
  Gemm(int n_, int threads_) : n(n_), threads(threads_) {
    for (int t = 0; t < threads; ++t) {
      a.push_back(RowMatrix::Random(n, n));
      b.push_back(RowMatrix::Random(n, n));
      c.emplace_back(n, n);
      c[t].noalias() = a[t] * b[t];  // warm-up
    }
  }
  // GFLOP/s of wall time (all threads) and GFLOP per CPU second (per core).
  std::pair<double, double> rate() {
    const auto [wall, cpu] = timed([&] {
      auto one = [&](int t) { c[t].noalias() = a[t] * b[t]; };
      std::vector<std::thread> pool;
      for (int t = 1; t < threads; ++t)
        pool.emplace_back(one, t);
      one(0);
      for (auto& th : pool)
        th.join();
    });
    const double flops = 2.0 * n * n * n * threads;
    return {flops / wall / 1e9, flops / cpu / 1e9};
  }
};

}  // namespace

int main(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(PLUMEKIT_TEST_DATA) + "/surrogate/real.pkcnn";
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 7;
  const ModelFile file = read_model_file(path);
  TorchUNet torch_net(file);
  const auto& f = file.features;
  // A physical-grid model: 112 x 112 by default (20 x 20 m at 0.2 m, padded to 16), or ROWS COLS.
  const int in_rows = f.physical() ? (argc > 4 ? std::stoi(argv[3]) : 112) : f.rows;
  const int in_cols = f.physical() ? (argc > 4 ? std::stoi(argv[4]) : 112) : f.cols;
  std::printf("model %s: %zu parameters, input %d x %d; %d repeats, medians\n", path.c_str(),
              parameter_count(file.layers), in_rows, in_cols, repeats);

  struct Row {
    int threads, batch;
    double flops, diff;
    std::vector<double> ours, theirs, peak;              // wall: s per sample, GFLOP/s
    std::vector<double> ours_cpu, theirs_cpu, peak_cpu;  // CPU s per sample, GFLOP per CPU s
  };
  std::vector<Row> rows;
  for (int threads : {1, 2}) {
    const Network net(file, EngineOptions{threads});
    Gemm gemm(1024, threads);
    torch::set_num_threads(threads);
    for (int batch : {1, 32}) {
      Tensor x(batch, file.architecture.in_channels, in_rows, in_cols);
      std::mt19937 rng(1);
      std::uniform_real_distribution<float> u(0.0f, 4.0f);
      for (float& v : x.data)
        v = u(rng);
      const torch::Tensor tx = torch::from_blob(x.data.data(), {x.n, x.c, x.h, x.w}).clone();
      torch::NoGradGuard no_grad;
      // Same weights, same answer: max |difference| over max |value|.
      const Tensor ours = net.predict(x);
      const torch::Tensor theirs = torch_net.forward(tx).contiguous();
      double diff = 0, top = 0;
      for (std::size_t i = 0; i < ours.data.size(); ++i) {
        diff = std::max(diff, std::abs(double(ours.data[i]) - theirs.data_ptr<float>()[i]));
        top = std::max(top, std::abs(double(ours.data[i])));
      }
      Row row{threads,
              batch,
              net.flops_per_sample(in_rows, in_cols),
              top > 0 ? diff / top : diff,
              {},
              {},
              {},
              {},
              {},
              {}};
      const int runs = batch == 1 ? 10 : 1;
      for (int r = 0; r < repeats; ++r) {
        const auto [gw, gc] = gemm.rate();
        row.peak.push_back(gw);
        row.peak_cpu.push_back(gc);
        auto [w, c] = timed([&] {
          for (int i = 0; i < runs; ++i)
            net.predict(x);
        });
        row.ours.push_back(w / runs / batch);
        row.ours_cpu.push_back(c / runs / batch);
        std::tie(w, c) = timed([&] {
          for (int i = 0; i < runs; ++i)
            torch_net.forward(tx);
        });
        row.theirs.push_back(w / runs / batch);
        row.theirs_cpu.push_back(c / runs / batch);
      }
      rows.push_back(row);
    }
  }
  // One table per clock. speed-up and %peak are medians of per-repeat ratios (same load).
  for (bool cpu : {false, true}) {
    std::printf(cpu ? "\nCPU time (all threads; GFLOP per CPU second, i.e. per core)\n"
                    : "\nwall time\n");
    std::printf(
        "threads batch | engine ms/sample GFLOP/s %%peak | libtorch ms/sample GFLOP/s | "
        "speed-up | Eigen GEMM GFLOP/s\n");
    for (const Row& r : rows) {
      const auto& a = cpu ? r.ours_cpu : r.ours;
      const auto& b = cpu ? r.theirs_cpu : r.theirs;
      const auto& p = cpu ? r.peak_cpu : r.peak;
      std::vector<double> ratio, of_peak;
      for (std::size_t i = 0; i < a.size(); ++i) {
        ratio.push_back(b[i] / a[i]);
        of_peak.push_back(r.flops / a[i] / 1e9 / p[i]);
      }
      std::printf(
          "   %d    %3d  |   %7.2f    %6.1f   %4.0f%% |   %7.2f    %6.1f  | %5.2fx  |  %6.1f  "
          "(max rel diff %.1e)\n",
          r.threads, r.batch, median(a) * 1e3, r.flops / median(a) / 1e9, 100 * median(of_peak),
          median(b) * 1e3, r.flops / median(b) / 1e9, median(ratio), median(p), r.diff);
    }
  }
  std::printf(
      "\nspeed-up = libtorch time / engine time; %%peak = engine GFLOP/s over Eigen's 1024^3 "
      "GEMM on as many threads (wall) or per core (CPU); both the median over the repeats of "
      "ratios measured back to back in one repeat.\n");
  return 0;
}
