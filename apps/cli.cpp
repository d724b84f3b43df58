#include "apps/cli.hpp"

#include <cstdlib>
#include <iostream>
#include <sstream>

#include "core/error.hpp"

namespace plumekit::cli {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PLUMEKIT_DATA"); env && *env) return env;
  return PLUMEKIT_DATA_DIR;
}

std::filesystem::path default_map() {
  return data_dir() / "maps" / "cluttered-1.json";
}

Output& output() {
  static Output out;
  return out;
}

void add_json_flag(CLI::App* command) {
  command->add_flag("--json", output().json, "Print a machine-readable JSON summary on stdout");
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

}  // namespace plumekit::cli
