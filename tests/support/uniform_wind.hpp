#pragma once
// A uniform wind along +x over an empty arena, built directly on the MAC
// faces (no flow solve): the setting of the analytic plume solutions.
#include <vector>

#include "cfd/wind_field.hpp"

namespace plumekit::test {

inline cfd::WindField uniform_wind(double width, double height, double cell, double speed) {
  const GridShape g = GridShape::with_cell(width, height, cell);
  std::vector<double> fu(static_cast<std::size_t>(g.nx + 1) * g.ny, speed);
  std::vector<double> fv(static_cast<std::size_t>(g.nx) * (g.ny + 1), 0.0);
  return cfd::WindField(g, fu, fv, std::vector<double>(g.size(), 0.0),
                        std::vector<std::uint8_t>(g.size(), 0));
}

}  // namespace plumekit::test
