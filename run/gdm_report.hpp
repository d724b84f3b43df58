#pragma once
// What `plumekit gdm` reports: the maps' settings and figures, the score against the true mean
// plume when the source is known, and the six source estimates.
#include <optional>
#include <string>

#include "core/report.hpp"
#include "methods/gdm_estimates.hpp"
#include "methods/kernel_dmv.hpp"
#include "run/gdm_score.hpp"

namespace plumekit::run {

struct GdmRun {
  std::string map_file, samples_file, out;
  methods::GdmOptions options;
  std::optional<Vec2> source;  // arena frame
  std::optional<MapScore> score;
};

Report gdm_report(const Map& map, const methods::GdmMaps& maps, const GdmRun& run);

// "Kernel DM+V" or "Kernel DM+V/W" (when the wind stretches the kernels).
std::string method_name(const methods::GdmOptions& options,
                        const std::vector<methods::Sample>& samples);

}  // namespace plumekit::run
