#pragma once
// The options tables of a localization, a team and an evaluation (core/option_table.hpp): their
// checks, the CLI flags of localize's team and of evaluate, and docs/options.md. run/options.cpp.
#include "core/option_table.hpp"

namespace plumekit::run {

struct TeamOptions;
struct EvaluationOptions;
struct SteOptions;
struct SteLikelihood;

// A localization's own options (SteOptions' fields that are not a nested struct): its checks,
// localize's and evaluate's flags and docs/options.md. The nested structs have their own tables.
const OptionTable<SteOptions>& ste_option_table();
// The likelihood's sigmas, whose unset values the plume model chooses (default_likelihood).
const OptionTable<SteLikelihood>& ste_likelihood_option_table();

const OptionTable<TeamOptions>& team_option_table();
// The counts of an evaluation; its seed, its part (--shard) and its SteOptions are checked
// and bound apart.
const OptionTable<EvaluationOptions>& evaluation_option_table();

}  // namespace plumekit::run
