#include "methods/method.hpp"

#include <cmath>

#include "core/error.hpp"

namespace plumekit::methods {

void check_observation(const Observation& o, const std::string& who) {
  if (!is_finite(o.position) || !std::isfinite(o.gas) || !is_finite(o.wind) ||
      !std::isfinite(o.wind_variance))
    throw InputError(who + ": an observation's position or reading is not finite");
}

}  // namespace plumekit::methods
