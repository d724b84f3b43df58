#include "core/random.hpp"

#include <cmath>

namespace plumekit {

double uniform01(std::mt19937_64& rng) {
  constexpr double kTwoTo64 = 18446744073709551616.0;
  const double u = static_cast<double>(rng() - std::mt19937_64::min()) / kTwoTo64;
  return u >= 1.0 ? std::nextafter(1.0, 0.0) : u;
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return uniform01(rng) * (hi - lo) + lo;
}

double NormalSampler::operator()(std::mt19937_64& rng) {
  if (saved_available_) {
    saved_available_ = false;
    return saved_;
  }
  double x, y, r2;
  do {
    x = 2.0 * uniform01(rng) - 1.0;
    y = 2.0 * uniform01(rng) - 1.0;
    r2 = x * x + y * y;
  } while (r2 > 1.0 || r2 == 0.0);
  const double mult = std::sqrt(-2 * std::log(r2) / r2);
  saved_ = x * mult;
  saved_available_ = true;
  return y * mult;
}

double normal(NormalSampler& sampler, std::mt19937_64& rng, double mean, double sd) {
  return sampler(rng) * sd + mean;
}

}  // namespace plumekit
