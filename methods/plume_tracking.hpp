#pragma once
// The seeds' bio-inspired plume acquisition and tracking for a robot that measures only while it
// stands still (seed 000 Sec. 5.1, seed 002 Sec. 3): sweep crosswind until the first detection,
// then track the plume upwind by surge-cast, zigzag (dung beetle) or the pseudo-gradient
// two-position strategy. A stop "detects" when its mean gas reading is above the threshold.
//
// Every tracker reads only its observations: the recorded (noisy) position, the gas reading and
// the measured wind. It never knows the source, so it has no estimate; the runner stops it when it
// reaches the success box downwind of the source or leaves the arena, and scores where it ends.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "methods/method.hpp"

namespace plumekit::methods {

// When the zigzag turns to the other side of the upwind direction.
enum class ZigzagFlip {
  OnLoss,       // seed 002 Sec. 3.2.2: when the reading drops below the threshold (plume edge)
  OnDetection,  // seed 000 Sec. 5.1.2.2's bullet list: whenever a reading is above it
};

struct TrackingOptions {
  double step = 1.0;  // m: sweep, surge, cast unit and zigzag leg; d_cross of the gradient
  // Concentration units: a stop detects when its mean reading is above this. The seeds used 5 % of
  // the peak of a normalised field; 50 is about that for a plumekit source of 1000 units/s, whose
  // readings near the axis a few metres downwind are in the hundreds to thousands.
  double detection_threshold = 50.0;
  // m kept from the arena's walls: the search area is the arena shrunk by it, since touching a
  // wall fails a run in the seeds (half the seeds' 1 m drone).
  double wall_margin = 0.5;
  double zigzag_alpha_deg = 60.0;  // angle of a zigzag leg off upwind (the seeds' real runs)
  ZigzagFlip zigzag_flip = ZigzagFlip::OnLoss;
  double gradient_beta_deg = 90.0;  // largest turn off upwind (the seeds' particle-filter study)
  int max_casts = 5;                // surge-cast: casts before it sweeps again
  int max_misses = 3;               // zigzag: consecutive non-detections that make it sweep again
  int max_steps = 300;              // stops before stopped_by() says "max_samples"

  // OptionError naming the field ("tracking.step", ...) for a value out of range.
  void validate() const;
};

// "loss", "detection"; OptionError naming tracking.zigzag_flip otherwise.
const char* to_string(ZigzagFlip flip);
ZigzagFlip parse_zigzag_flip(const std::string& name);

// The search area of the trackers: the arena's rectangle less the wall margin. Obstacles are the
// runner's concern (it moves a goal inside one to the nearest free point), as the seeds searched
// an open rectangle.
class SearchBounds {
 public:
  SearchBounds(const SearchArea& area, double margin);
  bool inside(Vec2 p) const;
  Vec2 clamp(Vec2 p) const;
  Vec2 centre() const;
  // The farthest point of p + t d, 0 <= t <= length, inside (a goal cut short at the edge); when
  // p itself is outside, p + length d clamped into the area.
  Vec2 along(Vec2 p, Vec2 d, double length) const;

 private:
  Vec2 lo_, hi_;
};

// The sweeping acquisition (seed 000 Sec. 5.1.1) as a component the trackers fall back to.
// Each step goes one step crosswind in the sweep direction; when that leaves the area it goes one
// step upwind instead and inverts the sweep direction; when that leaves too it goes one step
// toward the centre of the area (our "search direction": it always stays inside and leads away
// from the corner).
//
// The sweep direction is kept in the arena frame, as the crosswind unit last used: each step
// takes the perpendicular of the wind nearer to it, so a wind that turns slowly turns the sweep
// with it, and a noisy wind does not make it oscillate. At the first step it points to the side
// with more room (toward the centre; on a tie, the upwind direction turned counter-clockwise).
class Sweeper {
 public:
  Sweeper(const SearchBounds& bounds, double step);
  // The next stop from `p` for the upwind unit `up` (non-zero).
  Vec2 step(Vec2 p, Vec2 up);
  // The crosswind unit of the sweep direction at `p`; it becomes the sweep direction.
  Vec2 crosswind(Vec2 p, Vec2 up);
  // Turns the sweep direction around (no effect before the first crosswind()).
  void invert() { direction_ = -1.0 * direction_; }
  Vec2 direction() const { return direction_; }  // (0, 0) before the first crosswind()

 private:
  SearchBounds bounds_;
  double step_;
  Vec2 direction_;
};

// What the trackers share: input checks, the calm-wind rule, the step budget and the sweeping
// acquisition before the first detection and after the plume is lost for good.
//
// A calm stop (wind below 1e-9 m/s) keeps the last measured upwind direction; before any wind
// is measured upwind is -x (plumekit's default arena blows along +x).
//
// A tracker moves by steps ("1 m upwind of here"): it plans its goal from the position the stop
// recorded, and next(robot) hands the runner the same step from where the robot truly stands,
// as a robot's odometry would carry it out. The position noise (GPS) then blurs what the
// tracker knows of where it is, not the length of its steps: seed 000's simulated trackers
// (zigzag 15 degrees: d_o 1.07) cannot have taken GPS-sized detours.
class PlumeTracker : public LocalizationMethod {
 public:
  void observe(const Observation& o) final;
  Move next(Vec2 robot) final;
  std::optional<Vec2> estimate() const final { return std::nullopt; }
  std::string stopped_by() const final;
  // Sweeping for the plume, not tracking it.
  bool acquiring() const { return acquiring_; }
  const Sweeper& sweeper() const { return sweeper_; }
  int stops() const { return stops_; }

 protected:
  PlumeTracker(const SearchArea& area, const TrackingOptions& options);
  // The goal after the stop `o` that ends the acquisition (it detected); `up` is its upwind unit.
  virtual Vec2 begin_tracking(const Observation& o, Vec2 up) = 0;
  // The goal after a stop while tracking.
  virtual Vec2 track(const Observation& o, Vec2 up) = 0;
  // Sweeps again: the sweep step from `p`.
  Vec2 fall_back(Vec2 p, Vec2 up);
  bool detected(double gas) const { return gas > options_.detection_threshold; }

  TrackingOptions options_;
  SearchBounds bounds_;
  Sweeper sweeper_;

 private:
  bool acquiring_ = true;
  int stops_ = 0;
  Vec2 last_upwind_{-1.0, 0.0};
  Vec2 recorded_;  // the last stop's recorded position, which goal_ was planned from
  std::optional<Vec2> goal_;
};

// Sweeping alone, over the whole area, for a baseline: it never switches to tracking.
class SweepingMethod : public PlumeTracker {
 public:
  SweepingMethod(const SearchArea& area, const TrackingOptions& options);
  std::string name() const override { return "sweeping"; }

 protected:
  Vec2 begin_tracking(const Observation& o, Vec2 up) override;
  Vec2 track(const Observation& o, Vec2 up) override;
};

// Surge-cast, the micro-drone variant of the silkworm moth's strategy (seed 000 Sec. 5.1.2.1):
// a detection surges one step straight upwind; the k-th consecutive non-detection casts k steps
// crosswind, alternating sides, so the casts widen around the point of loss (+1, -1, +2, -2, ...
// steps); a non-detection after max_casts casts sweeps again. The first cast goes to the side the
// plume swung to, read from how the wind turned since the last detection (a counter-clockwise
// turn swings the plume to the right of upwind); in a steady wind, to the sweep direction's side.
// A surge that would leave the area takes the sweep step instead; a cast is cut at the edge.
class SurgeCast : public PlumeTracker {
 public:
  SurgeCast(const SearchArea& area, const TrackingOptions& options);
  std::string name() const override { return "surge-cast"; }
  int casts() const { return casts_; }

 protected:
  Vec2 begin_tracking(const Observation& o, Vec2 up) override;
  Vec2 track(const Observation& o, Vec2 up) override;

 private:
  Vec2 surge(Vec2 p, Vec2 up);
  int casts_ = 0;
  int cast_side_ = 1;         // +1: left of upwind (turned 90 deg counter-clockwise)
  Vec2 upwind_at_detection_;  // for the first cast's side
};

// Zigzag / dung beetle (seed 002 Sec. 3.2.2, seed 000 Sec. 5.1.2.2): each leg is one step at
// +-alpha off upwind. The side flips by options.zigzag_flip, and also when the next leg would
// leave the area (the sweep step when both sides would). After max_misses consecutive
// non-detections it sweeps again. The first leg after an acquisition goes to the sweep
// direction's side (across the plume the sweep entered) without a flip.
class Zigzag : public PlumeTracker {
 public:
  Zigzag(const SearchArea& area, const TrackingOptions& options);
  std::string name() const override { return "zigzag"; }
  int side() const { return side_; }  // +1: legs left of upwind (counter-clockwise)

 protected:
  Vec2 begin_tracking(const Observation& o, Vec2 up) override;
  Vec2 track(const Observation& o, Vec2 up) override;

 private:
  Vec2 leg(Vec2 p, Vec2 up);
  int side_ = 1;
  int misses_ = 0;
  bool in_plume_ = false;
};

// The pseudo-gradient of seed 002 Sec. 3.2.3 (Eqs. 1-2), a state machine of three phases:
//   Sweeping   until a stop detects; that stop is the first p1.
//   MeasureP1  the stop is p1: step crosswind in the sweep direction (the other way if that
//              leaves the area) to p2.
//   MeasureP2  the stop is p2: readings at or below the threshold count 0. Both 0: invert the
//              sweep direction and sweep again. Otherwise grad = c1 / (c1 + c2) and
//                grad > 0.5: delta = upwind(p1) turned beta (2 grad - 1) toward p1's side, and
//                            the sweep direction inverts (the next p2 lies on p1's side);
//                grad < 0.5: delta = upwind(p2) turned beta (1 - 2 grad) toward p2's side;
//                grad = 0.5: delta = the circular mean of upwind(p1) and upwind(p2);
//              p3 = (p1 + p2) / 2 + 1.5 step along delta (cut to the area), the next p1.
// The seeds' "beta <- -beta" with the inverted crosswind direction is the turn toward p1's side
// here: the turn's sign is taken from the side of the crosswind step, so it always points to the
// higher reading.
enum class GradientPhase { Sweeping, MeasureP1, MeasureP2 };

class PseudoGradient : public PlumeTracker {
 public:
  PseudoGradient(const SearchArea& area, const TrackingOptions& options);
  std::string name() const override { return "pseudo-gradient"; }
  GradientPhase phase() const { return acquiring() ? GradientPhase::Sweeping : phase_; }

 protected:
  Vec2 begin_tracking(const Observation& o, Vec2 up) override;
  Vec2 track(const Observation& o, Vec2 up) override;

 private:
  Vec2 measure_p1(const Observation& o, Vec2 up);
  Vec2 measure_p2(const Observation& o, Vec2 up);
  double reading(double gas) const { return detected(gas) ? gas : 0.0; }
  GradientPhase phase_ = GradientPhase::MeasureP1;
  Vec2 p1_, upwind1_, crosswind_;
  double c1_ = 0.0;
};

// The trackers by --method name: "sweeping", "surge-cast", "zigzag", "pseudo-gradient".
std::vector<std::string> tracking_method_names();
std::unique_ptr<LocalizationMethod> make_sweeping(const SearchArea& area,
                                                  const TrackingOptions& options);
std::unique_ptr<LocalizationMethod> make_surge_cast(const SearchArea& area,
                                                    const TrackingOptions& options);
std::unique_ptr<LocalizationMethod> make_zigzag(const SearchArea& area,
                                                const TrackingOptions& options);
std::unique_ptr<LocalizationMethod> make_pseudo_gradient(const SearchArea& area,
                                                         const TrackingOptions& options);
// OptionError("method", ...) for a name not in tracking_method_names().
std::unique_ptr<LocalizationMethod> make_tracking_method(const std::string& name,
                                                         const SearchArea& area,
                                                         const TrackingOptions& options);

// The seeds' distance overhead d_o = d_t / d_u (seed 000 App. C): `path` is where the robot went
// from its first above-threshold position on (the acquisition is left out), d_t its length, and
// d_u = |path.front() - source| - |path.back() - source| the progress toward the source.
// nullopt when there was no progress (d_u <= 0, an empty path).
std::optional<double> distance_overhead(const std::vector<Vec2>& path, Vec2 source);

}  // namespace plumekit::methods
