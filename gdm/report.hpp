#pragma once
// What `plumekit gdm` reports: the maps' settings and figures, the score against the true mean
// plume when the source is known, and the six source estimates.
#include <optional>
#include <string>

#include "core/report.hpp"
#include "gdm/kernel_dmv.hpp"
#include "gdm/map_score.hpp"

namespace plumekit::gdm {

struct GdmRun {
  std::string map_file, samples_file, out;
  GdmOptions options;
  std::optional<Vec2> source;  // arena frame
  std::optional<MapScore> score;
};

Report gdm_report(const Map& map, const GdmMaps& maps, const GdmRun& run);

// "Kernel DM+V" or "Kernel DM+V/W" (when the wind stretches the kernels).
std::string method_name(const GdmOptions& options, const std::vector<Sample>& samples);

}  // namespace plumekit::gdm
