#pragma once
// What every plumekit command shares: where the shipped data is, the --json
// switch, and how results and errors are printed.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/geometry.hpp"

namespace plumekit::cli {

// $PLUMEKIT_DATA if set, else the data/ folder of the source tree it was built from.
std::filesystem::path data_dir();
// The map commands use when none is given.
std::filesystem::path default_map();

// Set by each command's --json flag; read when printing results and errors.
struct Output {
  bool json = false;
};
Output& output();

// Adds --json to a command.
void add_json_flag(CLI::App* command);

// "X,Y" in metres; InputError naming `flag` when it is not two finite numbers and a comma.
Vec2 parse_point(const std::string& text, const std::string& flag);
// [x, y]
nlohmann::ordered_json point_json(Vec2 p);

// Prints the summary as JSON on stdout with --json, else the human text.
void report(const nlohmann::ordered_json& summary, const std::string& human);

}  // namespace plumekit::cli
