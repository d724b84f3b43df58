#pragma once
// The options tables of STE's own options structs (core/option_table.hpp):
// their validate() checks, the CLI's navigation and stop flags, the Python
// properties and docs/options.md are made from these. ste/options.cpp.
#include "core/option_table.hpp"

namespace plumekit::ste {

struct LikelihoodOptions;
struct BinOptions;
struct MhOptions;
struct NavigationOptions;
struct StopOptions;
struct PhysicsPlumeOptions;
struct GaussianPlumeBounds;

const OptionTable<LikelihoodOptions>& likelihood_option_table();
const OptionTable<BinOptions>& bin_option_table();
const OptionTable<MhOptions>& mh_option_table();
const OptionTable<NavigationOptions>& navigation_option_table();
const OptionTable<StopOptions>& stop_option_table();
const OptionTable<PhysicsPlumeOptions>& physics_option_table();
const OptionTable<GaussianPlumeBounds>& gaussian_option_table();

}  // namespace plumekit::ste
