#include "run/mission_times.hpp"

#include <algorithm>

#include "run/method_run.hpp"
#include "run/run_record.hpp"

namespace plumekit::run {

double first_within(const std::vector<Step>& steps, Vec2 source, double radius, double speed,
                    const std::vector<Vec2>& approach) {
  const SourceDisc disc{source, radius};
  double left_s = 0.0;  // when the robot left its previous stop
  for (const Step& s : steps) {
    if (s.path_in.size() >= 2) {
      double length = 0.0;
      for (std::size_t k = 1; k < s.path_in.size(); ++k)
        length += norm(s.path_in[k] - s.path_in[k - 1]);
      // A robot kept waiting (a team's separation rule) waits before it drives.
      const double departed_s = std::max(left_s, s.arrived_s - length / speed);
      if (const std::optional<SourceDisc::Entry> e = disc.entry(s.path_in))
        return std::min(departed_s + e->along / speed, s.arrived_s);
    }
    if (disc.contains(s.position)) return s.arrived_s;
    left_s = s.time_s;
  }
  if (const std::optional<SourceDisc::Entry> e = disc.entry(approach))
    return left_s + e->along / speed;
  return MissionTimes::kNever;
}

double first_detection(const std::vector<Step>& steps, double threshold) {
  for (const Step& s : steps) {
    for (const PassingRecord& r : s.on_the_way)
      if (r.value > threshold) return r.time_s;
    if (s.value > threshold) return s.time_s;
  }
  return MissionTimes::kNever;
}

}  // namespace plumekit::run
