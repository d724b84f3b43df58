// PlumeNetwork with a physical-grid model (surrogate v2, issue 19): the map's own grid of the
// model's cell, padded with zeros to the network's multiple; the wind's channels are the dataset's;
// the prediction is the network's output cropped back to the map's cells; a model that takes the
// wind refuses to be built without one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "physical_model.hpp"
#include "surrogate/features.hpp"
#include "surrogate/plume_network.hpp"

namespace plumekit::surrogate {
namespace {

// 3.0 x 1.4 m: 15 x 7 cells of 0.2 m (1.4 / 0.2 is 6.999...: 7), a block on the floor.
Map tiny_map() {
  Map m = default_arena(3.0, 1.4);
  m.name = "tiny";
  m.obstacles = {{{1.2, 0.0}, {1.6, 0.0}, {1.6, 0.8}, {1.2, 0.8}}};
  return m;
}

// Its steady wind on 0.1 m cells, solved once.
const cfd::WindField& tiny_wind() {
  static const cfd::WindField w = model_wind(tiny_map(), 0.1);
  return w;
}

// A uniform wind along +x on an empty arena, built on the MAC faces (no solve).
cfd::WindField uniform_wind(double width, double height, double cell, double speed) {
  const GridShape g = GridShape::with_cell(width, height, cell);
  std::vector<double> fu(static_cast<std::size_t>(g.nx + 1) * g.ny, speed);
  std::vector<double> fv(static_cast<std::size_t>(g.nx) * (g.ny + 1), 0.0);
  return cfd::WindField(g, fu, fv, std::vector<double>(g.size(), 0.0),
                        std::vector<std::uint8_t>(g.size(), 0));
}

std::shared_ptr<const Network> physical_network(std::vector<int> filters, int threads = 1) {
  return std::make_shared<const Network>(test::physical_model(std::move(filters), 3, 1).parse(),
                                         EngineOptions{threads});
}

TEST(PhysicalPlumeNetwork, PadsTheMapsGridWithZerosToTheNetworksMultiple) {
  const Map map = tiny_map();
  const cfd::WindField& wind = tiny_wind();
  const PlumeNetwork model(physical_network({4, 4}), map, &wind);  // multiple 4
  const GridShape g = model.grid();
  const GridShape want = surrogate::physical_grid(map, 0.2);
  EXPECT_EQ(g.nx, 15);
  EXPECT_EQ(g.ny, 7);
  EXPECT_EQ(g.nx, want.nx);
  EXPECT_EQ(g.ny, want.ny);
  EXPECT_EQ(g.width, 3.0);
  EXPECT_EQ(g.height, 1.4);
  EXPECT_EQ(model.input_rows(), 8);
  EXPECT_EQ(model.input_cols(), 16);

  const Vec2 source{2.3, 0.5};
  const std::vector<float> x = model.features(source);
  const int rows = 8, cols = 16;
  const std::size_t plane = rows * cols;
  ASSERT_EQ(x.size(), 5 * plane);
  const std::vector<float> m = surrogate::map_features(map, g);
  const std::vector<float> w = surrogate::wind_features(wind, g);
  const std::vector<float> d = surrogate::source_feature(source, g);
  const double floor = 0.1;  // the inverse form's default: half the model's cell
  bool some_wind = false;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * cols + i;
      if (i >= g.nx || j >= g.ny) {
        for (int c = 0; c < 5; ++c)
          EXPECT_EQ(x[c * plane + p], 0.0f)
              << "padding, channel " << c << " row " << j << " col " << i;
        continue;
      }
      const std::size_t k = g.index(i, j);
      EXPECT_EQ(x[p], m[k]);                         // region
      EXPECT_EQ(x[plane + p], m[g.size() + k]);      // signed distance
      EXPECT_EQ(x[2 * plane + p], w[k]);             // wind u
      EXPECT_EQ(x[3 * plane + p], w[g.size() + k]);  // wind v
      EXPECT_EQ(x[4 * plane + p],                    // 1 / source distance
                static_cast<float>(1.0 / std::max(static_cast<double>(d[k]), floor)));
      some_wind = some_wind || w[k] > 0.5f;
    }
  EXPECT_TRUE(some_wind);  // the wind channels hold the solved flow, not zeros
  // The source's own cell reads 1 / floor: the floor is half the cell, 0.1 m.
  EXPECT_FLOAT_EQ(*std::max_element(x.begin() + 4 * plane, x.end()), 10.0f);
}

TEST(PhysicalPlumeNetwork, PadsToSixteenForFourLevelsAndNotAtAllOnAMultiple) {
  const Map map = tiny_map();
  const PlumeNetwork deep(physical_network({2, 2, 2, 2}), map, &tiny_wind());
  EXPECT_EQ(deep.input_rows(), 16);
  EXPECT_EQ(deep.input_cols(), 16);
  EXPECT_EQ(deep.features({0.5, 0.7}).size(), 5u * 16 * 16);
  // 3.2 x 1.6 m: 16 x 8 cells, already multiples of 4.
  const Map exact = default_arena(3.2, 1.6);
  const cfd::WindField wind = uniform_wind(3.2, 1.6, 0.1, 0.8);
  const PlumeNetwork model(physical_network({4, 4}), exact, &wind);
  EXPECT_EQ(model.grid().nx, 16);
  EXPECT_EQ(model.grid().ny, 8);
  EXPECT_EQ(model.input_rows(), 8);
  EXPECT_EQ(model.input_cols(), 16);
  const std::vector<float> x = model.features({1.0, 0.8});
  ASSERT_EQ(x.size(), 5u * 8 * 16);
  // The uniform wind in every cell's u, none in v.
  for (std::size_t k = 0; k < 8 * 16; ++k) {
    EXPECT_FLOAT_EQ(x[2 * 8 * 16 + k], 0.8f) << k;
    EXPECT_EQ(x[3 * 8 * 16 + k], 0.0f) << k;
  }
}

TEST(PhysicalPlumeNetwork, PredictionIsTheNetworkCroppedToTheMapAndClamped) {
  const Map map = tiny_map();
  const auto net = physical_network({4, 4}, 2);
  const PlumeNetwork model(net, map, &tiny_wind());
  const Vec2 source{2.3, 0.5};
  const PlumePrediction p = model.predict(source);
  const GridShape& g = p.grid;
  EXPECT_EQ(g.nx, 15);
  EXPECT_EQ(g.ny, 7);
  ASSERT_EQ(p.mean.size(), g.size());
  ASSERT_EQ(p.std.size(), g.size());
  EXPECT_TRUE(model.has_std());

  Tensor x(1, 5, 8, 16);
  const std::vector<float> f = model.features(source);
  std::copy(f.begin(), f.end(), x.data.begin());
  const Tensor y = net->predict(x);
  const std::size_t plane = 8 * 16;
  int obstacle_cells = 0, positive = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j), q = static_cast<std::size_t>(j) * 16 + i;
      const bool obstacle = map.obstacle_at(g.centre(i, j)) >= 0;
      EXPECT_EQ(obstacle, f[q] == 0.0f);  // region label 0
      obstacle_cells += obstacle;
      positive += !obstacle && y.data[q] > 0;
      EXPECT_EQ(p.mean[k], obstacle ? 0.0f : std::max(0.0f, y.data[q])) << i << "," << j;
      EXPECT_EQ(p.std[k], obstacle ? 0.0f : std::max(0.0f, y.data[plane + q])) << i << "," << j;
      EXPECT_NEAR(p.mean_at(g.centre(i, j)), p.mean[k], 1e-6);
    }
  EXPECT_GT(obstacle_cells, 0);
  EXPECT_GT(positive, 0);
  // A batch is each source alone.
  const std::vector<Vec2> sources{{0.5, 0.7}, {2.3, 0.5}, {2.6, 1.1}};
  const std::vector<PlumePrediction> batch = model.predict_batch(sources, 2);
  ASSERT_EQ(batch.size(), 3u);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const PlumePrediction one = model.predict(sources[i]);
    EXPECT_EQ(batch[i].mean, one.mean) << i;
    EXPECT_EQ(batch[i].std, one.std) << i;
  }
  EXPECT_EQ(batch[1].mean, p.mean);
  EXPECT_THROW(model.predict({1.4, 0.4}), InputError);  // inside the block
}

TEST(PhysicalPlumeNetwork, TakesTheWindAndRefusesToRunWithoutIt) {
  const Map map = tiny_map();
  const auto net = physical_network({4, 4});
  EXPECT_TRUE(PlumeNetwork::takes_wind(*net));
  try {
    PlumeNetwork model(net, map);
    ADD_FAILURE() << "built without a wind";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wind"), std::string::npos) << e.what();
  }
  // Any map size: the model's grid is the map's.
  const Map large = default_arena(5.0, 2.0);
  const cfd::WindField wind = uniform_wind(5.0, 2.0, 0.1, 1.0);
  const PlumeNetwork model(net, large, &wind);
  EXPECT_EQ(model.grid().nx, 25);
  EXPECT_EQ(model.grid().ny, 10);
  EXPECT_EQ(model.input_cols(), 28);
  EXPECT_EQ(model.input_rows(), 12);
  EXPECT_EQ(model.predict({4.0, 1.0}).mean.size(), 25u * 10);
  // A thesis model takes no wind and still only its own arena.
  const auto thesis = std::make_shared<const Network>(
      Network::load(std::string(PLUMEKIT_TEST_DATA) + "/surrogate/real.pkcnn", EngineOptions{1}));
  EXPECT_FALSE(PlumeNetwork::takes_wind(*thesis));
  try {
    PlumeNetwork model(thesis, default_arena(10.0, 10.0));
    ADD_FAILURE() << "a thesis model took a 10 x 10 m map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("arena"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(PlumeNetwork(thesis, default_arena(10.0, 4.0)));
}

}  // namespace
}  // namespace plumekit::surrogate
