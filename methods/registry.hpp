#pragma once
// The registry of localization methods, as OMPL's planners and Ceres's cost functions are listed:
// each method says, in its own file, its name, a one-line description, the seed it comes from,
// its traits and a factory (a MethodSpec); registry.cpp lists them, one line each. The CLI's
// --method choices and help, `evaluate --method all`, the Python binding and
// docs/methods-registry.md all read this list.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "methods/crosswind_search.hpp"
#include "methods/method.hpp"
#include "planner/planner.hpp"
#include "ste/navigation.hpp"
#include "ste/passing_readings.hpp"
#include "ste/posterior.hpp"
#include "ste/ste_3d.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::methods {

struct MethodOptions;  // method_options.hpp

// How a run of a method ends, besides its step budget.
enum class RunEnd {
  OwnStopRule,  // its own stop rule (STE's entropy, the filter's declaration, ...)
  SourceBox,    // in the plume trackers' success box around the source (SourceBox)
  SourceDisc,   // within adaptive Lévy taxis' 0.5 m of the source (seed 004 ch. 15; SourceDisc)
};
const char* to_string(RunEnd end);

struct MethodTraits {
  // STE needs a plume model; the others read only the gas, the wind and the pose.
  bool uses_plume_model = false;
  RunEnd ends = RunEnd::OwnStopRule;
  // Works in a robot team (run/team.hpp): its method is a Teammate (as_teammate()) and holds a
  // posterior.
  bool teams = false;
  // Runs that end when the robot arrives near the source report whether it reached it and the
  // distance overhead.
  bool ends_on_arrival() const { return ends != RunEnd::OwnStopRule; }
};

// A fresh method searching `area` with `options` (max_steps already resolved into
// tracking.max_steps); `seed` drives its randomness.
using MethodFactory = std::function<std::unique_ptr<LocalizationMethod>(
    const MethodOptions& options, const SearchArea& area, std::uint64_t seed)>;

// Adds the method's own options to what a run records of them (summary.json's method_options),
// after the step and detection threshold every method shares and before its step budget: the
// report never names a method.
using MethodOptionsJson =
    std::function<void(const MethodOptions& options, nlohmann::ordered_json& into)>;

// What a method with a plume model (STE) takes from the run's scenario, which builds the model
// for the map: a fresh estimator for the run, the planner, the navigator and the stop rule. They
// must outlive the method.
struct PlumeModelParts {
  std::function<std::unique_ptr<ste::Estimator>()> estimator;
  const planner::Planner* planner = nullptr;
  const ste::Navigator* navigator = nullptr;
  const ste::StopOptions* stop = nullptr;
  // How STE takes the readings on the way (null: it ignores them).
  const ste::PassingOptions* passing = nullptr;
};
// A fresh method with a plume model, from the scenario's parts.
using PlumeModelFactory =
    std::function<std::unique_ptr<LocalizationMethod>(const PlumeModelParts& parts)>;

struct MethodSpec {
  std::string name;         // the --method name
  std::string description;  // one line, for --help and the docs
  std::string source;       // the seed and section it comes from
  MethodTraits traits;
  // One of the two: a method of readings alone is made from its options and area; a method with
  // a plume model (traits.uses_plume_model) from the parts the run's scenario built.
  MethodFactory factory;
  MethodOptionsJson options_json;  // empty: none of its own
  PlumeModelFactory model_factory = nullptr;
};

// Every method, in registry.cpp's order then the order add_method() was called.
const std::vector<MethodSpec>& method_registry();
// Adds a method (a user's or a test's own). std::invalid_argument for an empty name, a name
// already taken, or a spec without the factory its traits need.
void add_method(MethodSpec spec);
// The spec named `name`; OptionError on ste.method listing the names otherwise.
const MethodSpec& find_method(const std::string& name);
std::vector<std::string> method_names();
// "NAME[,NAME...]" (each once) or "all" (every method, in method_names()'s order): the methods
// `evaluate --method` runs in one world. OptionError on ste.method otherwise.
std::vector<std::string> parse_method_list(const std::string& text);

// Shorthands for find_method(name).traits.
bool uses_plume_model(const std::string& name);
bool stops_in_source_box(const std::string& name);
bool ends_on_arrival(const std::string& name);

// A fresh method: options.name's factory, after options.validate() and with the step budget
// resolved for the area; a method with a plume model from `model` (std::logic_error without).
std::unique_ptr<LocalizationMethod> make_method(const MethodOptions& options,
                                                const SearchArea& area, std::uint64_t seed,
                                                const PlumeModelParts* model = nullptr);

// The registry as a Markdown table (name, description, source, plume model, how a run ends):
// docs/methods-registry.md, which MethodRegistry.DocsTableIsTheRegistry keeps equal to it.
std::string registry_markdown();

// The tunnel's methods (seed 004's 3-D systems, run/tunnel_run.hpp), listed the same way.
struct TunnelMethodInputs {
  Box3 tunnel;
  double margin = 0.0;            // goals stay this far inside the walls
  ste::Ste3dOptions ste;          // the 3-D STE's
  CrosswindSearchOptions search;  // a tracker's: its step and altitude set by the run
  std::uint64_t chain_seed = 0;   // STE's Metropolis-Hastings chain
  std::uint64_t walk_seed = 0;    // a tracker's draws
};
using TunnelMethodFactory =
    std::function<std::unique_ptr<LocalizationMethod3>(const TunnelMethodInputs& inputs)>;
struct TunnelMethodSpec {
  std::string name;         // the tunnel's --method name
  std::string description;  // one line, for --help
  std::string source;       // the seed and section it comes from
  // A tracker starts downwind of the source, flies reading on the move, and succeeds inside the
  // source's box while in the plume; otherwise the method declares an estimate.
  bool tracker = false;
  // Flies at a fixed altitude 10 cm below the source (ch. 17's 2-D baseline, after Rahbar et al.).
  bool flies_flat = false;
  TunnelMethodFactory factory;
};
const std::vector<TunnelMethodSpec>& tunnel_method_registry();
// The spec named `name`; OptionError on tunnel.method listing the names otherwise.
const TunnelMethodSpec& find_tunnel_method(const std::string& name);
// "NAME[,NAME...]" (each once) or "all": the tunnel's methods in registry order.
std::vector<std::string> parse_tunnel_method_list(const std::string& text);
// "a (from), b (from) or c (from)": the --method help.
std::string tunnel_methods_help();

// Each method's spec, defined in the method's own file.
MethodSpec ste_spec();
MethodSpec sweeping_spec();
MethodSpec surge_cast_spec();
MethodSpec zigzag_spec();
MethodSpec pseudo_gradient_spec();
MethodSpec pf_gradient_spec();
MethodSpec pf_sweep_spec();
MethodSpec apf_spec();
MethodSpec levy_taxis_spec();
MethodSpec ste_local_spec();
TunnelMethodSpec ste_3d_spec();
TunnelMethodSpec surge_spiral_spec();
TunnelMethodSpec surge_cast_2d_spec();

}  // namespace plumekit::methods
