#pragma once
// The picture of a gas map: its mean, variance and confidence one above the other, with the
// samples, the true source when it is known, and each panel's peak.
#include <optional>
#include <string>
#include <vector>

#include "map/map.hpp"
#include "map/map_render.hpp"
#include "methods/kernel_dmv.hpp"

namespace plumekit::run {

// `method` names the maps ("Kernel DM+V", "Kernel DM+V/W"); `unit` the readings'.
Picture draw_gdm(const Map& map, const methods::GdmMaps& maps,
                 const std::vector<methods::Sample>& samples, const std::optional<Vec2>& source,
                 const std::string& method, const std::string& unit,
                 const RenderOptions& options = {80.0});

}  // namespace plumekit::run
