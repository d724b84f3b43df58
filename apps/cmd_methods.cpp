// `plumekit methods`: the localization methods the registry lists (methods/registry.hpp), for
// the floor (`localize`, `evaluate --method`) and the wind tunnel (`localize tunnel`).
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "methods/registry.hpp"

namespace plumekit::cli {

namespace {

using nlohmann::ordered_json;

ordered_json methods_json() {
  ordered_json floor = ordered_json::array(), tunnel = ordered_json::array();
  for (const methods::MethodSpec& s : methods::method_registry())
    floor.push_back({{"name", s.name},
                     {"description", s.description},
                     {"source", s.source},
                     {"plume_model", s.traits.uses_plume_model},
                     {"teams", s.traits.teams},
                     {"run_ends", methods::to_string(s.traits.ends)}});
  for (const methods::TunnelMethodSpec& s : methods::tunnel_method_registry())
    tunnel.push_back({{"name", s.name},
                      {"description", s.description},
                      {"source", s.source},
                      {"tracker", s.tracker}});
  return {{"ok", true}, {"methods", floor}, {"tunnel_methods", tunnel}};
}

std::string methods_text() {
  std::string text = "localize, evaluate --method:\n";
  for (const methods::MethodSpec& s : methods::method_registry())
    text += "  " + s.name + std::string(s.name.size() < 16 ? 16 - s.name.size() : 1, ' ') +
            s.description + " (" + s.source + ")\n";
  text += "localize tunnel, evaluate tunnel --method:";
  for (const methods::TunnelMethodSpec& s : methods::tunnel_method_registry())
    text += "\n  " + s.name + std::string(s.name.size() < 16 ? 16 - s.name.size() : 1, ' ') +
            s.description + " (" + s.source + ")";
  return text;
}

}  // namespace

void add_methods_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "methods", "List the localization methods, for the floor and the wind tunnel (the registry)");
  static bool markdown = false;
  cmd->add_flag("--markdown", markdown, "Print the table of docs/methods-registry.md");
  add_common_flags(cmd);
  cmd->callback([] {
    if (markdown) {
      std::cout << methods::registry_markdown();
      return;
    }
    report(methods_json(), methods_text());
  });
}

}  // namespace plumekit::cli
