#pragma once
// `plumekit maps random`: a folder of random maps, map-00000.json ..., each with its own random
// sources. Map i is the same whatever the count.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/report.hpp"
#include "core/seed.hpp"
#include "dataset/random_maps.hpp"

namespace plumekit::dataset {

struct MapSetOptions {
  int count = 10;                     // maps.count
  std::uint64_t seed = kDefaultSeed;  // maps.seed
  int sources = 0;                    // maps.sources: random sources stored in each map
  double source_clearance = 0.1;      // m from every obstacle and wall
  RandomMapOptions map;
  // OptionError naming the field ("maps.count", "maps.sources", "maps.width", ...).
  void validate() const;
};

// The maps (validates the options first).
std::vector<RandomMap> random_map_set(const MapSetOptions& options);

// Writes the maps into `dir` as map-00000.json, ...; returns the report naming `out` (the folder
// as the user gave it) and the count of each family.
Report write_map_set(const std::filesystem::path& dir, const std::string& out,
                     const MapSetOptions& options, std::vector<RandomMap>& maps);

}  // namespace plumekit::dataset
