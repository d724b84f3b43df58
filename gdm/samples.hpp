#pragma once
// Where a map's readings come from: a CSV a user brings from a real robot (x, y, reading[, u, v]
// in the map's frame), or the steps of a `plumekit localize --out` run (run.json). Every value is
// checked; a fault is an InputError naming the file, the line and the column.
#include <filesystem>
#include <string_view>
#include <vector>

#include "core/map.hpp"
#include "gdm/kernel_dmv.hpp"

namespace plumekit::gdm {

// CSV text: a header naming at least x, y and reading (and u, v together, for DM+V/W), in any
// order, then one sample per line; blank lines and lines starting with '#' are skipped.
// Positions and winds in the map's frame (converted to the arena's). `name` names the text.
std::vector<Sample> parse_samples_csv(std::string_view text, const std::string& name,
                                      const Map& map);
std::vector<Sample> read_samples_csv(const std::filesystem::path& file, const Map& map);

// The samples of a localize run.json: each step's recorded position, value and wind.
std::vector<Sample> read_run_samples(const std::filesystem::path& file, const Map& map);

}  // namespace plumekit::gdm
