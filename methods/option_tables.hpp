#pragma once
// The options tables of the methods' own options (core/option_table.hpp): their validate()
// checks, localize's and evaluate's method flags, the Python properties and docs/options.md are
// made from these. Each table lives beside its struct's code.
#include "core/option_table.hpp"

namespace plumekit::methods {

struct TrackingOptions;
struct ParticleFilterOptions;
struct PfMethodOptions;
struct LevyTaxisOptions;
struct LocalFrameworkOptions;
struct MethodOptions;
struct GdmOptions;
struct ApfOptions;
struct SweepPatternOptions;
struct CrosswindSearchOptions;

// The seeds' plume trackers (plume_tracking.cpp).
const OptionTable<TrackingOptions>& tracking_option_table();
// The particle filter (particle_filter.cpp) and its declaration rule (pf_method.cpp).
const OptionTable<ParticleFilterOptions>& particle_filter_option_table();
const OptionTable<PfMethodOptions>& pf_method_option_table();
// The predefined sweep, the particle filter's other exploration (pf_method.cpp).
const OptionTable<SweepPatternOptions>& sweep_option_table();
// Adaptive Lévy taxis (levy_taxis.cpp).
const OptionTable<LevyTaxisOptions>& levy_option_table();
// STE in the local framework (local_framework.cpp); its nested MH and navigation use STE's tables.
const OptionTable<LocalFrameworkOptions>& local_option_table();
// What MethodOptions adds to the methods' own: the run's step budget and the particle filter's
// penalties, unset the seeds' best for the exploration (method_options.cpp).
const OptionTable<MethodOptions>& method_option_table();
// Adaptive sampling for gas mapping, the APF (apf_planner.cpp).
const OptionTable<ApfOptions>& apf_option_table();
// Gas distribution mapping, Kernel DM+V and DM+V/W (kernel_dmv.cpp).
const OptionTable<GdmOptions>& gdm_option_table();
// The tunnel's crosswind trackers: surge-cast, surge-spiral, Lévy (crosswind_search.cpp).
const OptionTable<CrosswindSearchOptions>& crosswind_search_option_table();

}  // namespace plumekit::methods
