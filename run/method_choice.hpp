#pragma once
// Which localization method a run uses (--method) and the options of those other than STE:
// the seeds' plume trackers and particle filters (methods/), built here for one map.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "methods/apf_planner.hpp"
#include "methods/levy_taxis.hpp"
#include "methods/local_framework.hpp"
#include "methods/method.hpp"
#include "methods/pf_method.hpp"
#include "methods/plume_tracking.hpp"

namespace plumekit::run {

enum class MethodKind {
  Ste,
  Sweeping,
  SurgeCast,
  Zigzag,
  PseudoGradient,
  PfGradient,
  PfSweep,
  Apf,
  LevyTaxis,
  SteLocal
};
const char* to_string(MethodKind kind);
// The --method names in order: "ste", "sweeping", ... OptionError on ste.method otherwise.
MethodKind parse_method_kind(const std::string& name);
std::vector<std::string> method_names();
// "NAME[,NAME...]" (each once) or "all" (every method, in method_names()'s order): the methods
// `evaluate --method` runs in one world. OptionError on ste.method otherwise.
std::vector<MethodKind> parse_method_list(const std::string& text);

// STE needs a plume model; the others read only the gas, the wind and the pose. (The APF's gas
// maps are built from the readings.)
inline bool uses_plume_model(MethodKind kind) {
  return kind == MethodKind::Ste;
}
// Runs that end in the plume trackers' success box (SourceBox): the trackers'. The particle
// filter explored by the pseudo-gradient tracker goes on past the source, as the seeds' runs did
// (seed 002 Fig. 5(d): 133 iterations), to its budget or its declaration.
bool stops_in_source_box(MethodKind kind);
// Runs that end when the robot arrives near the source: in the trackers' box, or within adaptive
// Lévy taxis' 0.5 m of it (seed 004 ch. 15; SourceDisc). They report whether they reached it and
// the distance overhead.
bool ends_on_arrival(MethodKind kind);

struct MethodOptions {
  MethodKind kind = MethodKind::Ste;
  // The trackers, and the particle filter's exploration. Its max_steps is replaced by the one
  // below.
  methods::TrackingOptions tracking;
  // Stops of a run at most; 0 (auto): two per square step of the arena (80 on the thesis's
  // 10 x 4 m with 1 m steps, 512 in the seeds' 32 x 8 m tunnel), at least 50. A tracker caught
  // in a dead end should not wander for hours of simulated time.
  int max_steps = 0;
  // max_steps with auto resolved for an arena of `area` m².
  int max_steps_in_use(double area) const;
  // The particle filter and its declaration rule; its seed and step budget are set per run (the
  // run's seed, tracking.max_steps).
  methods::PfMethodOptions pf;
  // Unset: the seeds' best for the exploration (seed 001: (0.2, 0.8) with the pseudo-gradient,
  // (0.4, 0.9) with the predefined sweep).
  std::optional<double> pf_alpha, pf_beta;
  // Adaptive sampling for gas distribution mapping (seed 000 ch. 8; docs/methods.md); its
  // max_steps is replaced by the one above.
  methods::ApfOptions apf;
  // Adaptive Lévy taxis (seed 004 ch. 16); its max_steps is replaced by the one above.
  methods::LevyTaxisOptions levy;
  // STE in the local framework (seed 004 ch. 12): no map, odometry, a moving local map.
  methods::LocalFrameworkOptions local;
  // The filter's options for `kind`: alpha and beta resolved, the detection limit the trackers'
  // detection threshold, the step budget tracking.max_steps.
  methods::PfMethodOptions pf_in_use() const;
  // OptionError naming the field ("ste.method.tracking.step", ...).
  void validate() const;
};

// A fresh method other than STE (Scenario builds STE itself) searching `area`; `seed` drives the
// particle filter.
std::unique_ptr<methods::LocalizationMethod> make_method(const MethodOptions& options,
                                                         const methods::SearchArea& area,
                                                         std::uint64_t seed);

}  // namespace plumekit::run
