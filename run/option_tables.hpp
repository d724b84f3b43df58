#pragma once
// The options tables of a team and of an evaluation (core/option_table.hpp): their checks, the
// CLI flags of localize's team and of evaluate, and docs/options.md. run/options.cpp.
#include "core/option_table.hpp"

namespace plumekit::run {

struct TeamOptions;
struct EvaluationOptions;

const OptionTable<TeamOptions>& team_option_table();
// The counts of an evaluation; its seed, its part (--shard) and its SteOptions are checked
// and bound apart.
const OptionTable<EvaluationOptions>& evaluation_option_table();

}  // namespace plumekit::run
