// A hybrid model's data (issue 46, dataset.physics_input): six input channels, the physics plume
// of each source (surrogate::PhysicsFeature) before the source distance. With the world's decay the
// channel is exactly the advection-diffusion simulator's own plume, so a dataset of that simulator
// holds it twice; the manifest names the channels and the physics options; the reader takes six;
// the option is refused on the thesis's grid.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
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
#include "surrogate/features.hpp"

namespace plumekit::dataset {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("plumekit-physics-input-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(p);
  return p;
}

// Two small random maps of 5 x 3 m, two sources each, the advection-diffusion simulator with the
// filament world's decay: its targets are then what the physics channel holds.
DatasetOptions hybrid_options() {
  DatasetOptions o;
  o.maps = 2;
  o.sources = 2;
  o.seed = 7;
  o.map.width = 5.0;
  o.map.height = 3.0;
  o.map.families = {"rectangle", "l-shape"};
  o.flow.cell = 0.1;
  o.flow.convection = cfd::Convection::Upwind;
  o.plume.model = PlumeSimulator::AdvectionDiffusion;
  o.plume.advection_diffusion.decay_rate = 1.0 / o.plume.filament.lifetime_s();
  o.feature_cell = 0.2;
  o.physics_input = true;
  return o;
}

TEST(PhysicsInput, TheChannelIsTheSourcesPhysicsPlumeBeforeTheSourceDistance) {
  const DatasetOptions o = hybrid_options();
  const fs::path d = scratch("six");
  ASSERT_EQ(generate_dataset(d, o, {}).samples, 4);
  for (const std::string id : {"00000", "00001"}) {
    const Map map = read_map(d / "maps" / ("map-" + id + ".json"));
    const GridShape g = surrogate::physical_grid(map, 0.2);
    const std::size_t cells = g.size();
    const NpyArray inputs = read_npy(d / "shards" / ("shard-" + id) / "inputs.npy");
    const NpyArray targets = read_npy(d / "shards" / ("shard-" + id) / "targets.npy");
    ASSERT_EQ(inputs.shape, (std::vector<std::size_t>{2, 6, std::size_t(g.ny), std::size_t(g.nx)}));
    const auto wind = read_wind_cache(d / "wind" / ("map-" + id), map);
    ASSERT_TRUE(wind);
    const surrogate::PhysicsFeature physics(map, *wind, g, physics_mean_options(o));
    for (int r = 0; r < 2; ++r) {
      const Grid<double> c = physics(map.sources[r]);
      const std::size_t row = static_cast<std::size_t>(r) * 6 * cells;
      double peak = 0.0;
      for (std::size_t k = 0; k < cells; ++k) {
        const float channel = static_cast<float>(inputs.values[row + 4 * cells + k]);
        ASSERT_EQ(channel, static_cast<float>(c.values[k])) << id << "/" << r << " cell " << k;
        // The simulator's own plume, to the float: the same operator, source and resampling.
        ASSERT_EQ(channel, static_cast<float>(targets.values[r * 2 * cells + k])) << id << " " << k;
        if (map.obstacle_at(g.centre(k % g.nx, k / g.nx)) >= 0) {
          EXPECT_EQ(channel, 0.0f);
        }
        peak = std::max(peak, c.values[k]);
      }
      EXPECT_GT(peak, 100.0) << id << "/" << r;  // a release of 1000: hundreds near the source
      // The source distance is still the last channel.
      const std::vector<float> dist = surrogate::source_feature(map.sources[r], g);
      for (std::size_t k = 0; k < cells; k += 7)
        EXPECT_EQ(static_cast<float>(inputs.values[row + 5 * cells + k]), dist[k]);
    }
  }
  const Manifest m = read_manifest(d / "manifest.json");
  EXPECT_TRUE(physics_input(m));
  EXPECT_EQ(m.generator.at("physics_mean").at("decay_rate"), 1.0 / 28.0);
  EXPECT_EQ(m.generator.at("physics_mean").at("diffusivity"), 0.05);
  EXPECT_EQ(m.generator.at("physics_mean").at("release_rate"), 1000.0);
  const auto contract = nlohmann::json::parse(read_file(d / "manifest.json")).at("contract");
  EXPECT_EQ(contract.at("inputs").at("shape"), "[n, 6, ny, nx]");
  EXPECT_EQ(contract.at("inputs").at("names"),
            nlohmann::json({"region", "signed_distance", "wind_u", "wind_v", "physics_mean",
                            "source_distance"}));
  EXPECT_EQ(contract.at("inputs").at("channels").size(), 6u);
  EXPECT_EQ(read_shard(d, m.shards.at(0), 6).channels, 6);
  EXPECT_THROW(read_shard(d, m.shards.at(0), 5), InputError);
  EXPECT_EQ(read_sample(d, 1).inputs.size(), 6u);
  fs::remove_all(d);
}

// A point the flow grid leaves no air at (here the middle of a 1 m block, 5 flow cells from free
// space; on a real floor, a nook the flow grid closed) has a physics plume of nothing, not an
// error: a model's candidate source may lie there.
TEST(PhysicsInput, NoAirNoPlume) {
  Map m = default_arena(6.0, 3.0);
  m.obstacles = {{{2.0, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {2.0, 2.0}}};
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  fo.convection = cfd::Convection::Upwind;
  const cfd::WindField wind = cfd::solve_wind(m, fo).flow.wind;
  const GridShape g = surrogate::physical_grid(m, 0.2);
  const surrogate::PhysicsFeature physics(m, wind, g, cfd::AdvectionDiffusionOptions{});
  const Grid<double> none = physics({2.5, 1.5});
  EXPECT_EQ(none.shape.nx, g.nx);
  EXPECT_TRUE(std::all_of(none.values.begin(), none.values.end(), [](double v) { return v == 0; }));
  const Grid<double> some = physics({1.0, 1.5});
  EXPECT_GT(*std::max_element(some.values.begin(), some.values.end()), 100.0);
}

TEST(PhysicsInput, OlderManifestsAndTheOptionsChecks) {
  // Without the option: five channels, the names still written; the thesis grid: three.
  EXPECT_EQ(contract_json(0.2).at("inputs").at("names").size(), 5u);
  EXPECT_EQ(contract_json().at("inputs").at("names").back(), "source_distance");
  EXPECT_EQ(surrogate::input_channels(0.2, true), 6);
  DatasetOptions o = hybrid_options();
  o.feature_cell = 0.0;
  const fs::path out = scratch("refused");
  try {
    generate_dataset(out, o, {});
    ADD_FAILURE() << "no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "dataset.physics_input");
    EXPECT_NE(e.message().find("--feature-cell"), std::string::npos) << e.message();
  }
  EXPECT_FALSE(fs::exists(out));
  // A manifest that claims the channel without a physical grid, or not as a boolean, is refused.
  Manifest m;
  m.generator = {{"physics_input", true}};
  EXPECT_THROW(physics_input(m), InputError);
  m.generator = {{"feature_cell", 0.2}, {"physics_input", "yes"}};
  EXPECT_THROW(physics_input(m), InputError);
  m.generator = {{"feature_cell", 0.2}};
  EXPECT_FALSE(physics_input(m));
}

}  // namespace
}  // namespace plumekit::dataset
