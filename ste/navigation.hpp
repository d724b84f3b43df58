#pragma once
// Where to sample next (thesis sections 7.3 and 13.2).
//
// Candidates: a lattice of `step`-metre moves around the robot (the thesis
// code's 3 x 3 lattice of 0.5 m steps, the robot's own cell left out);
// candidates outside the inflated free space, or in a piece of it the robot
// cannot reach, are dropped. Each is scored by the KL divergence between the
// current posterior and the one predicted after sampling there: for the reading
// the expected source predicts (the thesis's eq. 7.6), or averaged over the
// readings of sources drawn from the posterior (the expected information gain,
// the default).
//
//   V = alpha (best candidate - robot) + (1 - alpha) (target - robot)
//
// The target is the maximum of beta P_M(x, y) + (1 - beta) D_I(x, y) over the
// thesis's posterior bins (0.5 x 0.2 m; section 13.2, `enhanced`): on a finer
// grid D_I would always pick the cell next to the robot, D_I the normalised inverse
// distance from the robot (0 on its own cell); or the MAP (section 7.3). A
// goal that falls outside free space is moved to the nearest free point.
//
// On a floor of rooms the lattice is not enough: a robot that reads nothing
// scores every nearby move alike and stays in its room. With `candidates =
// Floor` the robot also scores goals spread over the whole reachable floor (a
// lattice of `floor_spacing` metres, on a roadmap of the free space) by expected
// information per second of mission, gain / (travel time + sampling time), and
// leaves the lattice's decision for the best goal when it offers clearly more
// than the best move (docs/validation.md, "Floors"). There the lattice's moves lie on
// a fixed grid (around its point nearest the robot), so that a plume model can
// remember their readings from one decision to the next.
#include <memory>
#include <vector>

#include "planner/free_space.hpp"
#include "planner/grid_roadmap.hpp"
#include "ste/posterior.hpp"

namespace plumekit::ste {

struct NavigationOptions {
  double step = 0.5;  // m, lattice spacing
  // Moves of up to `lattice` steps per axis: (2 lattice + 1)^2 - 1 candidates. The thesis code's
  // is 1 (3 x 3); 2 (5 x 5) lets the robot leave a region where nothing is read
  // (docs/design/ste.md).
  int lattice = 2;
  double alpha = 0.5;    // weight of the KL move against the source move
  double beta = 0.75;    // weight of the marginal against the inverse distance
  bool enhanced = true;  // section 13.2's combined target; false: the MAP
  // The candidates' score: the thesis's KL divergence after the reading predicted for the
  // expected source (eq. 7.6), or the expected information gain over sources drawn from the
  // posterior (Estimator::expected_information_gain).
  enum class Reward { Kl, ExpectedGain } reward = Reward::ExpectedGain;
  // Where candidates come from: the lattice of moves around the robot (the thesis's), or also
  // goals spread over the whole reachable floor, ranked by expected gain per second (Floor).
  // Auto: Floor on an arena larger than the thesis's 10 x 4 m, Lattice on one within it
  // (Scenario resolves it; resolve_candidates).
  enum class Candidates { Lattice, Floor, Auto } candidates = Candidates::Auto;
  double floor_spacing = 1.0;  // m, between the floor's goals (Floor)
  // Floor: each goal's expected gain sums over at most this many of the posterior's cells (drawn
  // from it), so that a decision over hundreds of goals stays within 0.1 s.
  int floor_gain_cells = 512;
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};

struct Decision {
  Vec2 goal;
  Vec2 kld_target, source_target;
  std::vector<Vec2> candidates;  // the ones kept
  std::vector<double> gains;     // their KL divergences, nats
};

// What a move costs in mission time (Floor candidates): travel at `speed`, then a sample.
struct MissionPace {
  double speed = 0.5;     // m/s
  double sample_s = 5.0;  // s per sample
  // The share of a stop's sample each metre of travel reads (readings on the way, issue 47:
  // 1 / (speed sample_s)); 0: the robot reads only at stops. With it a floor goal is scored by
  // its path too: the gains of the floor goals its roadmap path passes, each worth this share of
  // a stop per metre of path it stands for (floor_spacing), are added to the goal's own.
  double passing_weight_per_m = 0.0;
};

class Navigator {
 public:
  // `bins`: where P_M and D_I are combined (the posterior bins).
  Navigator(const planner::FreeSpace& space, const GridShape& bins,
            const NavigationOptions& options, const MissionPace& pace = {});
  ~Navigator();
  Decision decide(Vec2 robot, const Estimator& estimator, const Posterior& posterior) const;
  const NavigationOptions& options() const { return options_; }
  // The floor's goals (Floor candidates; empty otherwise): fixed points, so a plume model can
  // tabulate its readings there once per map.
  const std::vector<Vec2>& floor_goals() const { return floor_goals_; }

 private:
  // max_cells: the moves' gain budget (0: every cell of the posterior, the thesis's lattice).
  Decision decide_on_lattice(Vec2 robot, const Estimator& estimator, const Posterior& posterior,
                             int max_cells) const;
  Decision decide_on_floor(Vec2 robot, const Estimator& estimator,
                           const Posterior& posterior) const;
  // The lattice's moves around the robot that stay in its piece of free space. Floor: around
  // the point of a fixed grid (the roadmap's, `step` apart) nearest the robot.
  std::vector<Vec2> lattice_moves(Vec2 robot) const;
  // max_cells: the estimator's budget per point (0: exact).
  std::vector<double> gains(const std::vector<Vec2>& points, const Estimator& estimator,
                            const Posterior& posterior, int max_cells) const;

  const planner::FreeSpace& space_;
  GridShape bins_;
  NavigationOptions options_;
  MissionPace pace_;
  std::vector<int> region_;  // per bin: the free-space piece its centre lies in, or -1
  std::unique_ptr<planner::GridRoadmap> roadmap_;  // Floor: travel distances
  std::vector<Vec2> floor_goals_;
  std::vector<int> floor_goal_node_;  // per floor goal: its roadmap node
};

// Per goal c (at roadmap node node[c], with its gain gain[c]): the gains of the other goals on its
// roadmap path from the robot (`previous`: each node's predecessor, -1 at the root), each times
// `weight`, the share of a stop the path's readings there are worth (path scoring, issue 47). An
// upper bound of the path's information: gains of samples taken one after another do not add.
std::vector<double> gains_along_paths(const std::vector<int>& node, const std::vector<double>& gain,
                                      const std::vector<int>& previous, double weight);

const char* to_string(NavigationOptions::Reward reward);
// "kl", "expected"; OptionError on ste.navigation.reward otherwise.
NavigationOptions::Reward parse_reward(const std::string& name);
const char* to_string(NavigationOptions::Candidates candidates);
// "lattice", "floor", "auto"; OptionError on ste.navigation.candidates otherwise.
NavigationOptions::Candidates parse_candidates(const std::string& name);
// `candidates` with Auto resolved for `map`: Floor when either side of the arena exceeds the
// thesis's 10 x 4 m (in either orientation), Lattice otherwise. On the thesis's arenas the
// lattice's 0.5 m moves and the pull to the posterior's peak do best; on a larger floor, goals
// over the whole floor (docs/validation.md, "Floors").
NavigationOptions::Candidates resolve_candidates(NavigationOptions::Candidates candidates,
                                                 const Map& map);

}  // namespace plumekit::ste
