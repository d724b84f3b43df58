#pragma once
// One interface for every gas source localization method, in the spirit of OMPL's planners: a
// method reads what the robot's sensors report at a stop (gas, wind, pose, time) and says where
// to sample next and, when it has one, where it believes the source is. The runner
// (run/method_run.hpp) drives it against the simulated world, plans the paths between stops
// around obstacles, and scores it; a robot driven by a user's own code can drive it the same way.
//
// Conventions: arena frame (metres, x right, y up); a wind vector points where the air moves to
// (downwind); "upwind" is minus the wind.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::ste {
struct Posterior;  // ste/posterior.hpp
}

namespace plumekit::methods {

// What the sensors report for one stop.
struct Observation {
  Vec2 position;     // where the robot records the stop (with position noise)
  double gas = 0.0;  // mean gas reading over the stop, concentration units (>= 0)
  Vec2 wind;         // the anemometer's mean wind over the stop, m/s
  // Circular variance S0 = 1 - R of the stop's single wind directions (seed 000 App. A), in
  // [0, 1]: 0 for a steady wind.
  double wind_variance = 0.0;
  double time_s = 0.0;  // since the mission started, at the stop's end
  // The robot did not reach the goal it was sent to: an obstacle stopped it on its straight way
  // there (a method without a map, Move::straight).
  bool blocked = false;
};

// InputError naming `who` when a number of the observation (position, gas, wind, circular
// variance) is not finite: what a method's observe() refuses.
void check_observation(const Observation& o, const std::string& who);

// Where to go next. A method proposes a goal; the runner drives there along the planner's path
// (or straight when nothing is in the way), moving a goal that lies in an obstacle or outside the
// arena to the nearest reachable free point. The method learns where the robot actually arrived
// from the next observation's position.
struct Move {
  Vec2 goal;
  // A collision-free path from the robot to `goal` that the method planned itself (STE plans
  // while it decides); empty: the runner plans one.
  std::vector<Vec2> path;
  double length = 0.0;  // metres along `path`
  // A method without a map (seed 004 ch. 12's local framework): the robot drives straight to the
  // goal and stops where an obstacle blocks its way (after its avoidance manoeuvre), which the
  // next observation says (Observation::blocked). False: the runner plans around obstacles.
  bool straight = false;
};

// The area a method searches: the arena's rectangle, and its obstacles for methods that want them
// (the seeds' methods search an open rectangle F_{l,w}).
struct SearchArea {
  const Map* map = nullptr;  // must outlive the method
  double width() const { return map->width; }
  double height() const { return map->height; }
  bool contains(Vec2 p) const { return map->in_arena(p); }
  bool is_free(Vec2 p) const { return map->is_free(p); }
};

class LocalizationMethod {
 public:
  virtual ~LocalizationMethod() = default;
  // The --method name ("ste", "surge-cast", "pf-gradient", ...).
  virtual std::string name() const = 0;
  // Reads one stop. InputError for a position or reading that is not finite.
  virtual void observe(const Observation& o) = 0;
  // Where to sample next, seen from `robot` (the true position the robot drives from). Called
  // after observe() while !stopped().
  virtual Move next(Vec2 robot) = 0;
  // The current estimate of the source, when the method has one (a plume tracker has none: the
  // runner scores where it ends).
  virtual std::optional<Vec2> estimate() const = 0;
  // Why the method stopped ("entropy", "max_samples", "declared", "lost", ...), or "" while it
  // goes on.
  virtual std::string stopped_by() const = 0;
  bool stopped() const { return !stopped_by().empty(); }

  // The method's picture of its belief, for the run's record and pictures, so that the runner
  // needs no knowledge of any method. Its posterior after the last observe() (STE's), or null
  // for a method that holds none.
  virtual const ste::Posterior* posterior() const { return nullptr; }
  // Its belief over `map`'s arena at the run's end (the particle filter's weights binned on
  // 0.1 m cells), or nullopt.
  virtual std::optional<Grid<double>> belief_map(const Map& map) const {
    (void)map;
    return std::nullopt;
  }
};

}  // namespace plumekit::methods
