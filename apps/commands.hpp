#pragma once
// Each command group registers its subcommands on the top-level app.
#include <CLI/CLI.hpp>

namespace plumekit::cli {

void add_map_commands(CLI::App& app);
void add_flow_commands(CLI::App& app);
void add_plan_commands(CLI::App& app);
void add_dataset_commands(CLI::App& app);
void add_predict_commands(CLI::App& app);
void add_ste_commands(CLI::App& app);  // localize, evaluate, demo
// `localize tunnel`, `evaluate tunnel` (after add_ste_commands)
void add_tunnel_commands(CLI::App& app);
void add_gdm_commands(CLI::App& app);
// `options --markdown`: the option reference, docs/options.md
void add_options_commands(CLI::App& app);
void add_methods_commands(CLI::App& app);  // the registry
void add_replay_commands(CLI::App& app);   // a recorded run drawn again

}  // namespace plumekit::cli
