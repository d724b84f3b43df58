// plumekit: gas source localization with mobile robots in cluttered maps.
// Exit codes (docs/commands.md, "Exit codes are a contract"): 0 success; 2 anything the user can
// fix (the message names the path or flag, and nothing was written); 1 only a plumekit bug. With
// --json every failure also prints the JSON error object.
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/temporary_files.hpp"

namespace {

int fail(int code, const std::string& kind, const std::string& message) {
  std::cerr << "plumekit: " << kind << ": " << message << '\n';
  if (plumekit::cli::output().json) {
    nlohmann::ordered_json j{{"ok", false}, {"exit_code", code}, {"error", message}};
    std::cout << j.dump(2) << '\n';
  }
  return code;
}

std::vector<std::string> subcommand_names(CLI::App* app) {
  std::vector<std::string> names;
  for (const CLI::App* s : app->get_subcommands([](CLI::App*) { return true; }))
    names.push_back(s->get_name());
  return names;
}

// "plumekit frobnicate": CLI11 says only that an argument was not expected.
// Name the unknown command and list the ones there are.
std::string unknown_command(CLI::App& app, int argc, char** argv) {
  CLI::App* at = &app;
  std::string path = "plumekit";
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') break;
    const std::vector<std::string> names = subcommand_names(at);
    if (names.empty()) break;
    CLI::App* next = nullptr;
    for (CLI::App* s : at->get_subcommands([](CLI::App*) { return true; }))
      if (s->get_name() == word) next = s;
    if (!next) {
      if (at->get_require_subcommand_min() == 0) break;
      std::string list;
      for (const std::string& n : names)
        list += (list.empty() ? "" : ", ") + n;
      return "'" + word + "' is not a command of " + path + " (commands: " + list + "; see " +
             path + " --help)";
    }
    at = next;
    path += " " + word;
  }
  return "";
}

// The deepest subcommand the command line selected.
const CLI::App* selected(const CLI::App& app) {
  const CLI::App* at = &app;
  for (std::vector<CLI::App*> subs = at->get_subcommands(); !subs.empty();
       subs = at->get_subcommands())
    at = subs.front();
  return at;
}

}  // namespace

int main(int argc, char** argv) {
  plumekit::install_interrupt_cleanup();
  for (int i = 1; i < argc; ++i)  // so that a parse error is reported as JSON too
    if (std::strcmp(argv[i], "--json") == 0) plumekit::cli::output().json = true;

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
  plumekit::cli::add_tunnel_commands(app);
  plumekit::cli::add_gdm_commands(app);
  plumekit::cli::add_options_commands(app);
  plumekit::cli::add_methods_commands(app);
  plumekit::cli::add_replay_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string message = unknown_command(app, argc, argv);
    if (message.empty()) message = e.what();
    return plumekit::cli::usage_error(message);
  } catch (const plumekit::MemoryLimitError& e) {
    // The library speaks of "the memory limit"; here it is a flag.
    std::string message = plumekit::cli::with_flag_names(*selected(app), e.what());
    const std::string phrase = "raise the memory limit to at least ";
    if (const auto at = message.find(phrase); at != std::string::npos)
      message.replace(at, phrase.size(), "raise the limit with --max-memory ");
    return fail(2, "error", message);
  } catch (const plumekit::InputError& e) {
    // OptionErrors and the messages that advise a setting name option fields.
    return fail(2, "error", plumekit::cli::with_flag_names(*selected(app), e.what()));
  } catch (const std::filesystem::filesystem_error& e) {
    // The file system refused (permission, a full disk, a name too long): the
    // user's to fix, and the message names the path.
    return fail(2, "error", e.what());
  } catch (const std::bad_alloc&) {
    return fail(2, "error",
                "out of memory; use a smaller map, a coarser cell, or fewer threads "
                "(see --max-memory)");
  } catch (const std::exception& e) {
    return fail(1, "internal error", e.what());
  }
  return 0;
}
