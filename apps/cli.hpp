#pragma once
// What every plumekit command shares: where the shipped data is, the --json
// switch, and how results and errors are printed.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/geometry.hpp"
#include "core/option_table.hpp"
#include "world/filament_model.hpp"

namespace plumekit::cli {

// $PLUMEKIT_DATA if set, else the data/ folder of the source tree it was built from.
std::filesystem::path data_dir();
// The map commands use when none is given.
std::filesystem::path default_map();
// The default plume model (surrogate::default_model, the hybrid) in this program's data folder.
std::filesystem::path shipped_cnn();
// --cnn's help: a file or a shipped model's name, each named with what it is.
std::string cnn_help();
// Makes the --cnn option `cnn` take a shipped model's name ("thesis") as well as a file.
void resolve_cnn_names(CLI::Option* cnn);
// A fixed-grid surrogate's refusal of a map's size (surrogate::MapSizeError's message) with what
// to type instead: --cnn hybrid, and with `physics` also --plume-model physics.
std::string with_map_size_advice(const std::string& message, bool physics);

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
// Binds `field` to the words `label` in messages, where one flag sets several fields ("--tunnel's
// height" for tunnel.height): a message then says which part of the flag is wrong.
void bind_field_label(CLI::App* command, const std::string& field, const std::string& label);
// `message` with every options field bound in `command` (or a parent of it)
// replaced by its flag: library messages name fields ("flow.cell"), a
// command's user knows flags ("--cell").
std::string with_flag_names(const CLI::App& command, std::string message);

// Adds the flag of one options-table entry (core/option_table.hpp) to
// `command`, bound to its field in `options` (which must outlive the parse):
// a number or a name takes a value and --help shows the struct's default (an
// optional number's unset text ends its help); a
// bool that is false by default is a switch, one that is true takes true/false.
template <class T>
CLI::Option* add_table_flag(CLI::App* command, T& options, const OptionEntry<T>& e) {
  CLI::Option* option = std::visit(
      [&](const auto& field) -> CLI::Option* {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, EnumField<T>>) {
          // Parsed at once by the library's parser: an unknown name is an OptionError.
          return command->add_option_function<std::string>(
              e.flag, [&options, set = field.set](const std::string& v) { set(options, v); },
              e.help);
        } else if constexpr (std::is_same_v<F, OptionalField<T>>) {
          // Unset is a choice made elsewhere, in words: said in the help, not as a value.
          return command->add_option_function<double>(
              e.flag, [&options, f = field.field](double v) { options.*f = v; },
              e.help + " (default: " + default_text(e) + ")");
        } else if constexpr (std::is_same_v<F, bool T::*>) {
          if (!(options.*field)) return command->add_flag(e.flag, options.*field, e.help);
          return command->add_option(e.flag, options.*field, e.help);
        } else {
          return command->add_option(e.flag, options.*field, e.help);
        }
      },
      e.field);
  if (std::holds_alternative<OptionalField<T>>(e.field)) return bind_field(command, option, e.name);
  if (!std::holds_alternative<bool T::*>(e.field) || option->get_expected_min() > 0)
    option->default_str(value_text(e, options));
  return bind_field(command, option, e.name);
}

// Adds the flags of every entry of `table` that has one, or only of the entries
// named in `only` ("flow.cell"), in the table's order.
template <class T>
void add_table_flags(CLI::App* command, T& options, const OptionTable<T>& table,
                     const std::vector<std::string>& only = {}) {
  for (const OptionEntry<T>& e : table.entries) {
    const bool wanted =
        only.empty() ? !e.flag.empty() : std::find(only.begin(), only.end(), e.name) != only.end();
    if (wanted) add_table_flag(command, options, e);
  }
}

// The flags that mean the same on every command (docs/commands.md, "Flags that mean the same on
// every command"). Each binds to a library field, so the --help default is the library's.

// The positional MAP of every command that takes one map (default: the shipped
// map, filled in when `map` is empty).
CLI::Option* add_map_argument(CLI::App* command, std::string& map);
// --seed S (core/seed.hpp: kDefaultSeed unless the field says otherwise).
CLI::Option* add_seed_flag(CLI::App* command, std::uint64_t& seed,
                           const std::string& what = "Seed of everything random");
// --threads,-j N (0: one per core; core/thread_pool.hpp), bound to `field`.
CLI::Option* add_threads_flag(CLI::App* command, int& threads, const std::string& field,
                              const std::string& what = "Worker threads (0: one per core)");

// --world faithful|thesis, then --occlusion on|off and --wind-model
// steady|unsteady (plume.world, plume.occlusion, plume.wind_model;
// docs/world.md, "Worlds"): the preset is applied first, so either flag
// overrides its half of it. For the dataset's plumes and the robot's world alike.
void add_world_options(CLI::App* command, world::FilamentOptions& filament);
// --gas-sensor NAME and --baseline B (sensor.gas, sensor.baseline): a gas
// sensor preset (docs/world.md, "Gas sensors"); `whose` starts the help
// ("The robot's", "The static sensors'").
void add_gas_sensor_options(CLI::App* command, world::GasSensorModel& sensor,
                            const std::string& whose);

// A spelling kept for one release: `old_flag` sets the same value as
// `new_flag` (already added), is hidden from --help, warns on stderr when
// used, and may not be given together with `new_flag`.
void warn_deprecated(const std::string& old_flag, const std::string& new_flag);
// "plumekit: warning: MESSAGE" on stderr, so that stdout holds only the result (and with --json
// only the JSON, where the command also lists its warnings).
void warn(const std::string& message);
template <typename T>
CLI::Option* add_deprecated_alias(CLI::App* command, const std::string& old_flag,
                                  const std::string& new_flag, T& target) {
  const CLI::Option* replacement = command->get_option(new_flag);
  // Checked here rather than with excludes(), which would list the hidden
  // spelling in the new flag's --help line.
  CLI::Option* alias = command->add_option_function<T>(
      old_flag,
      [&target, old_flag, new_flag, replacement](const T& value) {
        if (replacement->count() > 0)
          throw CLI::ValidationError(
              old_flag, "give " + new_flag + " or its old spelling " + old_flag + ", not both");
        warn_deprecated(old_flag, new_flag);
        target = value;
      },
      "Deprecated: use " + new_flag);
  alias->group("");
  return alias;
}

// A start point moved off an obstacle, reported alike by every command that
// moves one (plan, localize): the JSON key "start_moved" {"requested", "used"}
// and one human line.
void add_moved_start(nlohmann::ordered_json& summary, Vec2 requested, Vec2 used);
std::string moved_start_text(Vec2 requested, Vec2 used);

// "X,Y" in metres; InputError naming `flag` when it is not two finite numbers and a comma.
Vec2 parse_point(const std::string& text, const std::string& flag);
// [x, y]
nlohmann::ordered_json point_json(Vec2 p);

// Prints the summary as JSON on stdout with --json, else the human text.
void report(const nlohmann::ordered_json& summary, const std::string& human);

}  // namespace plumekit::cli
