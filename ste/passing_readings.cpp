#include "ste/passing_readings.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace plumekit::ste {

void PassingOptions::validate() const {
  const auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0))
      throw InputError(std::string("ste.passing.") + name + ": must be a number above 0");
  };
  positive(window_s, "window_s");
  positive(reading_s, "reading_s");
  positive(stop_s, "stop_s");
  if (!(std::isfinite(lag_s) && lag_s >= 0.0))
    throw InputError("ste.passing.lag_s: must be a number at least 0");
}

Vec2 point_before(const std::vector<PassingReading>& readings, double t, double lag_s) {
  const double at = t - lag_s;
  if (readings.empty()) return {};
  if (at <= readings.front().time_s) return readings.front().position;
  for (std::size_t k = 1; k < readings.size(); ++k) {
    const PassingReading &a = readings[k - 1], &b = readings[k];
    if (at <= b.time_s) {
      const double span = b.time_s - a.time_s;
      const double f = span > 0.0 ? (at - a.time_s) / span : 1.0;
      return a.position + f * (b.position - a.position);
    }
  }
  return readings.back().position;
}

std::vector<PartialSample> partial_samples(const std::vector<PassingReading>& readings,
                                           const PassingOptions& o) {
  o.validate();
  for (std::size_t k = 0; k < readings.size(); ++k) {
    const PassingReading& r = readings[k];
    if (!std::isfinite(r.position.x) || !std::isfinite(r.position.y) || !std::isfinite(r.time_s) ||
        !std::isfinite(r.value))
      throw InputError("ste.passing reading " + std::to_string(k) +
                       ": position, time or value is not a finite number");
  }
  // Readings per stretch: whole readings nearest window_s.
  const std::size_t per = std::max<std::size_t>(1, std::lround(o.window_s / o.reading_s));
  std::vector<PartialSample> samples;
  std::size_t first = 0;
  while (first < readings.size()) {
    std::size_t end = first + 1;
    while (end < readings.size() && end - first < per &&
           readings[end].time_s - readings[end - 1].time_s <= 2.0 * o.reading_s)
      ++end;
    double sum = 0.0;
    for (std::size_t k = first; k < end; ++k)
      sum += readings[k].value;
    const double n = static_cast<double>(end - first);
    // The middle of the stretch's time: each reading stands for the interval it ends.
    const double middle = 0.5 * (readings[first].time_s - o.reading_s + readings[end - 1].time_s);
    samples.push_back({point_before(readings, middle, o.lag_s), sum / n,
                       std::min(1.0, n * o.reading_s / o.stop_s)});
    first = end;
  }
  return samples;
}

}  // namespace plumekit::ste
