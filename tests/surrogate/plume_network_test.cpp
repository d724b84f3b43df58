// PlumeNetwork: its features are the dataset's, bit for bit; batches equal single predictions;
// point values are bilinear between cell centres and 0 inside obstacles; bad sources and models
// whose feature contract does not fit the map are refused.
#include "surrogate/plume_network.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/npy.hpp"
#include "dataset/generator.hpp"
#include "map/map_json.hpp"

namespace plumekit::surrogate {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = PLUMEKIT_TEST_DATA;
const fs::path kMap = fs::path(PLUMEKIT_DATA_DIR) / "maps" / "cluttered-1.json";

std::shared_ptr<const Network> real_network(int threads = 1) {
  return std::make_shared<const Network>(
      Network::load(kTestData / "surrogate" / "real.pkcnn", EngineOptions{threads}));
}

// Free points of `map` on a coarse lattice, some of them near obstacles.
std::vector<Vec2> free_points(const Map& map, int want) {
  std::vector<Vec2> out;
  for (int k = 0; static_cast<int>(out.size()) < want && k < 1000; ++k) {
    const Vec2 p{0.1 + std::fmod(k * 1.37, map.width - 0.2),
                 0.1 + std::fmod(k * 0.71, map.height - 0.2)};
    if (map.is_free(p)) out.push_back(p);
  }
  return out;
}

// A point inside obstacle k (its polygons need not be convex).
Vec2 inside_obstacle(const Map& map, int k) {
  for (double y = 0.025; y < map.height; y += 0.05)
    for (double x = 0.025; x < map.width; x += 0.05)
      if (map.obstacle_at({x, y}) == k) return {x, y};
  ADD_FAILURE() << "no point inside obstacle " << k;
  return {0, 0};
}

TEST(PlumeNetwork, FeaturesAreTheDatasets) {
  const fs::path dir =
      fs::temp_directory_path() / ("plumekit-plume-model-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  dataset::DatasetOptions o;
  o.maps = 1;
  o.sources = 2;
  o.seed = 7;
  o.flow.cell = 0.1;  // coarse flow and short plumes: only the inputs are compared
  o.flow.convection = cfd::Convection::Upwind;
  o.plume.filament.record_s = 1.0;
  o.plume.filament.max_spinup = 8.0;
  dataset::generate_dataset(dir, o, dataset::RunOptions{});

  fs::path shard;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename() == "inputs.npy") shard = e.path().parent_path();
  ASSERT_FALSE(shard.empty());
  const NpyArray inputs = read_npy(shard / "inputs.npy");
  const NpyArray sources = read_npy(shard / "sources.npy");
  ASSERT_EQ(inputs.shape, (std::vector<std::size_t>{2, 3, 64, 64}));
  const Map map = read_map(dir / "maps" / "map-00000.json");

  const PlumeNetwork model(real_network(), map);
  EXPECT_EQ(model.grid().nx, 64);
  EXPECT_EQ(model.grid().width, map.width);
  const std::size_t n = 3 * 64 * 64;
  for (int s = 0; s < 2; ++s) {
    // The dataset stores sources as float32; the features were computed from the double source.
    const Vec2 src{map.sources[s].x, map.sources[s].y};
    EXPECT_FLOAT_EQ(static_cast<float>(src.x), static_cast<float>(sources.values[2 * s]));
    const std::vector<float> x = model.features(src);
    ASSERT_EQ(x.size(), n);
    std::size_t differ = 0;
    for (std::size_t k = 0; k < n; ++k)
      differ += x[k] != static_cast<float>(inputs.values[s * n + k]);
    EXPECT_EQ(differ, 0u) << "sample " << s;
  }
  fs::remove_all(dir);
}

TEST(PlumeNetwork, BatchEqualsSingleAndNetwork) {
  const Map map = read_map(kMap);
  const auto net = real_network(2);
  const PlumeNetwork model(net, map);
  const std::vector<Vec2> src = free_points(map, 5);
  ASSERT_EQ(src.size(), 5u);
  const std::vector<PlumePrediction> batch = model.predict_batch(src, 2);
  ASSERT_EQ(batch.size(), 5u);
  for (std::size_t i = 0; i < src.size(); ++i) {
    const PlumePrediction one = model.predict(src[i]);
    EXPECT_EQ(one.mean, batch[i].mean) << i;
    EXPECT_EQ(one.std, batch[i].std) << i;
  }
  // The same numbers as the network on the same features, clamped at 0 and 0 in obstacle cells.
  Tensor x(1, 3, 64, 64);
  const std::vector<float> f = model.features(src[0]);
  std::copy(f.begin(), f.end(), x.data.begin());
  const Tensor y = net->predict(x);
  const std::size_t cells = 64 * 64;
  int obstacle_cells = 0, clamped = 0;
  for (std::size_t k = 0; k < cells; ++k) {
    const bool obstacle = f[k] == 0.0f;
    obstacle_cells += obstacle;
    clamped += !obstacle && y.data[k] < 0;
    EXPECT_EQ(batch[0].mean[k], obstacle ? 0.0f : std::max(0.0f, y.data[k])) << k;
    EXPECT_EQ(batch[0].std[k], obstacle ? 0.0f : std::max(0.0f, y.data[cells + k])) << k;
  }
  EXPECT_GT(obstacle_cells, 0);  // the map has obstacles: the zeroing was exercised
  EXPECT_TRUE(model.predict_batch({}).empty());
}

TEST(PlumeNetwork, PointValuesAreBilinearAndZeroInObstacles) {
  const Map map = read_map(kMap);
  const PlumeNetwork model(real_network(), map);
  const PlumePrediction p = model.predict(free_points(map, 1)[0]);
  const GridShape& g = p.grid;
  // Cell centres give the cell's value; the midpoint of four free centres their average.
  int checked = 0;
  for (int j = 5; j < 60; j += 9)
    for (int i = 3; i < 60; i += 7) {
      const Vec2 c = g.centre(i, j);
      if (!map.is_free(c)) continue;
      EXPECT_NEAR(p.mean_at(c), p.mean[g.index(i, j)], 1e-6);
      EXPECT_NEAR(p.std_at(c), p.std[g.index(i, j)], 1e-6);
      const Vec2 mid = c + 0.5 * Vec2{g.dx(), g.dy()};
      if (!map.is_free(mid)) continue;
      const double avg = (p.mean[g.index(i, j)] + p.mean[g.index(i + 1, j)] +
                          p.mean[g.index(i, j + 1)] + p.mean[g.index(i + 1, j + 1)]) /
                         4.0;
      EXPECT_NEAR(p.mean_at(mid), avg, 1e-6 * std::max(1.0, avg));
      // A quarter of the way along x on the row: linear between two centres.
      const Vec2 q = c + Vec2{0.25 * g.dx(), 0.0};
      EXPECT_NEAR(p.mean_at(q), 0.75 * p.mean[g.index(i, j)] + 0.25 * p.mean[g.index(i + 1, j)],
                  1e-6 * std::max(1.0, double(p.mean[g.index(i, j)])));
      ++checked;
    }
  EXPECT_GT(checked, 10);
  // Inside every obstacle: 0.
  for (int k = 0; k < static_cast<int>(map.obstacles.size()); ++k) {
    const Vec2 c = inside_obstacle(map, k);
    EXPECT_EQ(p.mean_at(c), 0.0);
    EXPECT_EQ(p.std_at(c), 0.0);
  }
  // Non-negative everywhere.
  EXPECT_GE(*std::min_element(p.mean.begin(), p.mean.end()), 0.0f);
  EXPECT_GE(*std::min_element(p.std.begin(), p.std.end()), 0.0f);
}

TEST(PlumeNetwork, RefusesSourcesOutsideFreeSpace) {
  const Map map = read_map(kMap);
  const PlumeNetwork model(real_network(), map);
  const Vec2 inside = inside_obstacle(map, 0);
  EXPECT_THROW(model.predict(inside), InputError);
  EXPECT_THROW(model.predict({-0.1, 1.0}), InputError);
  EXPECT_THROW(model.predict({1.0, map.height + 1}), InputError);
  EXPECT_THROW(model.predict({std::nan(""), 1.0}), InputError);
  // One bad source refuses the whole batch.
  EXPECT_THROW(model.predict_batch({free_points(map, 1)[0], inside}), InputError);
}

TEST(PlumeNetwork, RefusesAModelWhoseContractDoesNotFitTheMap) {
  const Map map = read_map(kMap);
  auto expect_refused = [&](std::shared_ptr<const Network> net, const Map& m, const char* what) {
    try {
      PlumeNetwork model(net, m);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  // The odd golden model: a 21x30 grid over a 7.5 x 5.25 m arena.
  expect_refused(
      std::make_shared<const Network>(Network::load(kTestData / "surrogate" / "odd.pkcnn")), map,
      "21x30");
  // A map of another size than the model's arena.
  expect_refused(real_network(), default_arena(12.0, 4.0), "arena");
  // Contracts the file reader would refuse, built by hand.
  ModelFile f = read_model_file(kTestData / "surrogate" / "real.pkcnn");
  ModelFile renamed = f;
  renamed.features.channels[0].name = "occupancy";
  expect_refused(std::make_shared<const Network>(std::move(renamed)), map, "occupancy");
  ModelFile log_form = f;
  log_form.features.source_distance_form = "log";
  expect_refused(std::make_shared<const Network>(std::move(log_form)), map, "\"log\"");
  ModelFile outputs = f;
  outputs.outputs[0].name = "average";
  expect_refused(std::make_shared<const Network>(std::move(outputs)), map, "\"mean\"");
  // And the real model on its own arena is accepted.
  EXPECT_NO_THROW(PlumeNetwork(real_network(), map));
}

// The real model without its std decoder: a mean-only model (a DeepCFD network of one output)
// predicts the same mean, bit for bit (the decoders are independent), and no std.
TEST(PlumeNetwork, AMeanOnlyModelPredictsTheSameMeanAndNoStd) {
  const Map map = read_map(kMap);
  ModelFile f = read_model_file(kTestData / "surrogate" / "real.pkcnn");
  ModelFile mean_only = f;
  mean_only.architecture.out_channels = 1;
  mean_only.layers.clear(), mean_only.weights.clear(), mean_only.biases.clear();
  for (std::size_t k = 0; k < f.layers.size(); ++k) {
    if (f.layers[k].name.rfind("decoder.1.", 0) == 0) continue;
    mean_only.layers.push_back(f.layers[k]);
    mean_only.weights.push_back(f.weights[k]);
    mean_only.biases.push_back(f.biases[k]);
  }
  mean_only.outputs.resize(1);
  const PlumeNetwork both(std::make_shared<const Network>(std::move(f)), map);
  const PlumeNetwork mean(std::make_shared<const Network>(std::move(mean_only)), map);
  EXPECT_TRUE(both.has_std());
  EXPECT_FALSE(mean.has_std());
  for (Vec2 s : free_points(map, 3)) {
    const PlumePrediction a = both.predict(s), b = mean.predict(s);
    EXPECT_EQ(a.mean, b.mean);
    EXPECT_TRUE(b.std.empty());
    EXPECT_EQ(b.std_at(s), 0.0);
    EXPECT_EQ(a.std.size(), a.mean.size());
  }
}

// The inverse source channel (the thesis's code, DeepCFD-style inputs): 1 / max(d, min_distance).
TEST(PlumeNetwork, TheInverseSourceChannelIsOneOverTheDistance) {
  const Map map = read_map(kMap);
  ModelFile f = read_model_file(kTestData / "surrogate" / "real.pkcnn");
  ModelFile inverse = f;
  inverse.features.source_distance_form = "inverse";
  inverse.features.channels[2].unit = "1/m";
  inverse.features.source_min_distance = 0.05;
  const PlumeNetwork euclidean(std::make_shared<const Network>(std::move(f)), map);
  const PlumeNetwork inv(std::make_shared<const Network>(std::move(inverse)), map);
  const Vec2 s = free_points(map, 1).front();
  const std::vector<float> a = euclidean.features(s), b = inv.features(s);
  const std::size_t cells = euclidean.grid().size();
  ASSERT_EQ(a.size(), 3 * cells);
  for (std::size_t k = 0; k < 2 * cells; ++k)
    ASSERT_EQ(a[k], b[k]);  // the map's channels are untouched
  double nearest = 1e9;
  for (std::size_t k = 2 * cells; k < 3 * cells; ++k) {
    EXPECT_FLOAT_EQ(b[k], static_cast<float>(1.0 / std::max<double>(a[k], 0.05)));
    nearest = std::min<double>(nearest, a[k]);
  }
  EXPECT_LT(nearest, 0.1);  // the source's own cell is near, so the floor matters there
}

// A map outside what the model was trained on is warned about, one sentence per reason.
TEST(PlumeNetwork, WarnsOfMapsOutsideWhatTheModelWasTrainedOn) {
  TrainingRanges t;
  t.map_width = ValueRange{10.0, 10.0};
  t.openings = ValueRange{2.0, 2.0};
  t.inlet_speed = ValueRange{0.5, 1.5};
  t.inlet_walls = {"left"};
  const Map thesis = default_arena();  // 10 x 4 m, inlet on the left at 1 m/s, outlet right
  EXPECT_TRUE(training_warnings(t, thesis).empty());
  EXPECT_TRUE(training_warnings(TrainingRanges{}, default_arena(20.0, 20.0)).empty());
  Map top = thesis;
  top.openings[0] = wall_opening(top, Side::Top, 0.0, 10.0, OpeningKind::Inlet, 3.0);
  const std::vector<std::string> w = training_warnings(t, top);
  ASSERT_EQ(w.size(), 2u) << (w.empty() ? "" : w[0]);
  EXPECT_NE(w[0].find("blows at 3 m/s; the model was trained on 0.5-1.5 m/s"), std::string::npos)
      << w[0];
  EXPECT_NE(w[1].find("on the top wall; the model was trained with inlets on the left wall"),
            std::string::npos)
      << w[1];
  // Positions are in the map's frame, as in every other message.
  Map framed = top;
  framed.frame.origin = {100.0, -50.0};
  const std::vector<std::string> fw = training_warnings(t, framed);
  ASSERT_EQ(fw.size(), 2u);
  EXPECT_EQ(fw[0].rfind("the inlet at (100, -46) blows at 3 m/s", 0), 0u) << fw[0];
  const std::vector<std::string> wide = training_warnings(t, default_arena(12.0, 4.0));
  ASSERT_EQ(wide.size(), 1u);
  EXPECT_NE(wide[0].find("the map is 12 x 4 m; the model was trained on maps 10-10 m wide"),
            std::string::npos)
      << wide[0];
  // PlumeNetwork says them for its map.
  ModelFile f = read_model_file(kTestData / "surrogate" / "real.pkcnn");
  f.trained_on = t;
  const Map cluttered = read_map(kMap);
  const PlumeNetwork net(std::make_shared<const Network>(std::move(f)), cluttered);
  EXPECT_EQ(net.warnings(), training_warnings(t, cluttered));
}

}  // namespace
}  // namespace plumekit::surrogate
