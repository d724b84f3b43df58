// PlumeNetwork with a hybrid model (issue 46): the physics_mean channel is the dataset's own
// (`dataset generate --physics-input`: surrogate::PhysicsFeature in the map's wind) divided by the
// channel's scale; the residual mean is the network's scaled mean plus the physics plume, then
// obstacle cells zeroed and negatives clamped; batches give the bytes of single predictions; the
// model refuses to run without the wind its physics plume is solved in.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/npy.hpp"
#include "dataset/generator.hpp"
#include "dataset/manifest.hpp"
#include "dataset/wind_cache.hpp"
#include "map/map_json.hpp"
#include "physical_model.hpp"
#include "surrogate/features.hpp"
#include "surrogate/plume_network.hpp"

namespace plumekit::surrogate {
namespace {

namespace fs = std::filesystem;

// A power of two: the engine's channel (concentration / scale) times it is then the dataset's
// float (raw concentration) exactly, so the two can be compared bit for bit.
constexpr double kScale = 256.0;

// One small random map of 5 x 3 m with two sources, its wind and the physics channel written by
// the dataset generator (the advection-diffusion simulator: fast; only the inputs are compared).
struct HybridData {
  fs::path dir;
  Map map;
  cfd::WindField wind;
  NpyArray inputs;
  dataset::DatasetOptions options;
};

const HybridData& hybrid_data() {
  static const HybridData d = [] {
    HybridData h;
    h.dir = fs::temp_directory_path() /
            ("plumekit-hybrid-plume-network-test-" + std::to_string(::getpid()));
    fs::remove_all(h.dir);
    dataset::DatasetOptions& o = h.options;
    o.maps = 1;
    o.sources = 2;
    o.seed = 11;
    o.map.width = 5.0;
    o.map.height = 3.0;
    o.map.families = {"l-shape"};
    o.flow.cell = 0.1;
    o.flow.convection = cfd::Convection::Upwind;
    o.plume.model = dataset::PlumeSimulator::AdvectionDiffusion;
    o.feature_cell = 0.2;
    o.physics_input = true;
    dataset::generate_dataset(h.dir, o, dataset::RunOptions{});
    h.map = read_map(h.dir / "maps" / "map-00000.json");
    h.wind = *dataset::read_wind_cache(h.dir / "wind" / "map-00000", h.map);
    h.inputs = read_npy(h.dir / "shards" / "shard-00000" / "inputs.npy");
    fs::remove_all(h.dir);
    return h;
  }();
  return d;
}

// The C++ random-weight hybrid model with the dataset's physics options and scale kScale.
test::PhysicalModel hybrid_file(const dataset::DatasetOptions& o) {
  test::PhysicalModel m = test::hybrid_model({4, 4}, 3, 1, 0.2, 3);
  const cfd::AdvectionDiffusionOptions p = dataset::physics_mean_options(o);
  nlohmann::json& c = m.header["features"]["channels"][4];
  c["scale"] = kScale;
  c["diffusivity"] = p.diffusivity;
  c["decay_rate"] = p.decay_rate;
  c["release_rate"] = p.release_rate;
  return m;
}

std::shared_ptr<const Network> network(const test::PhysicalModel& m, int threads = 1) {
  return std::make_shared<const Network>(m.parse("hybrid.pkcnn"), EngineOptions{threads});
}

TEST(HybridPlumeNetwork, ThePhysicsChannelIsTheDatasetsOverTheScale) {
  const HybridData& d = hybrid_data();
  const GridShape g = physical_grid(d.map, 0.2);
  ASSERT_EQ(d.inputs.shape, (std::vector<std::size_t>{2, 6, std::size_t(g.ny), std::size_t(g.nx)}));
  const PlumeNetwork model(network(hybrid_file(d.options)), d.map, &d.wind);
  const PhysicsFeature physics(d.map, d.wind, g, dataset::physics_mean_options(d.options));
  const std::size_t plane = static_cast<std::size_t>(model.input_rows()) * model.input_cols();
  const std::size_t cells = g.size();
  for (int s = 0; s < 2; ++s) {
    const Vec2 source = d.map.sources[s];
    const std::vector<float> x = model.features(source);
    ASSERT_EQ(x.size(), 6 * plane);
    const Grid<double> c = physics(source);
    std::size_t differ = 0, plume = 0;
    for (int j = 0; j < model.input_rows(); ++j)
      for (int i = 0; i < model.input_cols(); ++i) {
        const std::size_t q = static_cast<std::size_t>(j) * model.input_cols() + i;
        const float got = x[4 * plane + q];
        if (i >= g.nx || j >= g.ny) {
          EXPECT_EQ(got, 0.0f) << "padding " << i << "," << j;
          continue;
        }
        const std::size_t k = g.index(i, j);
        const std::size_t at = static_cast<std::size_t>(s) * 6 * cells;
        const auto stored = static_cast<float>(d.inputs.values[at + 4 * cells + k]);
        EXPECT_EQ(got, static_cast<float>(c.values[k] / kScale)) << k;
        if (stored >= 1e-30f) {  // not subnormal: a power-of-two scale is exact
          differ += got * static_cast<float>(kScale) != stored;
          plume += stored > 1.0f;
        } else {
          EXPECT_LT(std::abs(got), 1e-30f) << k;
        }
        // The map's channels, region to wind_v, are the dataset's too.
        for (int ch = 0; ch < 4; ++ch)
          differ += x[ch * plane + q] != static_cast<float>(d.inputs.values[at + ch * cells + k]);
      }
    EXPECT_EQ(differ, 0u) << "source " << s;
    EXPECT_GT(plume, 20u) << "source " << s;  // a plume, not an empty channel
  }
}

TEST(HybridPlumeNetwork, TheMeanIsTheNetworksPlusThePhysicsPlumeThenClamped) {
  const HybridData& d = hybrid_data();
  const auto net = network(hybrid_file(d.options), 2);
  const PlumeNetwork model(net, d.map, &d.wind);
  const GridShape& g = model.grid();
  const PhysicsFeature physics(d.map, d.wind, g, dataset::physics_mean_options(d.options));
  const Vec2 source = d.map.sources[0];
  const PlumePrediction p = model.predict(source);
  Tensor x(1, 6, model.input_rows(), model.input_cols());
  const std::vector<float> f = model.features(source);
  std::copy(f.begin(), f.end(), x.data.begin());
  const Tensor y = net->predict(x);
  const Grid<double> c = physics(source);
  const std::size_t plane = x.plane();
  int summed = 0, clamped = 0, obstacle = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j), q = static_cast<std::size_t>(j) * model.input_cols() + i;
      const bool solid = d.map.obstacle_at(g.centre(i, j)) >= 0;
      // The network's mean, times its scale 40 (Network::predict), plus the physics plume in
      // concentration units: the channel times its scale.
      const float sum = residual_output(y.data[q], f[4 * plane + q], kScale);
      EXPECT_EQ(p.mean[k], solid ? 0.0f : std::max(0.0f, sum)) << k;
      EXPECT_EQ(p.std[k], solid ? 0.0f : std::max(0.0f, y.data[plane + q])) << k;
      if (solid) {
        ++obstacle;
      } else if (sum > 0.0f) {
        // The physics plume itself, in dataset units, to float rounding.
        EXPECT_NEAR(p.mean[k], y.data[q] + c.values[k], 1e-5 * (1.0 + c.values[k])) << k;
        summed += c.values[k] > 1.0;
      } else {
        ++clamped;
      }
    }
  EXPECT_GT(obstacle, 0);
  EXPECT_GT(summed, 20);
  std::printf("residual mean: %d cells in the plume summed, %d clamped, %d in obstacles\n", summed,
              clamped, obstacle);
  // Batches, on two threads, give the bytes of single predictions.
  Vec2 third{0.3, 0.3};
  while (!d.map.is_free(third))
    third.x += 0.2;
  const std::vector<Vec2> sources{d.map.sources[0], d.map.sources[1], third};
  const std::vector<PlumePrediction> batch = model.predict_batch(sources, 2);
  ASSERT_EQ(batch.size(), 3u);
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const PlumePrediction one = model.predict(sources[s]);
    EXPECT_EQ(batch[s].mean, one.mean) << s;
    EXPECT_EQ(batch[s].std, one.std) << s;
  }
  EXPECT_EQ(batch[0].mean, p.mean);
  // A model whose mean is not a residual (the physics plume as an input alone) is the network's.
  test::PhysicalModel plain_file = hybrid_file(d.options);
  plain_file.header["outputs"][0].erase("plus_input");
  const PlumeNetwork plain(network(plain_file), d.map, &d.wind);
  const PlumePrediction q = plain.predict(source);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j), r = static_cast<std::size_t>(j) * model.input_cols() + i;
      EXPECT_EQ(q.mean[k],
                d.map.obstacle_at(g.centre(i, j)) >= 0 ? 0.0f : std::max(0.0f, y.data[r]))
          << k;
    }
}

TEST(HybridPlumeNetwork, RefusesToRunWithoutTheWindAndItsFaultyFiles) {
  const HybridData& d = hybrid_data();
  const auto net = network(hybrid_file(d.options));
  try {
    PlumeNetwork model(net, d.map);
    ADD_FAILURE() << "built without a wind";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("physics plume"), std::string::npos) << e.what();
  }
  // The file's faults never reach PlumeNetwork: the model does not load.
  test::PhysicalModel bad_scale = hybrid_file(d.options);
  bad_scale.header["features"]["channels"][4]["scale"] = -1.0;
  EXPECT_THROW(network(bad_scale), InputError);
  test::PhysicalModel on_std = hybrid_file(d.options);
  on_std.header["outputs"][1]["plus_input"] = "physics_mean";
  EXPECT_THROW(network(on_std), InputError);
  test::PhysicalModel no_channel = test::physical_model({4, 4});
  no_channel.header["outputs"][0]["plus_input"] = "physics_mean";
  EXPECT_THROW(network(no_channel), InputError);
}

}  // namespace
}  // namespace plumekit::surrogate
