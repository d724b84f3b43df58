#include "apps/cli.hpp"

#include <cstdlib>
#include <iostream>

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

void report(const nlohmann::ordered_json& summary, const std::string& human) {
  if (output().json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    std::cout << human;
    if (!human.empty() && human.back() != '\n') std::cout << '\n';
  }
}

}  // namespace plumekit::cli
