#pragma once
// When STE stops (thesis ch. 7): the posterior is certain (entropy below a fraction of its
// maximum, on sources the samples could see) or the sample budget is spent.
#include <cstddef>
#include <string>

#include "ste/posterior.hpp"

namespace plumekit::ste {

struct StopOptions {
  double entropy_fraction = 0.02;  // stop below 2 % of the maximum entropy
  // ... and only when at least this share of the posterior's mass is on sources the samples
  // could tell from no source (Posterior::seen_mass): a certain posterior on sources whose plume
  // reaches no sample says only that nothing was read.
  double seen_mass = 0.95;
  // A second rule, for the moving protocol (issue 47): stop once confidence_mass of the posterior
  // lies within confidence_radius of its expected source (mass_within), with seen_mass as above.
  // The thesis's entropy on 0.5 x 0.2 m bins asks for the source's bin; a robot that must say
  // where the leak is to half a metre can say it sooner. 0: off (the thesis's rule alone).
  double confidence_radius = 0.0;  // m
  double confidence_mass = 0.9;
  // 0 (auto): the thesis's 50, or on a floor (the floor mode) one sample per 10 m² of its
  // reachable free space when that is more (Scenario resolves it; resolve_max_samples).
  int max_samples = kAutoMaxSamples;
  static constexpr int kAutoMaxSamples = 0;
  static constexpr int kThesisMaxSamples = 50;
  int max_samples_in_use() const {
    return max_samples == kAutoMaxSamples ? kThesisMaxSamples : max_samples;
  }
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};

// The share of the posterior's (x, y) marginal whose cells' centres lie within `radius` of its
// expected source.
double mass_within(const Posterior& posterior, double radius);

// Why the run stops after `samples` samples with this posterior: "entropy", "confident",
// "max_samples", or "" (it goes on).
std::string stop_reason(const Posterior& posterior, int samples, const StopOptions& stop);

// `max_samples` with auto (0) resolved: the thesis's 50, or on a floor whose `floor_goals` goals
// `floor_spacing` apart cover more than 500 m² (one goal per spacing²), one sample per 10 m² of
// it. 50 samples do not cover a 30 x 50 m warehouse when the gas lives 28 s (docs/validation.md,
// "Floors").
int resolve_max_samples(int max_samples, std::size_t floor_goals, double floor_spacing);

}  // namespace plumekit::ste
