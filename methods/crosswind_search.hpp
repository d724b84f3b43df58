#pragma once
// The 3-D bio-inspired surge-spiral plume tracker (seed 004 ch. 17, Rahbar et al., IROS 2017) and
// its 2-D baseline surge-cast flown at a fixed altitude, in a wind tunnel (a Box3: x downwind
// along the tunnel, y across, z up; the wind blows toward +x). The robot moves at constant speed
// and decides every interval; `step` is the distance it covers per decision. Three phases:
//   - acquisition ("levy"): a Lévy walk on the crosswind plane through the robot (Eq. 17.2): a
//     move length M_l of Eq. 17.1 (levy_move_length) and a direction T_a ~ U[0, 2 pi) give the
//     target (x0, y0 + M_l sin T_a, z0 + M_l cos T_a), walked `step` per decision; a new target
//     is drawn on arrival. Cast2d walks on y alone, y0 +- M_l on a fair coin (Eq. 17.4 as meant).
//   - "surge": while in the plume, `step` upwind (minus the wind's direction; -x in a calm).
//   - on losing the plume, from the loss point c (the position of the first reading below the
//     threshold): Spiral3d follows Eq. 17.3's Archimedean spiral in the crosswind plane x = x_c,
//     (y, z) = c + s_d t (cos 2 pi t, sin 2 pi t), t advanced so that each goal lies exactly
//     `step` further along the spiral's arc (its closed-form length solved by Newton); Cast2d
//     casts crosswind legs at x_c to y_c + D, y_c - 2D, y_c + 3D, ... (D = cast; the first leg
//     toward +y). A reading in the plume returns to surge at any time; the next loss restarts
//     the spiral or the cast from its own loss point. Neither ever gives up: the runner's budget
//     ends a run that does not reach the source.
// Decisions where the thesis is silent:
//   - The in-plume threshold. The thesis keeps "the highest 70 % (90 %) of the gas measurements of
//     the initial phase" as inside the plume. Until `calibration` readings of at least
//     `detection` have been seen, the threshold is `detection`; then it is fixed at
//     max(detection, the (1 - threshold) quantile of those readings), the quantile interpolated
//     linearly between order statistics (core's percentile). So threshold = 0.9 is the looser rule
//     (its 10 % quantile lies below the 70 % rule's 30 % quantile). The reading that completes
//     the calibration is judged against the new threshold.
//   - Goals are kept 0.05 m (at most half the tunnel's size) inside every wall, and never more
//     than `step` from the robot. A leg (Lévy target, spiral point, cast end) moves on when the
//     robot is within a tenth of a step of it; a clamped spiral or cast runs along the wall.
//   - Cast2d: every goal has z = altitude, and `step` bounds the move in the x-y plane (the
//     robot flies at that altitude); the surge uses the wind's x-y part.
#include <cstdint>
#include <random>
#include <vector>

#include "core/geometry.hpp"
#include "methods/method.hpp"

namespace plumekit::methods {

enum class CrosswindMode { Spiral3d, Cast2d };

struct CrosswindSearchOptions {
  CrosswindMode mode = CrosswindMode::Spiral3d;
  double step = 0.05;         // m per decision: 50 mm/s (thesis) x 1 s
  double levy_mu = 3.0;       // Eq. 17.1's exponent, thesis value
  double levy_min = 0.5;      // L_min, m, thesis value
  double levy_max = 4.0;      // the power law's draws are cut here (not in the thesis)
  double spiral_drift = 0.1;  // s_d of Eq. 17.3, m of radius per turn (not in the thesis)
  double cast = 0.43;         // D_cast, m (thesis, from Lochmatter)
  double threshold = 0.7;  // Table 17.1: the share of calibration readings in the plume, 0.7 or 0.9
  int calibration = 20;    // readings that set the in-plume threshold
  double detection = 5.0;  // concentration units: the lowest reading that counts as gas
  double altitude = 0.0;   // Cast2d only: the fixed z the robot flies at (the runner sets it)

  // OptionError naming "tunnel.search.<field>" for a value that is NaN or out of range.
  void validate() const;
};

// The tracker reads while it flies: each observation (Observation3) is the mean over its last
// decision interval, taken where the robot is at its end.
class CrosswindSearch : public LocalizationMethod3 {
 public:
  // OptionError for bad options or a Cast2d altitude outside the tunnel; InputError for a tunnel
  // that is not finite or has hi < lo.
  CrosswindSearch(const Box3& tunnel, const CrosswindSearchOptions& options, std::uint64_t seed);

  // InputError naming the field when a number is not finite or the gas reading is negative.
  void observe(const Observation3& o) override;
  // The next goal: at most `step` from `robot` and inside the tunnel (robot inside it).
  Move3 next(Vec3 robot) override;
  // "surge-spiral" or "surge-cast-2d" (the tunnel's --method names).
  std::string name() const override;
  // None: the run scores where it ends.
  std::optional<Vec3> estimate() const override { return std::nullopt; }
  // Never gives up: the runner's time limit ends a run that does not reach the source.
  std::string stopped_by() const override { return ""; }
  bool reads_while_moving() const override { return true; }
  std::string phase() const override;              // "levy", "surge", "spiral" or "cast"
  double threshold() const { return threshold_; }  // the in-plume threshold in use
  std::optional<double> plume_threshold() const override { return threshold_; }
  // Where the current leg leads (Lévy target, spiral point or cast end), for tests and pictures.
  Vec3 waypoint() const { return waypoint_; }
  Vec3 loss_point() const { return loss_; }  // the last loss point
  double spiral_t() const { return t_; }     // Eq. 17.3's t of the current spiral point
  bool calibrated() const { return calibrated_; }

 private:
  enum class Phase { Levy, Surge, Spiral, Cast };
  double uniform01();
  Vec3 clamp_inside(Vec3 p) const;
  Vec3 toward(Vec3 robot, Vec3 goal) const;  // at most a step, inside the tunnel
  bool arrived(Vec3 robot) const;
  void draw_levy_target(Vec3 robot);
  void advance_spiral();

  Box3 tunnel_, inner_;
  CrosswindSearchOptions options_;
  std::mt19937_64 rng_;
  Phase phase_ = Phase::Levy;
  double threshold_;
  bool calibrated_ = false;
  std::vector<double> calibration_readings_;
  Vec3 upwind_{-1.0, 0.0, 0.0};
  Vec3 waypoint_, loss_;
  bool has_waypoint_ = false;
  double t_ = 0.0;  // Eq. 17.3's spiral parameter
  int leg_ = 0;     // cast legs begun since the loss
};

}  // namespace plumekit::methods
