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
struct Ste3dOptions;

const OptionTable<LikelihoodOptions>& likelihood_option_table();
const OptionTable<BinOptions>& bin_option_table();
const OptionTable<MhOptions>& mh_option_table();
const OptionTable<NavigationOptions>& navigation_option_table();
const OptionTable<StopOptions>& stop_option_table();
const OptionTable<PhysicsPlumeOptions>& physics_option_table();
const OptionTable<GaussianPlumeBounds>& gaussian_option_table();
// The tunnel's 3-D STE (ste/ste_3d.cpp); its nested structs use the tables above.
const OptionTable<Ste3dOptions>& ste3d_option_table();

}  // namespace plumekit::ste
