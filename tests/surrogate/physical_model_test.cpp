// Physical-grid model files (surrogate v2, issue 19): the header's features (cell_size, multiple,
// the five channels) are read and each fault refused; the engine runs any multiple of the
// network's size, the same bytes on any thread count and batch, and refuses other sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "physical_model.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

using test::expect_refused;
using test::physical_model;
using test::PhysicalModel;

TEST(PhysicalModelFile, ReadsTheContract) {
  const ModelFile m = physical_model({2, 3, 2, 3}).parse();  // 4 levels: multiple 16
  const FeatureContract& f = m.features;
  EXPECT_TRUE(f.physical());
  EXPECT_TRUE(f.has_wind());
  EXPECT_EQ(f.rows, 0);
  EXPECT_EQ(f.cols, 0);
  EXPECT_EQ(f.width, 0.0);
  EXPECT_EQ(f.height, 0.0);
  EXPECT_DOUBLE_EQ(f.cell_size, 0.2);
  EXPECT_EQ(f.multiple, 16);
  ASSERT_EQ(f.channels.size(), 5u);
  EXPECT_EQ(f.channels[2].name, "wind_u");
  EXPECT_EQ(f.channels[3].unit, "m/s");
  EXPECT_EQ(f.source_channel(), 4);
  EXPECT_EQ(f.source_distance_form, "inverse");
  // The inverse form's floor: half the cell by default, else the header's.
  EXPECT_DOUBLE_EQ(f.source_min_distance, 0.1);
  PhysicalModel given = physical_model({2, 3, 2, 3});
  given.header["features"]["channels"][4]["min_distance"] = 0.05;
  EXPECT_DOUBLE_EQ(given.parse().features.source_min_distance, 0.05);
  // The euclidean form, in metres.
  PhysicalModel metres = physical_model({4, 4}, 3, 1, 0.25);
  metres.header["features"]["channels"][4] = {
      {"name", "source_distance"}, {"unit", "m"}, {"form", "euclidean"}};
  const ModelFile e = metres.parse();
  EXPECT_EQ(e.features.source_distance_form, "euclidean");
  EXPECT_EQ(e.features.multiple, 4);
  EXPECT_DOUBLE_EQ(e.features.source_min_distance, 0.125);
  // A thesis model is not physical.
  EXPECT_FALSE(FeatureContract{}.physical());
  EXPECT_FALSE(FeatureContract{}.has_wind());
}

TEST(PhysicalModelFile, RefusesAFixedGridBesideTheCellSize) {
  PhysicalModel m = physical_model({2, 2});
  m.header["features"]["grid"] = {64, 64};
  expect_refused(m, "features has cell_size (a physical grid) and grid or arena");
  m = physical_model({2, 2});
  m.header["features"]["arena"] = {10.0, 4.0};
  expect_refused(m, "features has cell_size");
}

TEST(PhysicalModelFile, RefusesAMultipleThatIsNotTwoToTheLevels) {
  PhysicalModel m = physical_model({2, 2, 2, 2});
  m.header["features"]["multiple"] = 8;
  expect_refused(m, "features.multiple is 8; a network that pools 4 times needs 16");
  m.header["features"].erase("multiple");
  expect_refused(m, "has no \"multiple\"");
  m = physical_model({2, 2});
  m.header["features"]["multiple"] = 16;
  expect_refused(m, "features.multiple is 16; a network that pools 2 times needs 4");
}

TEST(PhysicalModelFile, RefusesACellSizeOutOfRange) {
  PhysicalModel m = physical_model({2, 2});
  m.header["features"]["cell_size"] = 0.005;
  expect_refused(m, "features.cell_size must be");
  m.header["features"]["cell_size"] = 20.0;
  expect_refused(m, "features.cell_size must be");
  m.header["features"]["cell_size"] = "0.2";
  expect_refused(m, "features.cell_size has the wrong type");
}

TEST(PhysicalModelFile, RefusesChannelsOutOfTheContract) {
  // In the wrong order.
  PhysicalModel m = physical_model({2, 2});
  std::swap(m.header["features"]["channels"][1], m.header["features"]["channels"][2]);
  expect_refused(m,
                 "a physical-grid model's contract is region (label), signed_distance (m), "
                 "wind_u (m/s), wind_v (m/s)");
  m = physical_model({2, 2});
  std::swap(m.header["features"]["channels"][2], m.header["features"]["channels"][3]);
  expect_refused(m, "features.channels[2] is \"wind_v\"");
  // The wind in metres.
  m = physical_model({2, 2});
  m.header["features"]["channels"][2]["unit"] = "m";
  expect_refused(m, "features.channels[2] is \"wind_u\" in \"m\"");
  // The inverse source distance in metres.
  m = physical_model({2, 2});
  m.header["features"]["channels"][4]["unit"] = "m";
  expect_refused(m, "features.channels[4] is \"source_distance\" in \"m\"");
  // An unknown form.
  m = physical_model({2, 2});
  m.header["features"]["channels"][4]["form"] = "log";
  expect_refused(m, "form \"log\" is unknown");
  // The thesis's three channels on a physical grid.
  m = physical_model({2, 2}, 3, 1, 0.2, 1, 3);
  const nlohmann::json three =
      nlohmann::json::array({m.header["features"]["channels"][0],
                             m.header["features"]["channels"][1],
                             {{"name", "source_distance"}, {"unit", "m"}, {"form", "euclidean"}}});
  m.header["features"]["channels"] = three;
  expect_refused(m, "features.channels lists 3 channels; a physical-grid model's contract has 5");
}

TEST(PhysicalModelFile, RefusesAChannelCountOtherThanTheArchitecturesInputs) {
  // A consistent 3-input network whose header lists the five channels.
  const PhysicalModel m = physical_model({2, 2}, 3, 1, 0.2, 1, 3);
  expect_refused(m, "features.channels must list 3 input channels");
  // Five inputs, four channels listed.
  PhysicalModel four = physical_model({2, 2});
  four.header["features"]["channels"].erase(4);
  expect_refused(four, "features.channels must list 5 input channels");
}

TEST(PhysicalModelFile, InletWallsMayBeInteriorNotCeiling) {
  PhysicalModel m = physical_model({2, 2});
  m.header["trained_on"] = {{"inlet_walls", {"left", "interior"}}};
  EXPECT_EQ(m.parse().trained_on.inlet_walls, (std::vector<std::string>{"left", "interior"}));
  m.header["trained_on"]["inlet_walls"] = {"ceiling"};
  expect_refused(m, "trained_on.inlet_walls holds \"ceiling\"");
}

// Random inputs of n samples of rows x cols.
Tensor random_input(int n, int rows, int cols, unsigned seed) {
  Tensor t(n, 5, rows, cols);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 2.0f);
  for (float& v : t.data)
    v = u(rng);
  return t;
}

TEST(PhysicalEngine, RunsAnyMultipleOfItsSizeAndRefusesOthers) {
  const Network net(physical_model({4, 4}).parse(), EngineOptions{1});  // multiple 4
  for (const auto& [rows, cols] :
       std::vector<std::pair<int, int>>{{4, 8}, {12, 4}, {8, 8}, {4, 4}}) {
    const Tensor y = net.predict(random_input(2, rows, cols, 3));
    EXPECT_EQ(y.n, 2);
    EXPECT_EQ(y.c, 2);
    EXPECT_EQ(y.h, rows);
    EXPECT_EQ(y.w, cols);
    EXPECT_EQ(y.data.size(), 2u * 2 * rows * cols);
    EXPECT_TRUE(std::any_of(y.data.begin(), y.data.end(), [](float v) { return v != 0.0f; }));
  }
  for (const auto& [rows, cols] :
       std::vector<std::pair<int, int>>{{6, 8}, {3, 4}, {8, 2}, {0, 4}, {4, 10}}) {
    EXPECT_THROW(net.predict(random_input(1, rows, cols, 4)), std::invalid_argument)
        << rows << "x" << cols;
  }
  // The channel count is still checked.
  EXPECT_THROW(net.predict(Tensor(1, 3, 8, 8)), std::invalid_argument);
  try {
    net.predict(random_input(1, 6, 8, 4));
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("multiples of 4"), std::string::npos) << e.what();
  }
}

TEST(PhysicalEngine, SameBytesOnAnyThreadCountAndBatch) {
  const ModelFile f = physical_model({4, 4}, 3, 2, 0.2, 5).parse();
  const Network one(f, EngineOptions{1}), two(f, EngineOptions{2});
  const Tensor input = random_input(3, 8, 12, 6);
  const Tensor want = one.predict(input);
  EXPECT_EQ(two.predict(input).data, want.data);  // samples shared out
  // Each sample alone (two threads: its decoders side by side) is its row of the batch.
  for (int i = 0; i < 3; ++i) {
    Tensor single(1, 5, 8, 12);
    std::copy(input.sample_data(i), input.sample_data(i) + input.sample(), single.data.begin());
    for (const Network* net : {&one, &two}) {
      const Tensor y = net->predict(single);
      EXPECT_TRUE(std::equal(y.data.begin(), y.data.end(), want.sample_data(i))) << i;
    }
  }
  // Workspaces pooled from a larger input leave a smaller one's result as it was.
  const Tensor small = random_input(1, 4, 8, 7);
  const Tensor before = two.predict(small);
  two.predict(random_input(3, 16, 16, 8));
  one.predict(random_input(1, 16, 16, 8));
  EXPECT_EQ(two.predict(small).data, before.data);
  EXPECT_EQ(one.predict(small).data, before.data);
  EXPECT_EQ(two.predict(input).data, want.data);
}

TEST(PhysicalEngine, FlopsScaleWithTheInputsCells) {
  const Network net(physical_model({4, 4}, 3, 1).parse(), EngineOptions{1});
  const double small = net.flops_per_sample(16, 16), large = net.flops_per_sample(32, 32);
  EXPECT_GT(small, 0.0);
  EXPECT_DOUBLE_EQ(large, 4.0 * small);
  EXPECT_DOUBLE_EQ(net.flops_per_sample(16, 32), 2.0 * small);
  EXPECT_THROW(net.flops_per_sample(), std::logic_error);
  // A thesis model's own grid is the one it counts at.
  const Network odd = Network::load(std::string(PLUMEKIT_TEST_DATA) + "/surrogate/odd.pkcnn");
  EXPECT_DOUBLE_EQ(odd.flops_per_sample(), odd.flops_per_sample(21, 30));
}

}  // namespace
}  // namespace plumekit::surrogate
