#pragma once
// Readings taken while the robot moves (issue 47): a sensor reads at its own rate (10 Hz) along
// every path, not only at stops. STE cannot use each 10 Hz reading as a stop's 5 s mean: one
// reading of an intermittent plume says little, and the readings along a path are correlated in
// time as a stop's are. So the readings of each stretch of `window_s` seconds are averaged into
// one partial sample that counts as window_s / stop_s of a stop (Estimator::add_partial): a
// second of readings counts as a second of a stop, moving or not.
//
// The sensor's response is part of the forward model: a first-order sensor (the MOX models)
// reports the concentration it met about `lag_s` earlier (its mean delay: the dead time plus the
// time constant), so a stretch's partial sample is placed where the robot was lag_s before the
// stretch's middle, along the readings' recorded points. Where the robot waits (no motion), that
// is where it stands.
#include <vector>

#include "core/geometry.hpp"

namespace plumekit::ste {

// One reading on the way: where the robot recorded it, when (s, any origin), and the value.
struct PassingReading {
  Vec2 position;
  double time_s = 0.0;
  double value = 0.0;
};

// A sample worth `weight` of a stop's (0 < weight <= 1): Estimator::add_partial.
struct PartialSample {
  Vec2 position;
  double value = 0.0;
  double weight = 1.0;
};

struct PassingOptions {
  double window_s = 1.0;   // the stretch averaged into one partial sample, s
  double reading_s = 0.1;  // the time one reading stands for: the sensor's interval, s
  double stop_s = 5.0;     // a stop's sampling, s: a stretch counts window_s / stop_s of one
  double lag_s = 0.0;      // the sensor's mean delay, s (0: an ideal sensor)
  // InputError naming the field unless each is finite, window_s, reading_s, stop_s > 0 and
  // lag_s >= 0.
  void validate() const;
};

// The partial samples of `readings` (oldest first): consecutive stretches of about window_s
// (a gap of more than two reading intervals starts a new one), each the mean of its readings,
// weighing its readings' time over stop_s (at most 1), at the point lag_s before its middle.
// InputError naming the reading for a point, time or value that is not finite.
std::vector<PartialSample> partial_samples(const std::vector<PassingReading>& readings,
                                           const PassingOptions& options);

// The point `lag_s` before time `t` along the readings' recorded points (linear between them;
// the first point before them).
Vec2 point_before(const std::vector<PassingReading>& readings, double t, double lag_s);

}  // namespace plumekit::ste
