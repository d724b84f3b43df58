// The engine against PyTorch: golden pairs written by surrogate/train/make_golden.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/npy.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

const std::string kDir = std::string(PLUMEKIT_TEST_DATA) + "/surrogate/";

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

void check_golden(const std::string& stem, int threads) {
  const Network net = Network::load(kDir + stem + ".pkcnn", EngineOptions{threads});
  const Tensor input = load_tensor(kDir + stem + "_input.npy");
  const Tensor want = load_tensor(kDir + stem + "_output.npy");
  const double rel = relative_error(net.predict(input), want);
  std::printf("%s, %d thread(s): max relative error %.3g\n", stem.c_str(), threads, rel);
  EXPECT_LT(rel, 1e-4) << stem;
}

TEST(Golden, RealArchitectureMatchesPyTorch) {
  check_golden("real", 1);
}

TEST(Golden, OddChannelsOddGridMatchesPyTorch) {
  check_golden("odd", 1);
}

TEST(Golden, BatchSplitAcrossThreadsGivesTheSameOutput) {
  check_golden("odd", 2);
}

TEST(Golden, RealArchitectureHas600130Parameters) {
  const Network net = Network::load(kDir + "real.pkcnn");
  EXPECT_EQ(net.parameter_count(), 600130u);
  // DESIGN.md: about 0.4 GFLOP per forward pass.
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
