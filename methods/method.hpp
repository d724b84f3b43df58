#pragma once
// One interface for every gas source localization method, in the spirit of OMPL's planners: a
// method reads what the robot's sensors report at a stop (gas, wind, pose, time) and says where
// to sample next and, when it has one, where it believes the source is. The run loop
// (run/method_run.hpp) drives it against the simulated world, plans the paths between stops
// around obstacles, and scores it; a robot driven by a user's own code can drive it the same way.
//
// The interface is one template over the space the robot moves in: Vec2 for a floor plan
// (LocalizationMethod), Vec3 for seed 004's wind tunnel (LocalizationMethod3: its 3-D STE and
// trackers), so that the floor's and the tunnel's methods are driven by the same loop.
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
struct Posterior;   // ste/posterior.hpp
struct Posterior3;  // ste/ste_3d.hpp
}  // namespace plumekit::ste

namespace plumekit::methods {

// A gas reading taken on the way between stops (the world's read_while_moving): where the robot
// recorded it, when (since the mission started, s) and what it read.
template <class P>
struct BasicPassing {
  P position;
  double time_s = 0.0;
  double gas = 0.0;
};

// What the sensors report for one stop (or, for a method that reads while it moves, for the last
// decision interval).
template <class P>
struct BasicObservation {
  P position;        // where the robot records the stop (with position noise)
  double gas = 0.0;  // mean gas reading over the stop, concentration units (>= 0)
  P wind;            // the anemometer's mean wind over the stop, m/s
  // Circular variance S0 = 1 - R of the stop's single wind directions (seed 000 App. A), in
  // [0, 1]: 0 for a steady wind.
  double wind_variance = 0.0;
  double time_s = 0.0;  // since the mission started, at the stop's end
  // The robot did not reach the goal it was sent to: an obstacle stopped it on its straight way
  // there (a method without a map, Move::straight).
  bool blocked = false;
  // The readings taken on the way here since the last stop, oldest first; empty when the robot
  // reads only at stops. A method that does not use them may ignore them.
  std::vector<BasicPassing<P>> on_the_way{};
};
using Observation = BasicObservation<Vec2>;
using Observation3 = BasicObservation<Vec3>;

// InputError naming `who` when a number of the observation (position, gas, wind, circular
// variance) is not finite: what a method's observe() refuses.
void check_observation(const Observation& o, const std::string& who);

// Where to go next. A method proposes a goal; the runner drives there along the planner's path
// (or straight when nothing is in the way), moving a goal that lies in an obstacle or outside the
// arena to the nearest reachable free point. The method learns where the robot actually arrived
// from the next observation's position.
template <class P>
struct BasicMove {
  P goal;
  // A collision-free path from the robot to `goal` that the method planned itself (STE plans
  // while it decides); empty: the runner plans one.
  std::vector<P> path;
  double length = 0.0;  // metres along `path`
  // A method without a map (seed 004 ch. 12's local framework): the robot drives straight to the
  // goal and stops where an obstacle blocks its way (after its avoidance manoeuvre), which the
  // next observation says (Observation::blocked). False: the runner plans around obstacles.
  bool straight = false;
  // A goal alone: the runner plans (or, in the tunnel, flies) the way.
  static BasicMove to(P goal) {
    BasicMove m;
    m.goal = goal;
    return m;
  }
};
using Move = BasicMove<Vec2>;
using Move3 = BasicMove<Vec3>;

// The area a method searches: the arena's rectangle, and its obstacles for methods that want them
// (the seeds' methods search an open rectangle F_{l,w}).
struct SearchArea {
  const Map* map = nullptr;  // must outlive the method
  double width() const { return map->width; }
  double height() const { return map->height; }
  bool contains(Vec2 p) const { return map->in_arena(p); }
  bool is_free(Vec2 p) const { return map->is_free(p); }
};

template <class P>
class BasicMethod {
 public:
  virtual ~BasicMethod() = default;
  // The --method name ("ste", "surge-cast", "pf-gradient", "surge-spiral", ...).
  virtual std::string name() const = 0;
  // Reads one stop. InputError for a position or reading that is not finite.
  virtual void observe(const BasicObservation<P>& o) = 0;
  // Where to sample next, seen from `robot` (the true position the robot drives from). Called
  // after observe() while !stopped().
  virtual BasicMove<P> next(P robot) = 0;
  // The current estimate of the source, when the method has one (a plume tracker has none: the
  // runner scores where it ends).
  virtual std::optional<P> estimate() const = 0;
  // Why the method stopped ("entropy", "max_samples", "declared", "lost", ...), or "" while it
  // goes on.
  virtual std::string stopped_by() const = 0;
  bool stopped() const { return !stopped_by().empty(); }
};

class Teammate;

// A method on a floor plan.
class LocalizationMethod : public BasicMethod<Vec2> {
 public:
  // The method as a member of a robot team (seed 004 ch. 13, run/team.hpp), or null for a method
  // that cannot work in one (its spec's traits.teams says which).
  virtual Teammate* as_teammate() { return nullptr; }
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

// What a method does in a robot team (seed 004 ch. 13) besides its own stops: it takes the samples
// its teammates send (cooperative and collaborative teams share every sample), and it can plan
// as if samples had been taken where its teammates are headed (collaborative teams).
class Teammate {
 public:
  virtual ~Teammate() = default;
  struct Sample {
    Vec2 position;
    double gas = 0.0;
    double weight = 1.0;  // below 1: readings on the way, worth that share of a stop's sample
  };
  // Teammates' samples, added before the next observation's own, in order.
  virtual void share(const std::vector<Sample>& samples) = 0;
  // What its last observation made of its readings on the way, to share (weights below 1).
  virtual std::vector<Sample> passing_samples() const { return {}; }
  // next(), planned as if samples had been taken at `virtual_points`, reading what its belief
  // predicts there: it does not plan to learn what its teammates are about to learn.
  virtual Move next_beside(Vec2 robot, const std::vector<Vec2>& virtual_points) = 0;
};

// A method in seed 004's wind tunnel (x downwind along it, y across, z up): it flies straight to
// its goals (the tunnel is empty).
class LocalizationMethod3 : public BasicMethod<Vec3> {
 public:
  // Whether it reads while it flies (a tracker: the mean over each decision interval) rather
  // than stopping to sample (STE's 5 s stops).
  virtual bool reads_while_moving() const = 0;
  // What it is doing, for the run's record: "sample" (STE), or a tracker's phase.
  virtual std::string phase() const = 0;
  // A tracker's in-plume threshold (a run succeeds inside the source's box while in the plume);
  // nullopt for a method that declares its source.
  virtual std::optional<double> plume_threshold() const { return std::nullopt; }
  // STE's posterior after the last observe(), or null.
  virtual const ste::Posterior3* posterior() const { return nullptr; }
};

}  // namespace plumekit::methods
