#pragma once
// What every plumekit command shares: where the shipped data is, the --json
// switch, and how results and errors are printed.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
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

// Adds the flags every command has: --json, and --max-memory SIZE (the
// process's memory limit, core/memory_limit.hpp: "8G", "512M").
void add_common_flags(CLI::App* command);

// Prints a command-line mistake (an unknown flag, a malformed value) to stderr,
// and as the JSON error object with --json; returns exit code 2.
int usage_error(const std::string& message);

// Binds an options field (the name an OptionError carries, "flow.cell") to the
// flag `option` of `command`, so that errors name the flag. Returns `option`.
CLI::Option* bind_field(CLI::App* command, CLI::Option* option, const std::string& field);
// `message` with every options field bound in `command` (or a parent of it)
// replaced by its flag: library messages name fields ("flow.cell"), a
// command's user knows flags ("--cell").
std::string with_flag_names(const CLI::App& command, std::string message);

// "X,Y" in metres; InputError naming `flag` when it is not two finite numbers and a comma.
Vec2 parse_point(const std::string& text, const std::string& flag);
// [x, y]
nlohmann::ordered_json point_json(Vec2 p);

// Prints the summary as JSON on stdout with --json, else the human text.
void report(const nlohmann::ordered_json& summary, const std::string& human);

}  // namespace plumekit::cli
