// Hybrid model files (issue 46): a physical-grid model whose inputs hold physics_mean (the physics
// plume, divided by its channel's scale, with the plume's options) and whose mean may be a residual
// over it (plus_input). The contract is read and each fault refused naming the file and the key;
// the engine against PyTorch on the committed golden pair, the residual summed by
// residual_output() as PlumeNetwork sums it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/npy.hpp"
#include "physical_model.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

using test::expect_refused;
using test::hybrid_model;
using test::PhysicalModel;

TEST(HybridModelFile, ReadsThePhysicsChannelAndTheResidualMean) {
  const ModelFile m = hybrid_model({4, 4}).parse();
  const FeatureContract& f = m.features;
  EXPECT_TRUE(f.physical());
  EXPECT_TRUE(f.has_physics());
  EXPECT_EQ(f.physics_channel, 4);
  EXPECT_EQ(f.source_channel(), 5);
  ASSERT_EQ(f.channels.size(), 6u);
  EXPECT_EQ(f.channels[4].name, "physics_mean");
  EXPECT_EQ(f.channels[4].unit, "concentration / scale");
  EXPECT_EQ(f.physics.scale, 250.0);
  EXPECT_EQ(f.physics.diffusivity, 0.05);
  EXPECT_EQ(f.physics.decay_rate, 1.0 / 28.0);
  EXPECT_EQ(f.physics.release_rate, 1000.0);
  ASSERT_EQ(m.outputs.size(), 2u);
  EXPECT_EQ(m.outputs[0].plus_input, "physics_mean");
  EXPECT_EQ(m.outputs[0].scale, 40.0f);
  EXPECT_EQ(m.outputs[1].plus_input, "");
  EXPECT_EQ(feature_channel_names(true, true),
            (std::vector<std::string>{"region", "signed_distance", "wind_u", "wind_v",
                                      "physics_mean", "source_distance"}));
  // A plain 6-channel model (the physics as an input, no residual) and a zero decay are fine.
  PhysicalModel plain = hybrid_model({4, 4});
  plain.header["outputs"][0].erase("plus_input");
  plain.header["features"]["channels"][4]["decay_rate"] = 0.0;
  const ModelFile p = plain.parse();
  EXPECT_TRUE(p.features.has_physics());
  EXPECT_EQ(p.outputs[0].plus_input, "");
  EXPECT_EQ(p.features.physics.decay_rate, 0.0);
  // Models without the channel: none of it.
  const ModelFile v2 = test::physical_model({4, 4}).parse();
  EXPECT_FALSE(v2.features.has_physics());
  EXPECT_EQ(v2.features.physics_channel, -1);
}

TEST(HybridModelFile, RefusesABadScaleOrPlumeOptionNamingTheKey) {
  const auto with = [](const char* key, const nlohmann::json& v) {
    PhysicalModel m = hybrid_model({4, 4});
    m.header["features"]["channels"][4][key] = v;
    return m;
  };
  expect_refused(with("scale", 0.0), "features.channels[4].scale");
  expect_refused(with("scale", -2.0), "features.channels[4].scale");
  expect_refused(with("scale", "big"), "features.channels[4].scale has the wrong type");
  expect_refused(with("diffusivity", 0.0), "features.channels[4].diffusivity");
  expect_refused(with("diffusivity", 500.0), "features.channels[4].diffusivity");
  expect_refused(with("decay_rate", -0.01), "features.channels[4].decay_rate");
  expect_refused(with("release_rate", 0.0), "features.channels[4].release_rate");
  PhysicalModel missing = hybrid_model({4, 4});
  missing.header["features"]["channels"][4].erase("release_rate");
  expect_refused(missing, "has no \"release_rate\"");
  PhysicalModel unit = hybrid_model({4, 4});
  unit.header["features"]["channels"][4]["unit"] = "concentration";
  expect_refused(unit, "physics_mean (concentration / scale)");
  // Six channels in another order: the physics plume stands before the source distance.
  PhysicalModel order = hybrid_model({4, 4});
  std::swap(order.header["features"]["channels"][3], order.header["features"]["channels"][4]);
  expect_refused(order, "features.channels[3] is \"physics_mean\"");
}

TEST(HybridModelFile, RefusesPlusInputOnTheStdOnAnotherInputOrWithoutTheChannel) {
  PhysicalModel on_std = hybrid_model({4, 4});
  on_std.header["outputs"][1]["plus_input"] = "physics_mean";
  expect_refused(on_std, "outputs[1] (\"std\") has plus_input");
  PhysicalModel other = hybrid_model({4, 4});
  other.header["outputs"][0]["plus_input"] = "wind_u";
  expect_refused(other, "outputs[0].plus_input is \"wind_u\"");
  // A v2 (five-channel) model cannot add a channel it does not have.
  PhysicalModel v2 = test::physical_model({4, 4});
  v2.header["outputs"][0]["plus_input"] = "physics_mean";
  expect_refused(v2, "shape mismatch: outputs[0].plus_input");
  // Nor seven channels, nor six whose fifth is not the physics plume.
  PhysicalModel seven = test::physical_model({4, 4}, 3, 1, 0.2, 1, 7);
  nlohmann::json c = test::hybrid_channels();
  const nlohmann::json first = c[0];
  c.insert(c.begin(), first);
  seven.header["features"]["channels"] = c;
  expect_refused(seven, "5 (6 with physics_mean)");
}

// The committed pair (make_golden.py): PyTorch's network on an arbitrary six-channel input, the
// mean being scale * network + the physics channel's scale * its input.
TEST(HybridGolden, TheResidualMeanMatchesPyTorch) {
  const std::string dir = std::string(PLUMEKIT_TEST_DATA) + "/surrogate/";
  const Network net = Network::load(dir + "hybrid.pkcnn", EngineOptions{1});
  const FeatureContract& f = net.file().features;
  ASSERT_TRUE(f.has_physics());
  const NpyArray in = read_npy(dir + "hybrid_input.npy");
  const NpyArray want = read_npy(dir + "hybrid_output.npy");
  ASSERT_EQ(in.shape.size(), 4u);
  Tensor x(static_cast<int>(in.shape[0]), static_cast<int>(in.shape[1]),
           static_cast<int>(in.shape[2]), static_cast<int>(in.shape[3]));
  std::transform(in.values.begin(), in.values.end(), x.data.begin(),
                 [](double v) { return static_cast<float>(v); });
  const Tensor raw = net.predict(x);
  Tensor y = raw;
  ASSERT_EQ(want.values.size(), y.data.size());
  const std::size_t plane = static_cast<std::size_t>(x.h) * x.w;
  const std::vector<OutputSpec>& outs = net.file().outputs;
  for (int n = 0; n < y.n; ++n)
    for (int o = 0; o < y.c; ++o) {
      if (outs[o].plus_input.empty()) continue;
      float* v = y.sample_data(n) + o * plane;
      const float* phys = x.sample_data(n) + f.physics_channel * plane;
      for (std::size_t q = 0; q < plane; ++q)
        v[q] = residual_output(v[q], phys[q], f.physics.scale);
    }
  // Max-abs error over max-abs value of each output, as the other golden pairs.
  for (int o = 0; o < y.c; ++o) {
    double err = 0, scale = 0, residual = 0;
    for (int n = 0; n < y.n; ++n)
      for (std::size_t q = 0; q < plane; ++q) {
        const std::size_t k = (static_cast<std::size_t>(n) * y.c + o) * plane + q;
        err = std::max(err, std::abs(double{y.data[k]} - want.values[k]));
        scale = std::max(scale, std::abs(want.values[k]));
        residual = std::max(residual, std::abs(want.values[k] - raw.data[k]));
      }
    std::printf("hybrid output %d: max relative error %.3g\n", o, err / scale);
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(err / scale, 1e-4) << o;
    // The physics plume is a large part of the mean: without it the mean would be far off.
    if (!outs[o].plus_input.empty()) {
      EXPECT_GT(residual / scale, 0.1) << o;
    }
  }
}

}  // namespace
}  // namespace plumekit::surrogate
