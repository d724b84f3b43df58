// plumekit: gas source localization with mobile robots in cluttered maps.
// Exit codes: 0 success, 2 bad input (message on stderr, no output written),
// 1 internal failure.
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"

namespace {

int fail(int code, const std::string& kind, const std::string& message) {
  std::cerr << "plumekit: " << kind << ": " << message << '\n';
  if (plumekit::cli::output().json) {
    nlohmann::ordered_json j{{"ok", false}, {"exit_code", code}, {"error", message}};
    std::cout << j.dump(2) << '\n';
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "plumekit: find gas sources with mobile robots in cluttered maps.\n"
      "Pipeline: map -> flow -> plume datasets -> CNN surrogate -> source term estimation."};
  app.set_version_flag("--version", PLUMEKIT_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);
  plumekit::cli::add_map_commands(app);
  plumekit::cli::add_flow_commands(app);
  plumekit::cli::add_plan_commands(app);
  plumekit::cli::add_dataset_commands(app);
  plumekit::cli::add_predict_commands(app);
  plumekit::cli::add_ste_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the usage error
    return 2;
  } catch (const plumekit::InputError& e) {
    return fail(2, "error", e.what());
  } catch (const std::exception& e) {
    return fail(1, "internal error", e.what());
  }
  return 0;
}
