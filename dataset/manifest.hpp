#pragma once
// manifest.json: what a dataset holds, exactly: the format version, every
// generator parameter and the seed, the feature and target contract, and each
// shard's sample count and file checksums. It holds no timings and no thread
// count, so the same seed and parameters give the same bytes.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cfd/options.hpp"
#include "core/seed.hpp"
#include "dataset/plume.hpp"
#include "dataset/random_maps.hpp"
#include "dataset/shard.hpp"

namespace plumekit::dataset {

inline constexpr const char* kDatasetFormat = "plumekit-dataset/1";

struct DatasetOptions {
  int maps = 180;     // the thesis's dataset: 180 maps x 100 sources
  int sources = 100;  // per map
  std::uint64_t seed = kDefaultSeed;
  PlumeOptions plume;
  RandomMapOptions map;
  cfd::FlowOptions flow;  // the flow solver's own defaults (docs/options.md)
  // Sources lie at least this far from every obstacle and wall.
  double source_clearance = 0.1;
  // dataset.feature_cell: 0, the thesis's 64 x 64 grid over the arena and three input channels;
  // else the v2 surrogate's physical grid of this nominal cell (m) and five channels, with the
  // wind (features.hpp, physical_grid).
  double feature_cell = 0.0;
  // dataset.physics_input (issue 46): a sixth input channel, physics_mean, before the source
  // distance: plumekit's own physics plume for the source (surrogate::PhysicsFeature with
  // physics_mean_options()), so a hybrid model learns the world's correction to it. Physical
  // grids only.
  bool physics_input = false;
  // dataset.inlet_speeds: when hi > 0, every random map's inlets blow at one speed drawn uniformly
  // from [lo, hi] m/s (rounded to 0.01 m/s) from the map's own stream, instead of maps.inlet_speed.
  double inlet_speed_lo = 0.0, inlet_speed_hi = 0.0;
  // Instead of random maps: these maps, each with its own `sources` (the test
  // maps' ground truth). `map_files` names them in the manifest.
  std::vector<Map> given_maps;
  std::vector<std::string> map_files;
  // Checks every field (OptionError naming it: "dataset.maps", "flow.cell",
  // "plume.release_rate", "maps.families", ...) and each map's flow grid size;
  // dataset_options.cpp. generate_dataset calls it before writing anything.
  void validate() const;
};

// Every parameter that changes the bytes of the dataset.
nlohmann::ordered_json parameters_json(const DatasetOptions& o);
// The feature/target contract, in words and numbers (the thesis grid, or the physical grid of
// `feature_cell` m).
nlohmann::ordered_json contract_json(double feature_cell = 0.0, bool physics_input = false);
// The physics_mean channel's options: the dataset's plume diffusivity and release rate, and the
// filament world's decay, 1 over a filament's lifetime: the physics model ste's estimators use.
cfd::AdvectionDiffusionOptions physics_mean_options(const DatasetOptions& o);
// The random-map draw's inlet speed for map `index` when o.inlet_speed_hi > 0.
double drawn_inlet_speed(const DatasetOptions& o, int index, int redraw);

struct ShardEntry {
  int map_index = 0;
  std::string family;  // the random map's family, or the map file
  int samples = 0;
  Checksums checksums;
};

nlohmann::ordered_json manifest_json(const nlohmann::ordered_json& parameters,
                                     const std::vector<ShardEntry>& shards, int part_k, int part_n);

std::string shard_name(int map_index);  // shard-00007

}  // namespace plumekit::dataset
