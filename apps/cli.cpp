#include "apps/cli.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/seed.hpp"
#include "core/thread_pool.hpp"
#include "surrogate/shipped_models.hpp"

namespace plumekit::cli {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PLUMEKIT_DATA"); env && *env) return env;
  return PLUMEKIT_DATA_DIR;
}

std::filesystem::path default_map() {
  return data_dir() / "maps" / "cluttered-1.json";
}

std::filesystem::path shipped_cnn() {
  return surrogate::default_model(data_dir());
}

std::string cnn_help() {
  std::string help = "CNN model: a plumekit-cnn file, or a shipped model's name (docs/data.md): ";
  for (const surrogate::ShippedModel& m : surrogate::shipped_models())
    help += std::string(m.name) + " (" + m.what + "), ";
  return help.substr(0, help.size() - 2);
}

void resolve_cnn_names(CLI::Option* cnn) {
  // --help shows the name; the field holds the file the name stands for.
  if (cnn->get_default_str() == shipped_cnn().string()) cnn->default_str("hybrid");
  cnn->transform(
      [](std::string text) { return surrogate::resolve_model(text, data_dir()).string(); }, "",
      "shipped model");
}

std::string with_map_size_advice(const std::string& message, bool physics) {
  return message + ". For a map of any size, use the default model (--cnn hybrid)" +
         (physics ? ", or the physics plume model: --plume-model physics" : "");
}

Output& output() {
  static Output out;
  return out;
}

void add_common_flags(CLI::App* command) {
  command->add_flag("--json", output().json, "Print a machine-readable JSON summary on stdout");
  bind_field(command,
             command->add_option_function<std::string>(
                 "--max-memory",
                 [](const std::string& size) {
                   set_memory_limit(parse_memory_size(size, "memory.limit"));
                 },
                 "Refuse work whose memory estimate exceeds SIZE (\"8G\", \"512M\"; default: "
                 "half the machine's memory, or $PLUMEKIT_MAX_MEMORY)"),
             "memory.limit");
}

int usage_error(const std::string& message) {
  std::cerr << "plumekit: usage error: " << message << "\nRun with --help for more information.\n";
  if (output().json) {
    nlohmann::ordered_json j{{"ok", false}, {"exit_code", 2}, {"error", message}};
    std::cout << j.dump(2) << '\n';
  }
  return 2;
}

namespace {
std::map<const CLI::App*, std::map<std::string, std::string>>& bound_fields() {
  static std::map<const CLI::App*, std::map<std::string, std::string>> fields;
  return fields;
}
}  // namespace

CLI::Option* bind_field(CLI::App* command, CLI::Option* option, const std::string& field) {
  bound_fields()[command][field] = option->get_name();
  return option;
}

void bind_field_label(CLI::App* command, const std::string& field, const std::string& label) {
  bound_fields()[command][field] = label;
}

namespace {

bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Whether `length` characters at `at` are a whole field name, not part of a longer one
// ("pf.beta" in "apf.beta_m"); a sentence's full stop may follow it.
bool whole_name(const std::string& text, std::size_t at, std::size_t length) {
  if (at > 0 && (name_char(text[at - 1]) || text[at - 1] == '.')) return false;
  const std::size_t end = at + length;
  if (end < text.size() && name_char(text[end])) return false;
  return !(end + 1 < text.size() && text[end] == '.' && name_char(text[end + 1]));
}

}  // namespace

std::string with_flag_names(const CLI::App& command, std::string message) {
  std::map<std::string, std::string> fields;  // the nearest binding wins
  for (const CLI::App* app = &command; app; app = app->get_parent())
    if (const auto f = bound_fields().find(app); f != bound_fields().end())
      fields.insert(f->second.begin(), f->second.end());
  // Longest first, so that no field is replaced inside a longer one.
  std::vector<std::pair<std::string, std::string>> order(fields.begin(), fields.end());
  std::sort(order.begin(), order.end(),
            [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
  for (const auto& [field, flag] : order)
    for (std::size_t at = message.find(field); at != std::string::npos;) {
      if (!whole_name(message, at, field.size())) {
        at = message.find(field, at + 1);
        continue;
      }
      message.replace(at, field.size(), flag);
      at = message.find(field, at + flag.size());
    }
  return message;
}

CLI::Option* add_map_argument(CLI::App* command, std::string& map) {
  if (map.empty()) map = default_map().string();
  return command->add_option("MAP", map, "Map file (plumekit-map JSON, format 1 or 2)")
      ->capture_default_str();
}

CLI::Option* add_seed_flag(CLI::App* command, std::uint64_t& seed, const std::string& what) {
  return command->add_option("--seed", seed, what)->capture_default_str();
}

CLI::Option* add_threads_flag(CLI::App* command, int& threads, const std::string& field,
                              const std::string& what) {
  return bind_field(command, command->add_option("--threads,-j", threads, what), field)
      ->capture_default_str();
}

void warn_deprecated(const std::string& old_flag, const std::string& new_flag) {
  std::cerr << "plumekit: warning: " << old_flag
            << " is deprecated and goes in the next release; use " << new_flag << '\n';
}

void warn(const std::string& message) {
  std::cerr << "plumekit: warning: " << message << '\n';
}

void add_moved_start(nlohmann::ordered_json& summary, Vec2 requested, Vec2 used) {
  summary["start_moved"] = {{"requested", point_json(requested)}, {"used", point_json(used)}};
}

std::string moved_start_text(Vec2 requested, Vec2 used) {
  std::ostringstream s;
  s << "start moved from (" << requested.x << ", " << requested.y << ") to (" << used.x << ", "
    << used.y << "): closer than the margin to an obstacle or wall";
  return s.str();
}

Vec2 parse_point(const std::string& text, const std::string& flag) {
  std::istringstream in(text);
  Vec2 p;
  char comma = 0;
  if (!(in >> p.x >> comma >> p.y) || comma != ',' || !(in >> std::ws).eof() || !is_finite(p))
    throw InputError(flag + ": expected a point X,Y in metres (e.g. 1.5,2), got '" + text + "'");
  return p;
}

nlohmann::ordered_json point_json(Vec2 p) {
  return nlohmann::ordered_json::array({p.x, p.y});
}

void report(const nlohmann::ordered_json& summary, const std::string& human) {
  if (output().json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    std::cout << human;
    if (!human.empty() && human.back() != '\n') std::cout << '\n';
  }
}

void add_gas_sensor_options(CLI::App* command, world::GasSensorModel& sensor,
                            const std::string& whose) {
  bind_field(command,
             command
                 ->add_option_function<std::string>(
                     "--gas-sensor",
                     [&sensor](const std::string& name) {
                       const double baseline = sensor.baseline;
                       sensor = world::gas_sensor_preset(name);
                       sensor.baseline = baseline;
                     },
                     whose + " gas sensor: ideal (reads the concentration), catalytic, "
                             "electrochemical, infrared (seed 000, Table 4.1) or mox-fast (seed "
                             "004's MiCS-5521); docs/world.md, \"Gas sensors\"")
                 ->default_str(sensor.name),
             "sensor.gas");
  bind_field(command,
             command->add_option("--baseline", sensor.baseline,
                                 "Gas sensor baseline added to every reading, concentration units"),
             "sensor.baseline")
      ->capture_default_str();
}

namespace {

void add_occlusion_option(CLI::App* command, bool& occlusion) {
  bind_field(command,
             command
                 ->add_option("--occlusion", occlusion,
                              "Filament plume: gas stops at walls (a filament counts at a sensor "
                              "only with a line of sight), on or off")
                 ->type_name("on|off")
                 ->default_str(occlusion ? "on" : "off"),
             "plume.occlusion");
}

void add_wind_model_option(CLI::App* command, bool& unsteady) {
  bind_field(
      command,
      command
          ->add_option_function<std::string>(
              "--wind-model",
              [&unsteady](const std::string& name) {
                if (name != "steady" && name != "unsteady")
                  throw OptionError("plume.wind_model",
                                    "unknown wind model '" + name + "'; use steady or unsteady");
                unsteady = name == "unsteady";
              },
              "Filament plume's wind: steady (the flow plus a uniform meander, the thesis's) or "
              "unsteady (a meandering field that fades at walls; docs/world.md, "
              "\"Unsteady wind\")")
          ->type_name("steady|unsteady")
          ->default_str(unsteady ? "unsteady" : "steady"),
      "plume.wind_model");
}

}  // namespace

// CLI11 runs the callbacks in the order the options were added, so the preset
// comes first and --occlusion or --wind-model, when given, override it.
void add_world_options(CLI::App* command, world::FilamentOptions& filament) {
  const bool faithful = filament.occlusion && filament.unsteady_wind,
             thesis = !filament.occlusion && !filament.unsteady_wind;
  bind_field(
      command,
      command
          ->add_option_function<std::string>(
              "--world", [&filament](const std::string& name) { world::set_world(filament, name); },
              "Filament world preset: faithful (--occlusion on --wind-model unsteady), "
              "thesis (--occlusion off --wind-model steady, the thesis-style world of the "
              "thesis's figures), or neumann (seed 000's filaments in a laminar wind, from a "
              "0.2 m source disc, for its 32 x 8 m tunnel: data/seeds/); either flag "
              "overrides its half. Each with -v1 (faithful-v1): the same world computed as "
              "before issue 45, bit for bit, to reproduce earlier results (docs/world.md, "
              "\"Worlds\")")
          ->type_name("faithful|thesis|neumann[-v1]")
          ->default_str(std::string(faithful ? "faithful"
                                    : thesis ? "thesis"
                                             : "neither") +
                        (filament.engine == world::PlumeEngine::V1 ? "-v1" : "")),
      "plume.world");
  add_occlusion_option(command, filament.occlusion);
  add_wind_model_option(command, filament.unsteady_wind);
}

}  // namespace plumekit::cli
