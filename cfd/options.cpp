#include "cfd/options.hpp"

#include <string>

#include "cfd/grid_check.hpp"
#include "core/option_check.hpp"

namespace plumekit::cfd {

// The upper bounds are far beyond any useful setting; they catch unit
// mistakes and typos (a cell of 50 m, a viscosity of 1e9) before a solve that
// cannot succeed. cfd/README.md lists them.
void FlowOptions::validate() const {
  check_positive("flow.cell", cell, kMaxCell, "m", "the default is 0.05 m");
  check_positive("flow.nu", nu, 10.0, "m^2/s",
                 "the default is 0.01 m^2/s (air's molecular value is 1.5e-05)");
  check_range("flow.tolerance", tolerance, 1e-14, 0.1, "", "the default is 1e-08");
  check_count("flow.max_iterations", max_iterations, 0, 100000,
              "0 means the default (100, or 300 with the mixing-length closure)");
  check_positive("flow.kappa", kappa, 1.0, "", "von Karman's constant is 0.41");
  check_range("flow.lm_max", lm_max, -1e3, 1e3, "m",
              "0 or less means 0.09 times half the arena's smaller side");
  const char* walls[] = {"left", "right", "bottom", "top"};
  for (int k = 0; k < 4; ++k)
    check_range(std::string("flow.wall_speed.") + walls[k], wall_speed[k], -100.0, 100.0, "m/s",
                "0 is a no-slip wall");
}

}  // namespace plumekit::cfd
