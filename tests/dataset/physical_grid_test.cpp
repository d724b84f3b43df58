// Datasets on a physical grid with the wind (surrogate v2, issue 19; dataset.feature_cell) and
// drawn inlet speeds (dataset.inlet_speeds): each map's own grid of nominal cells, five input
// channels whose wind is the map's cached steady flow, the manifest saying so; inlet speeds from
// their own stream, the maps' shapes those of the same seed without them; bad values refused; a
// dataset that uses neither keeps the parameters it had before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cfd/flow_policy.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/generator.hpp"
#include "dataset/random_maps.hpp"
#include "dataset/wind_cache.hpp"
#include "map/map_json.hpp"
#include "support/small_map.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("plumekit-physical-grid-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(p);
  return p;
}

TEST(PhysicalGrid, NominalCellsOverTheWholeMap) {
  Map m = default_arena(10.0, 4.0);
  GridShape g = surrogate::physical_grid(m, 0.2);
  EXPECT_EQ(g.nx, 50);
  EXPECT_EQ(g.ny, 20);
  EXPECT_EQ(g.width, 10.0);
  EXPECT_EQ(g.height, 4.0);
  EXPECT_DOUBLE_EQ(g.dx(), 0.2);
  EXPECT_DOUBLE_EQ(g.dy(), 0.2);
  // Halves round away from zero (std::lround): 32.5 -> 33, 22.5 -> 23 (not to even).
  m = default_arena(6.5, 4.5);
  g = surrogate::physical_grid(m, 0.2);
  EXPECT_EQ(g.nx, 33);
  EXPECT_EQ(g.ny, 23);
  // The cells cover the whole map: the last cell ends on its far side.
  EXPECT_DOUBLE_EQ(g.nx * g.dx(), 6.5);
  EXPECT_DOUBLE_EQ(g.centre(g.nx - 1, g.ny - 1).x + 0.5 * g.dx(), 6.5);
  EXPECT_DOUBLE_EQ(g.centre(g.nx - 1, g.ny - 1).y + 0.5 * g.dy(), 4.5);
  // W / cell in floating point: 6.1 / 0.2 is 30.499999999999996 and 4.3 / 0.2 21.499999999999996,
  // so 30 x 21 (not the 31 x 22 of exact decimals), as the flow's GridShape::with_cell rounds.
  m = default_arena(6.1, 4.3);
  g = surrogate::physical_grid(m, 0.2);
  EXPECT_EQ(g.nx, 30);
  EXPECT_EQ(g.ny, 21);
  const GridShape w = GridShape::with_cell(6.1, 4.3, 0.2);
  EXPECT_EQ(g.nx, w.nx);
  EXPECT_EQ(g.ny, w.ny);
  EXPECT_DOUBLE_EQ(g.nx * g.dx(), 6.1);
  // A cell within half a cell of nominal; at least one cell a side.
  EXPECT_NEAR(g.dx(), 0.2, 0.1 / g.nx + 1e-12);
  m = default_arena(0.05, 3.0);
  g = surrogate::physical_grid(m, 0.2);
  EXPECT_EQ(g.nx, 1);
  EXPECT_EQ(g.ny, 15);
  // The dataset's grid: the thesis's 64 x 64 at feature_cell 0, else the physical one.
  m = default_arena(6.5, 4.5);
  EXPECT_EQ(surrogate::sample_grid(m, 0.0).nx, 64);
  EXPECT_EQ(surrogate::sample_grid(m, 0.0).ny, 64);
  EXPECT_EQ(surrogate::sample_grid(m, 0.2).nx, 33);
  EXPECT_EQ(surrogate::input_channels(0.0), 3);
  EXPECT_EQ(surrogate::input_channels(0.2), 5);
}

TEST(PhysicalGrid, WindFeaturesAreTheWindAtTheCellCentres) {
  Map m = default_arena(3.0, 1.5);
  m.name = "small";
  // Its edges on no feature cell's centre (a centre on an edge is the obstacle's by the region
  // label, but its flow cell may be free); every flow cell holding an inside centre is solid.
  m.obstacles = {{{0.95, 0.0}, {1.45, 0.0}, {1.45, 0.9}, {0.95, 0.9}}};
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  const cfd::WindField wind = cfd::solve_wind(m, fo).flow.wind;
  const GridShape g =
      surrogate::physical_grid(m, 0.2);  // 15 x 8 (7.5 rounds up): cells of 0.1875 m high
  ASSERT_EQ(g.nx, 15);
  ASSERT_EQ(g.ny, 8);
  const std::vector<float> f = surrogate::wind_features(wind, g);
  ASSERT_EQ(f.size(), 2 * g.size());
  int obstacle = 0, blowing = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      const Vec2 c = g.centre(i, j);
      const Vec2 u = wind.at(c);
      EXPECT_EQ(f[k], static_cast<float>(u.x)) << i << "," << j;
      EXPECT_EQ(f[g.size() + k], static_cast<float>(u.y)) << i << "," << j;
      if (m.obstacle_at(c) >= 0) {
        ++obstacle;
        EXPECT_EQ(f[k], 0.0f) << i << "," << j;
        EXPECT_EQ(f[g.size() + k], 0.0f) << i << "," << j;
      }
      blowing += f[k] > 0.5f;
    }
  EXPECT_GT(obstacle, 0);
  EXPECT_GT(blowing, 10);  // the inlet's 1 m/s, through the free space
  // Above the block the air speeds up: more than the inlet's 1 m/s.
  EXPECT_GT(f[g.index(6, 6)], 1.0f);
}

// Two small random maps of 5 x 3.1 m (25 x 16 cells of 0.2 m: 3.1 / 0.2 is 15.5, rounded up),
// two sources each, the fast advection-diffusion model, coarse flow, drawn inlet speeds.
DatasetOptions physical_options() {
  DatasetOptions o;
  o.maps = 2;
  o.sources = 2;
  o.seed = 21;
  o.map.width = 5.0;
  o.map.height = 3.1;
  o.map.families = {"rectangle", "l-shape"};
  o.flow.cell = 0.1;
  o.flow.convection = cfd::Convection::Upwind;
  o.plume.model = PlumeSimulator::AdvectionDiffusion;
  o.feature_cell = 0.2;
  o.inlet_speed_lo = 0.3;
  o.inlet_speed_hi = 2.0;
  return o;
}

// The float32 values of rows [from, from + count) of an array.
std::vector<float> slice(const NpyArray& a, std::size_t from, std::size_t count) {
  std::vector<float> out(count);
  for (std::size_t k = 0; k < count; ++k)
    out[k] = static_cast<float>(a.values[from + k]);
  return out;
}

TEST(PhysicalGridDataset, ShardsHoldFiveChannelsOnEachMapsGrid) {
  const DatasetOptions o = physical_options();
  const fs::path d = scratch("v2");
  const DatasetSummary s = generate_dataset(d, o, {});
  ASSERT_EQ(s.samples, 4);
  for (int k = 0; k < 2; ++k) {
    const std::string id = k == 0 ? "00000" : "00001";
    const Map map = read_map(d / "maps" / ("map-" + id + ".json"));
    const GridShape g = surrogate::physical_grid(map, 0.2);
    EXPECT_EQ(g.nx, 25);
    EXPECT_EQ(g.ny, 16);
    const fs::path shard = d / "shards" / ("shard-" + id);
    const NpyArray inputs = read_npy(shard / "inputs.npy");
    const NpyArray targets = read_npy(shard / "targets.npy");
    const std::size_t nx = g.nx, ny = g.ny, cells = g.size();
    ASSERT_EQ(inputs.shape, (std::vector<std::size_t>{2, 5, ny, nx}));
    ASSERT_EQ(targets.shape, (std::vector<std::size_t>{2, 2, ny, nx}));
    // Channels 0 and 1 the map's, 2 and 3 its cached wind's, 4 the source's distance.
    const std::vector<float> base = surrogate::map_features(map, g);
    const std::optional<cfd::WindField> wind = read_wind_cache(d / "wind" / ("map-" + id), map);
    ASSERT_TRUE(wind);
    const std::vector<float> w = surrogate::wind_features(*wind, g);
    ASSERT_EQ(map.sources.size(), 2u);
    for (int r = 0; r < 2; ++r) {
      const std::size_t row = static_cast<std::size_t>(r) * 5 * cells;
      EXPECT_EQ(slice(inputs, row, 2 * cells), base) << k << "/" << r;
      EXPECT_EQ(slice(inputs, row + 2 * cells, 2 * cells), w) << k << "/" << r;
      EXPECT_EQ(slice(inputs, row + 4 * cells, cells), surrogate::source_feature(map.sources[r], g))
          << k << "/" << r;
      double peak = 0.0;
      for (std::size_t c = 0; c < cells; ++c)
        peak = std::max(peak, targets.values[r * 2 * cells + c]);
      EXPECT_GT(peak, 0.0) << k << "/" << r;
    }
    // The wind channels are the map's own flow: its inlet's speed comes through.
    double fastest = 0.0;
    for (float v : w)
      fastest = std::max(fastest, static_cast<double>(v));
    EXPECT_GT(fastest, 0.5 * map.openings[0].speed);
  }

  // The manifest: feature_cell and inlet_speeds in the generator, the contract of five channels.
  const Manifest m = read_manifest(d / "manifest.json");
  EXPECT_EQ(m.generator.at("feature_cell"), 0.2);
  EXPECT_EQ(m.generator.at("inlet_speeds"), nlohmann::ordered_json({0.3, 2.0}));
  EXPECT_EQ(feature_cell(m), 0.2);
  const auto manifest = nlohmann::json::parse(read_file(d / "manifest.json"));
  const auto& contract = manifest.at("contract");
  EXPECT_EQ(contract.at("grid").at("cell"), 0.2);
  EXPECT_EQ(contract.at("inputs").at("shape"), "[n, 5, ny, nx]");
  EXPECT_EQ(contract.at("inputs").at("channels").size(), 5u);
  EXPECT_EQ(contract.at("targets").at("shape"), "[n, 2, ny, nx]");
  EXPECT_EQ(nlohmann::json::parse(read_file(d / "parameters.json")).at("feature_cell"), 0.2);

  // The reader: the shard's own grid and five channels; a sample's grids are its map's.
  const ShardArrays a = read_shard(d, m.shards.at(1), 5);
  EXPECT_EQ(a.channels, 5);
  EXPECT_EQ(a.nx, 25);
  EXPECT_EQ(a.ny, 16);
  EXPECT_EQ(a.inputs.size(), 2u * 5 * 25 * 16);
  EXPECT_THROW(read_shard(d, m.shards.at(1), 3), InputError);  // the thesis's 3 channels
  const DatasetSample sample = read_sample(d, 3);              // shard 1, row 1
  EXPECT_EQ(sample.shard.name, "shard-00001");
  EXPECT_EQ(sample.row, 1);
  ASSERT_EQ(sample.inputs.size(), 5u);
  ASSERT_EQ(sample.targets.size(), 2u);
  const std::size_t cells = 25 * 16;
  for (int c = 0; c < 5; ++c) {
    EXPECT_EQ(sample.inputs[c].shape.nx, 25);
    EXPECT_EQ(sample.inputs[c].shape.ny, 16);
    ASSERT_EQ(sample.inputs[c].values.size(), cells);
    for (std::size_t k = 0; k < cells; k += 37)
      EXPECT_EQ(sample.inputs[c].values[k], a.inputs[(5 + c) * cells + k]) << c << " " << k;
  }
  EXPECT_EQ(sample.inputs_sha256.size(), 64u);

  // Each map's inlets blow at its drawn speed; the shapes are those of the same seed without it.
  for (int k = 0; k < 2; ++k) {
    const Map map = read_map(d / "maps" / (k == 0 ? "map-00000.json" : "map-00001.json"));
    const double u = drawn_inlet_speed(o, k, 0);
    int inlets = 0;
    for (const Opening& op : map.openings)
      if (op.is_inlet()) {
        EXPECT_EQ(op.speed, u) << k;
        ++inlets;
      }
    EXPECT_GT(inlets, 0);
    Map plain = random_map(o.map, o.seed, k).map;
    plain.sources = random_sources(plain, o.sources, o.source_clearance, o.seed, k);
    Map same = map;
    for (Opening& op : same.openings)
      if (op.is_inlet()) op.speed = o.map.inlet_speed;
    EXPECT_EQ(map_to_json(same), map_to_json(plain)) << k;
  }
  fs::remove_all(d);
}

TEST(PhysicalGridDataset, ContractSaysThreeOrFiveChannels) {
  const nlohmann::ordered_json v1 = contract_json(), v2 = contract_json(0.2);
  EXPECT_EQ(v1.at("inputs").at("shape"), "[n, 3, 64, 64]");
  EXPECT_EQ(v1.at("inputs").at("channels").size(), 3u);
  EXPECT_EQ(v1.at("grid").at("nx"), 64);
  EXPECT_FALSE(v1.at("grid").contains("cell"));
  EXPECT_EQ(v2.at("inputs").at("shape"), "[n, 5, ny, nx]");
  ASSERT_EQ(v2.at("inputs").at("channels").size(), 5u);
  EXPECT_EQ(v2.at("grid").at("cell"), 0.2);
  const std::string u = v2.at("inputs").at("channels")[2].get<std::string>();
  EXPECT_EQ(u.rfind("2: ", 0), 0u) << u;
  EXPECT_NE(u.find("u in m/s"), std::string::npos) << u;
  EXPECT_EQ(v2.at("inputs").at("channels")[4].get<std::string>().rfind("4: Euclidean", 0), 0u);
  EXPECT_EQ(v2.at("targets").at("shape"), "[n, 2, ny, nx]");
}

TEST(InletSpeeds, DrawnPerMapInTheRangeToACentimetrePerSecond) {
  DatasetOptions o;
  o.seed = 5;
  o.inlet_speed_lo = 0.3;
  o.inlet_speed_hi = 2.0;
  std::set<double> seen;
  for (int i = 0; i < 8; ++i) {
    const double u = drawn_inlet_speed(o, i, 0);
    EXPECT_GE(u, 0.3);
    EXPECT_LE(u, 2.0);
    EXPECT_NEAR(u * 100.0, std::round(u * 100.0), 1e-9) << u;
    EXPECT_EQ(drawn_inlet_speed(o, i, 0), u);  // a function of (seed, map, redraw)
    seen.insert(u);
  }
  EXPECT_GE(seen.size(), 4u);
  // Another seed or a redraw draws again.
  DatasetOptions other = o;
  other.seed = 6;
  int differ = 0;
  for (int i = 0; i < 8; ++i) {
    differ += drawn_inlet_speed(other, i, 0) != drawn_inlet_speed(o, i, 0);
    differ += drawn_inlet_speed(o, i, 1) != drawn_inlet_speed(o, i, 0);
  }
  EXPECT_GT(differ, 8);
  // A range of one speed is that speed.
  o.inlet_speed_lo = o.inlet_speed_hi = 0.75;
  EXPECT_EQ(drawn_inlet_speed(o, 3, 0), 0.75);
}

// generate_dataset must throw OptionError on `field` and leave `out` absent.
void expect_refused(const DatasetOptions& o, const std::string& field, const std::string& part) {
  const fs::path out = scratch("refused");
  try {
    generate_dataset(out, o, {});
    ADD_FAILURE() << field << ": no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), field);
    EXPECT_NE(e.message().find(part), std::string::npos) << e.message();
  }
  EXPECT_FALSE(fs::exists(out)) << field << ": generate_dataset wrote before validating";
  fs::remove_all(out);
}

DatasetOptions tiny() {
  DatasetOptions o;
  o.maps = 1;
  o.sources = 1;
  o.flow.cell = 0.1;
  return o;
}

TEST(PhysicalGridOptions, BadFeatureCellsAndInletSpeedsAreRefused) {
  DatasetOptions o = tiny();
  for (double cell : {0.01, -0.2, 2.5, std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::infinity()}) {
    o.feature_cell = cell;
    expect_refused(o, "dataset.feature_cell", "must be a finite number from 0.02 to 2 m");
  }
  for (double cell : {0.02, 0.2, 2.0}) {
    o.feature_cell = cell;
    EXPECT_NO_THROW(o.validate()) << cell;
  }
  o = tiny();
  o.inlet_speed_lo = 2.0;
  o.inlet_speed_hi = 0.3;
  expect_refused(o, "dataset.inlet_speeds", "LO,HI with 0 < LO <= HI");
  expect_refused(o, "dataset.inlet_speeds", "LO must not exceed HI, got LO 2 and HI 0.3 m/s");
  o.inlet_speed_lo = 0.3;
  o.inlet_speed_hi = 1e6;
  expect_refused(o, "dataset.inlet_speeds", "at most 100 m/s: plumekit's flow is incompressible");
  o.inlet_speed_lo = 0.0;
  o.inlet_speed_hi = 1.0;
  expect_refused(o, "dataset.inlet_speeds", "got 0");
  o.inlet_speed_lo = 0.5;
  o.inlet_speed_hi = 0.0;  // a low speed without a high one
  expect_refused(o, "dataset.inlet_speeds", "got 0");
  o.inlet_speed_lo = 0.5;
  o.inlet_speed_hi = std::numeric_limits<double>::quiet_NaN();
  expect_refused(o, "dataset.inlet_speeds", "got nan");
  o.inlet_speed_hi = 0.5;
  EXPECT_NO_THROW(o.validate());

  // Given maps keep their own inlet speeds.
  const fs::path dir = scratch("given");
  plumekit::test::write_small_map(dir);
  o = tiny();
  use_map_dir(o, dir / "maps");
  ASSERT_EQ(o.given_maps.size(), 1u);
  EXPECT_NO_THROW(o.validate());
  o.inlet_speed_lo = 0.3;
  o.inlet_speed_hi = 2.0;
  expect_refused(o, "dataset.inlet_speeds", "given maps keep their own");
  fs::remove_all(dir);
}

TEST(PhysicalGridOptions, ADatasetWithoutThemKeepsItsParameters) {
  // Neither key unless used, so a dataset made before them resumes with today's parameters.
  const nlohmann::ordered_json plain = parameters_json(DatasetOptions{});
  EXPECT_FALSE(plain.contains("feature_cell"));
  EXPECT_FALSE(plain.contains("inlet_speeds"));
  const fs::path dir = scratch("given-params");
  plumekit::test::write_small_map(dir);
  DatasetOptions given = tiny();
  use_map_dir(given, dir / "maps");
  const nlohmann::ordered_json g = parameters_json(given);
  EXPECT_FALSE(g.contains("feature_cell"));
  EXPECT_FALSE(g.contains("inlet_speeds"));
  fs::remove_all(dir);
  // With them, each is a parameter: a run without them does not resume such a dataset.
  DatasetOptions v2;
  v2.feature_cell = 0.2;
  v2.inlet_speed_lo = 0.3;
  v2.inlet_speed_hi = 2.0;
  const nlohmann::ordered_json p = parameters_json(v2);
  EXPECT_EQ(p.at("feature_cell"), 0.2);
  EXPECT_EQ(p.at("inlet_speeds"), nlohmann::ordered_json({0.3, 2.0}));
  const std::vector<std::string> d = parameter_differences(plain, p);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0], "feature_cell: this run none, the dataset 0.2");
  EXPECT_EQ(d[1], "inlet_speeds: this run none, the dataset [0.3,2.0]");
}

}  // namespace
}  // namespace plumekit::dataset
