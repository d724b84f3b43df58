#pragma once
// The surrogate's inference engine: a DeepCFD U-Net loaded once from a plumekit-cnn file and run
// many times. Construction either yields a complete network or throws; predict() is const and may
// be called from several threads at once.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/thread_pool.hpp"
#include "surrogate/layers.hpp"
#include "surrogate/model_file.hpp"
#include "surrogate/tensor.hpp"

namespace plumekit::surrogate {

struct EngineOptions {
  // Threads of the network's pool (0: one per core), kept from one predict() call to the next.
  // The samples of a batch are shared out among them; a batch with fewer samples than threads runs
  // each sample's decoders (one per output) side by side instead, after its encoder. Results do
  // not depend on the thread count.
  int threads = kDefaultThreads;
  // OptionError naming engine.threads outside 0..1024.
  void validate() const;
};

class Network {
 public:
  explicit Network(ModelFile file, EngineOptions options = {});
  ~Network();
  Network(Network&&) noexcept;
  Network& operator=(Network&&) noexcept;
  // Reads and checks `path`; InputError naming the file and the fault when it is malformed.
  static Network load(const std::filesystem::path& path, EngineOptions options = {});

  // input [n, in_channels, rows, cols] -> [n, out_channels, rows, cols], each output channel
  // multiplied by its scale from the file (so in the file's output units). rows x cols is the
  // file's grid, or for a physical-grid model any multiples of features.multiple up to
  // kMaxInputSide. std::invalid_argument otherwise.
  Tensor predict(const Tensor& input) const;

  // For tests against PyTorch that must not hinge on max-pool near-ties (docs/design/surrogate.md):
  // the same forward pass, one thread, with every 2x2 max-pool's argmax taken from `indices`
  // instead of computed. indices[b] holds level b's, [n][filters[b]][h_b/2][w_b/2], each the flat
  // y*w+x in that level's input plane (PyTorch's return_indices convention). std::invalid_argument
  // when a size is wrong or an index lies outside its 2x2 window.
  using PoolIndices = std::vector<std::vector<std::int32_t>>;
  Tensor predict_with_pool_indices(const Tensor& input, const PoolIndices& indices) const;

  // The file's description (header, layers, contract, outputs). Its raw tensors are released once
  // converted into the layers, so `weights` and `biases` are empty here.
  const ModelFile& file() const { return file_; }
  // The engine's threads (EngineOptions::threads resolved: at least 1).
  int threads() const;
  std::size_t parameter_count() const;
  // Multiply-adds times two, per sample, of all convolutions at the file's grid (a thesis model)
  // or at rows x cols.
  double flops_per_sample() const;
  double flops_per_sample(int rows, int cols) const;
  // The largest input side a physical-grid model takes (409.6 m at 0.1 m cells).
  static constexpr int kMaxInputSide = 4096;

 private:
  struct Workspace;
  struct WorkspacePool;
  // The encoder fills ws.skips, ws.indices and ws.bottom; decode() reads them (from `enc`) and
  // uses its own `ws` for activations, so the decoders of one sample can run at once.
  // `forced`, when given, holds each level's pool indices for this sample.
  void encode(const float* x, int rows, int cols, Workspace& ws,
              const std::int32_t* const* forced = nullptr) const;
  void check_input(const Tensor& input) const;
  void decode(int output, const Workspace& enc, Workspace& ws, float* y) const;

  ModelFile file_;
  EngineOptions options_;
  std::vector<Conv> encoder_;  // level-major, convs_per_block per level
  std::vector<Conv> decoder_;  // output-major, then level L-1..0, convs_per_block per level
  // Workspaces outlive predict() calls, so a batch of one allocates (and page-faults) nothing.
  std::unique_ptr<WorkspacePool> pool_;
  // The threads persist between predict() calls (a held pointer: Network is movable).
  std::unique_ptr<ThreadPool> threads_;
};

}  // namespace plumekit::surrogate
