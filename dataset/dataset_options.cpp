// DatasetOptions::validate (declared in manifest.hpp, where the struct lives).
#include "cfd/grid_check.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "dataset/manifest.hpp"

namespace plumekit::dataset {

void DatasetOptions::validate() const {
  if (given_maps.empty()) {
    check_count("dataset.maps", maps, 1, 1'000'000, "the thesis's dataset has 180");
    check_count("dataset.sources", sources, 1, 1'000'000, "the thesis's dataset has 100 per map");
    map.validate();
  }
  if (given_maps.size() != map_files.size())
    throw std::logic_error("DatasetOptions: given_maps and map_files differ in length");
  check_non_negative("dataset.source_clearance", source_clearance, 10.0, "m",
                     "the default is 0.1 m");
  flow.validate();
  plume.validate();
  // Each map's flow grid (cell count and memory) before any is solved: a
  // random map's arena is maps.width x maps.height.
  if (given_maps.empty()) {
    cfd::check_grid_size(default_arena(map.width, map.height), flow);
  } else {
    for (std::size_t k = 0; k < given_maps.size(); ++k) {
      if (given_maps[k].sources.empty())
        throw InputError(map_files[k] + ": the map has no sources; a dataset needs them");
      try {
        cfd::check_grid_size(given_maps[k], flow);
      } catch (const OptionError& e) {
        throw OptionError(e.field(), e.message() + " (map " + map_files[k] + ")");
      }
    }
  }
}

}  // namespace plumekit::dataset
