#pragma once
// Where a map's readings come from: a CSV a user brings from a real robot (x, y, reading[, u, v]
// in the map's frame), or the steps of a `plumekit localize --out` run (run.json). Every value is
// checked; a fault is an InputError naming the file, the line and the column.
#include <filesystem>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "map/map.hpp"
#include "methods/kernel_dmv.hpp"

namespace plumekit::run {

// CSV text: a header naming at least x, y and reading (and u, v together, for DM+V/W), in any
// order and any case, then one sample per line; a UTF-8 byte order mark, blank lines and lines
// starting with '#' are skipped. Positions and winds in the map's frame (converted to the arena's);
// each sample keeps sample_fault's rules. `name` names the text.
std::vector<methods::Sample> parse_samples_csv(std::string_view text, const std::string& name,
                                               const Map& map);
std::vector<methods::Sample> read_samples_csv(const std::filesystem::path& file, const Map& map);

// A localize run.json's content; InputError naming `name` unless it is a JSON object.
nlohmann::json parse_run_json(std::string_view text, const std::string& name);

// The map file a run recorded ("map", written relative to the folder localize ran in, or as a
// bare name when the map lay outside it): that path from the current folder, else from the run's
// folder and each folder above it, else a bare name in one of `shipped` (the shipped map folders).
// InputError naming the recorded map and where it was looked for when none is a file, or when the
// run records no map. `run_file` is the run.json's path.
std::filesystem::path find_run_map(const nlohmann::json& run, const std::filesystem::path& run_file,
                                   const std::vector<std::filesystem::path>& shipped);

// The samples of a localize run: each step's recorded position, value and wind; on a team run
// (a "team" entry) every robot's steps, robot by robot. Each sample keeps sample_fault's rules;
// a fault names `name` and the step ("team.members[1].steps[3]").
std::vector<methods::Sample> run_samples(const nlohmann::json& run, const std::string& name,
                                         const Map& map);
std::vector<methods::Sample> read_run_samples(const std::filesystem::path& file, const Map& map);

}  // namespace plumekit::run
