// The engine against PyTorch: golden pairs written by surrogate/train/make_golden.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/npy.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

const std::string kDir = std::string(PLUMEKIT_TEST_DATA) + "/surrogate/";
// The trained models in data/models/, each with the golden pair its training run wrote.
const std::string kModels = std::string(PLUMEKIT_TEST_DATA) + "/../../data/models/";

Tensor load_tensor(const std::string& path) {
  const NpyArray a = read_npy(path);
  EXPECT_EQ(a.shape.size(), 4u) << path;
  Tensor t(static_cast<int>(a.shape[0]), static_cast<int>(a.shape[1]), static_cast<int>(a.shape[2]),
           static_cast<int>(a.shape[3]));
  std::transform(a.values.begin(), a.values.end(), t.data.begin(),
                 [](double v) { return static_cast<float>(v); });
  return t;
}

// max |got - want| / max |want|
double relative_error(const Tensor& got, const Tensor& want) {
  EXPECT_EQ(got.n, want.n);
  EXPECT_EQ(got.c, want.c);
  EXPECT_EQ(got.h, want.h);
  EXPECT_EQ(got.w, want.w);
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < want.data.size(); ++i) {
    err = std::max(err, std::abs(double{got.data[i]} - want.data[i]));
    scale = std::max(scale, std::abs(double{want.data[i]}));
  }
  EXPECT_GT(scale, 0.0);
  return err / scale;
}

void check_golden(const std::string& stem, int threads, const std::string& dir = kDir) {
  const Network net = Network::load(dir + stem + ".pkcnn", EngineOptions{threads});
  const Tensor input = load_tensor(dir + stem + "_input.npy");
  const Tensor want = load_tensor(dir + stem + "_output.npy");
  const double rel = relative_error(net.predict(input), want);
  std::printf("%s, %d thread(s): max relative error %.3g\n", stem.c_str(), threads, rel);
  EXPECT_LT(rel, 1e-4) << stem;
}

TEST(Golden, RealArchitectureMatchesPyTorch) {
  check_golden("real", 1);
}

// The shipped model and the golden pair its training run wrote (two held-out samples, in
// concentration units; train.py picks the samples with the widest max-pool margins).
TEST(Golden, ShippedModelMatchesPyTorch) {
  check_golden("plume-unet", 1, kModels);
  check_golden("plume-unet", 2, kModels);
  EXPECT_EQ(Network::load(kModels + "plume-unet.pkcnn").parameter_count(), 600130u);
}

// The faithful-world fine-tuning committed beside it (issue 18; not the default).
TEST(Golden, FaithfulWorldModelMatchesPyTorch) {
  check_golden("plume-unet-faithful", 2, kModels);
}

// The v2 model (issue 19): a physical-grid network, its golden pair two held-out samples of one
// padded shape (not 64 x 64), in concentration units.
TEST(Golden, PhysicalGridModelMatchesPyTorch) {
  check_golden("plume-unet-v2", 1, kModels);
  check_golden("plume-unet-v2", 2, kModels);
  const Network net = Network::load(kModels + "plume-unet-v2.pkcnn");
  EXPECT_TRUE(net.file().features.physical());
  EXPECT_EQ(net.file().features.multiple, 16);
  EXPECT_EQ(net.parameter_count(), 600530u);  // the thesis's architecture with 5 inputs
}

// The hybrid model (issue 46): six inputs, the physics plume of the source among them; its golden
// pair two held-out building samples of one padded shape, in concentration units (not residual:
// the network's output is the prediction).
TEST(Golden, HybridModelMatchesPyTorch) {
  check_golden("plume-unet-v3", 1, kModels);
  check_golden("plume-unet-v3", 2, kModels);
  const Network net = Network::load(kModels + "plume-unet-v3.pkcnn");
  EXPECT_TRUE(net.file().features.has_physics());
  EXPECT_EQ(net.file().features.physics_channel, 4);
  EXPECT_TRUE(net.file().outputs.at(0).plus_input.empty());
  EXPECT_EQ(net.parameter_count(), 600730u);  // the thesis's architecture with 6 inputs
}

TEST(Golden, OddChannelsOddGridMatchesPyTorch) {
  check_golden("odd", 1);
}

TEST(Golden, BatchSplitAcrossThreadsGivesTheSameOutput) {
  check_golden("odd", 2);
}

TEST(Golden, ThreadCountsAndRepeatedCallsGiveTheSameBytes) {
  // Batch 1 on 2 threads runs the two decoders side by side; batch 3 on 2 threads splits the
  // samples; later calls reuse pooled workspaces. All must give the bytes of one thread.
  const Tensor input = load_tensor(kDir + "real_input.npy");
  const Network one = Network::load(kDir + "real.pkcnn", EngineOptions{1});
  const Network two = Network::load(kDir + "real.pkcnn", EngineOptions{2});
  const Tensor want = one.predict(input);
  EXPECT_EQ(two.predict(input).data, want.data);
  EXPECT_EQ(two.predict(input).data, want.data);
  EXPECT_EQ(one.predict(input).data, want.data);
  Tensor three(3, input.c, input.h, input.w);
  for (int i = 0; i < 3; ++i)
    std::copy(input.data.begin(), input.data.end(), three.sample_data(i));
  const Tensor got = two.predict(three);
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(std::equal(want.data.begin(), want.data.end(), got.sample_data(i))) << i;
}

// The engine's pool (core/thread_pool) outlives each call: five threads on batches of 1, 3 and 7
// (decoders side by side, then samples shared out), called again and again, from the default (one
// per core) too, give the bytes of one thread. A negative count names its field.
TEST(Golden, APersistentPoolOfAnySizeGivesTheSameBytes) {
  const Tensor input = load_tensor(kDir + "real_input.npy");
  const Network one = Network::load(kDir + "real.pkcnn", EngineOptions{1});
  const Network five = Network::load(kDir + "real.pkcnn", EngineOptions{5});
  const Network cores = Network::load(kDir + "real.pkcnn");
  const Tensor want = one.predict(input);
  for (int n : {1, 3, 7, 1}) {
    Tensor batch(n, input.c, input.h, input.w);
    for (int i = 0; i < n; ++i)
      std::copy(input.data.begin(), input.data.end(), batch.sample_data(i));
    for (const Network* net : {&five, &cores}) {
      const Tensor got = net->predict(batch);
      for (int i = 0; i < n; ++i)
        EXPECT_TRUE(std::equal(want.data.begin(), want.data.end(), got.sample_data(i)))
            << "batch " << n << " sample " << i;
    }
  }
  try {
    Network::load(kDir + "real.pkcnn", EngineOptions{-1});
    ADD_FAILURE() << "no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "engine.threads");
  }
}

// PyTorch's pool indices for a golden pair, split into the engine's levels.
Network::PoolIndices load_pool_indices(const std::string& stem, const Network& net, int n) {
  const NpyArray a = read_npy(kDir + stem + "_pool_indices.npy");
  const auto& arch = net.file().architecture;
  Network::PoolIndices out;
  std::size_t at = 0;
  int h = net.file().features.rows, w = net.file().features.cols;
  for (int f : arch.filters) {
    h /= 2;
    w /= 2;
    const std::size_t count = static_cast<std::size_t>(n) * f * h * w;
    EXPECT_LE(at + count, a.values.size()) << stem;
    if (at + count > a.values.size()) return out;
    out.emplace_back(a.values.begin() + at, a.values.begin() + at + count);
    at += count;
  }
  EXPECT_EQ(at, a.values.size()) << stem;
  return out;
}

TEST(Golden, EngineMaxPoolPicksPyTorchsArgmax) {
  // On pairs whose pool decisions have margins (real, 2e-6) or exact ties broken by the same rule
  // (odd), forcing PyTorch's indices changes not one bit of the engine's output.
  for (const std::string stem : {"real", "odd"}) {
    const Network net = Network::load(kDir + stem + ".pkcnn");
    const Tensor input = load_tensor(kDir + stem + "_input.npy");
    const Tensor forced =
        net.predict_with_pool_indices(input, load_pool_indices(stem, net, input.n));
    EXPECT_EQ(forced.data, net.predict(input).data) << stem;
  }
}

TEST(Golden, NearTiesMatchPyTorchWithItsPoolIndices) {
  // Smooth, plume-like features put max-pool windows within float32 rounding of a tie (margin
  // 4e-7 here; 1e-8 on real plumes), where two correct engines may pick different argmaxes and
  // max-unpool then moves a value. With PyTorch's indices forced, the rest must agree to 1e-4.
  const Network net = Network::load(kDir + "real.pkcnn");
  const Tensor input = load_tensor(kDir + "real_smooth_input.npy");
  const Tensor want = load_tensor(kDir + "real_smooth_output.npy");
  const double forced = relative_error(
      net.predict_with_pool_indices(input, load_pool_indices("real_smooth", net, input.n)), want);
  const double free = relative_error(net.predict(input), want);
  std::printf("real_smooth: max relative error %.3g with PyTorch's pool indices, %.3g without\n",
              forced, free);
  EXPECT_LT(forced, 1e-4);
}

TEST(Golden, ForcedPoolIndicesAreChecked) {
  const Network net = Network::load(kDir + "odd.pkcnn");
  const Tensor input = load_tensor(kDir + "odd_input.npy");
  Network::PoolIndices good = load_pool_indices("odd", net, input.n);
  Network::PoolIndices bad = good;
  bad[1][3] += 2;  // the window's neighbour
  EXPECT_THROW(net.predict_with_pool_indices(input, bad), std::invalid_argument);
  bad = good;
  bad[2].pop_back();
  EXPECT_THROW(net.predict_with_pool_indices(input, bad), std::invalid_argument);
  bad = good;
  bad.pop_back();
  EXPECT_THROW(net.predict_with_pool_indices(input, bad), std::invalid_argument);
  EXPECT_NO_THROW(net.predict_with_pool_indices(input, good));
  // And they are used: another pixel of the same window changes the output (for some window).
  const std::vector<float> base = net.predict_with_pool_indices(input, good).data;
  int changed = 0;
  for (std::size_t q = 0; q < 20; ++q) {
    bad = good;
    const int w = net.file().features.cols;
    bad[0][q] += bad[0][q] % w % 2 == 0 ? 1 : -1;  // the other column of the window
    changed += net.predict_with_pool_indices(input, bad).data != base;
  }
  EXPECT_GT(changed, 0);
}

TEST(Golden, RealArchitectureHas600130Parameters) {
  const Network net = Network::load(kDir + "real.pkcnn");
  EXPECT_EQ(net.parameter_count(), 600130u);
  // docs/design/surrogate.md, "Architecture": about 0.4 GFLOP per forward pass.
  EXPECT_NEAR(net.flops_per_sample() / 1e9, 0.4, 0.1);
}

TEST(Golden, PredictRefusesAWrongInputShape) {
  const Network net = Network::load(kDir + "odd.pkcnn");
  EXPECT_THROW(net.predict(Tensor(1, 3, 64, 64)), std::invalid_argument);
}

TEST(Golden, NetworkRefusesAnInconsistentHandMadeModelFile) {
  ModelFile m = read_model_file(kDir + "odd.pkcnn");
  m.biases.pop_back();
  EXPECT_THROW(Network{m}, std::invalid_argument);
}

}  // namespace
}  // namespace plumekit::surrogate
