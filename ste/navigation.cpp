#include "ste/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace plumekit::ste {

namespace {

// The roadmap under the floor's goals is this much finer than they are spread, so that doors and
// corridors a little wider than the planner's margin still carry a path.
constexpr double kRoadmapCell = 0.25;  // m, at most
// Floor goals this close to the robot are its own position, not a move.
constexpr double kSamePlace = 0.25;  // m
// The robot leaves its lattice's moves for a floor goal that offers this many times their best
// expected gain per second.
constexpr double kLeaveFactor = 2.0;

}  // namespace

Navigator::Navigator(const planner::FreeSpace& space, const GridShape& bins,
                     const NavigationOptions& options, const MissionPace& pace)
    : space_(space), bins_(bins), options_(options), pace_(pace), region_(bins.size(), -1) {
  options.validate();
  for (int j = 0; j < bins.ny; ++j)
    for (int i = 0; i < bins.nx; ++i)
      region_[bins.index(i, j)] = space.region_of(bins.centre(i, j));
  if (options.candidates != NavigationOptions::Candidates::Floor) return;
  const int stride = std::max(1, static_cast<int>(std::ceil(options.floor_spacing / kRoadmapCell)));
  roadmap_ = std::make_unique<planner::GridRoadmap>(space, options.floor_spacing / stride);
  for (std::size_t k = 0; k < roadmap_->size(); ++k)
    if (roadmap_->column(k) % stride == stride / 2 && roadmap_->row(k) % stride == stride / 2) {
      floor_goals_.push_back(roadmap_->node(k));
      floor_goal_node_.push_back(static_cast<int>(k));
    }
}

Navigator::~Navigator() = default;

std::vector<double> Navigator::gains(const std::vector<Vec2>& points, const Estimator& estimator,
                                     const Posterior& posterior, int max_cells) const {
  if (options_.reward == NavigationOptions::Reward::ExpectedGain)
    return estimator.expected_information_gains(points, posterior, max_cells);
  std::vector<double> g;
  for (const Vec2& p : points)
    g.push_back(estimator.information_gain(p, posterior));
  return g;
}

std::vector<Vec2> Navigator::lattice_moves(Vec2 robot) const {
  const int home = space_.region_of(robot);
  std::vector<Vec2> moves;
  const int n = options_.lattice;
  const double step = options_.step;
  // Floor: around the fixed grid's point nearest the robot, so that the next decision finds
  // most of its moves' readings remembered (CachedReadings). The grid is the roadmap's, so
  // with the default spacings every floor goal is one of its points.
  Vec2 origin = robot;
  int ci = 0, cj = 0;
  if (roadmap_) {
    origin = roadmap_->origin();
    ci = static_cast<int>(std::lround((robot.x - origin.x) / step));
    cj = static_cast<int>(std::lround((robot.y - origin.y) / step));
  }
  for (int dj = -n; dj <= n; ++dj)
    for (int di = -n; di <= n; ++di) {
      const Vec2 c{origin.x + (ci + di) * step, origin.y + (cj + dj) * step};
      if ((di == 0 && dj == 0) || !space_.contains(c) || space_.region_of(c) != home) continue;
      moves.push_back(c);
    }
  return moves;
}

Decision Navigator::decide(Vec2 robot, const Estimator& estimator,
                           const Posterior& posterior) const {
  return roadmap_ ? decide_on_floor(robot, estimator, posterior)
                  : decide_on_lattice(robot, estimator, posterior, 0);
}

Decision Navigator::decide_on_floor(Vec2 robot, const Estimator& estimator,
                                    const Posterior& posterior) const {
  // The thesis's decision first: its moves, and its pull towards the posterior's peak. Its moves
  // are scored on the floor goals' budget of cells: over every cell of a building's posterior
  // they took most of a decision.
  Decision d = decide_on_lattice(robot, estimator, posterior, options_.floor_gain_cells);
  // Expected gain per second of mission: travel, then the sample.
  auto rate = [&](double gain, double travel) {
    return gain / (travel / pace_.speed + pace_.sample_s);
  };
  double local_rate = 0.0;
  for (std::size_t c = 0; c < d.candidates.size(); ++c)
    local_rate = std::max(local_rate, rate(d.gains[c], norm(d.candidates[c] - robot)));
  // The floor's goals, reached along the roadmap.
  std::vector<Vec2> goals;
  std::vector<double> travel;
  std::vector<int> node, previous;
  const std::vector<double> roadmap = roadmap_->distances_from(robot, &previous);
  for (std::size_t g = 0; g < floor_goals_.size(); ++g) {
    const double t = roadmap[floor_goal_node_[g]];
    if (t == planner::GridRoadmap::kUnreachable || norm(floor_goals_[g] - robot) < kSamePlace)
      continue;
    goals.push_back(floor_goals_[g]);
    travel.push_back(t);
    node.push_back(floor_goal_node_[g]);
  }
  const std::vector<double> g = gains(goals, estimator, posterior, options_.floor_gain_cells);
  const std::vector<double> on_the_way = gains_along_paths(
      node, g, previous, std::min(1.0, pace_.passing_weight_per_m * options_.floor_spacing));
  double best = 0.0;
  Vec2 away = robot;
  for (std::size_t c = 0; c < goals.size(); ++c) {
    const double r = rate(g[c] + on_the_way[c], travel[c]);
    if (r > best) best = r, away = goals[c];
  }
  d.candidates.insert(d.candidates.end(), goals.begin(), goals.end());
  d.gains.insert(d.gains.end(), g.begin(), g.end());
  // Leave the neighbourhood only for clearly more information per second than it offers.
  if (best > kLeaveFactor * local_rate) d.kld_target = d.source_target = d.goal = away;
  return d;
}

Decision Navigator::decide_on_lattice(Vec2 robot, const Estimator& estimator,
                                      const Posterior& posterior, int max_cells) const {
  Decision d;
  const int home = space_.region_of(robot);
  // V_KLD: the most informative reachable candidate.
  d.candidates = lattice_moves(robot);
  d.gains = gains(d.candidates, estimator, posterior, max_cells);
  double best = -1.0;
  d.kld_target = robot;
  for (std::size_t c = 0; c < d.candidates.size(); ++c)
    if (d.gains[c] > best) best = d.gains[c], d.kld_target = d.candidates[c];

  // V_source: the MAP, or the best of beta P_M + (1 - beta) D_I.
  d.source_target = posterior.map;
  if (options_.enhanced) {
    const GridShape& g = bins_;
    // P_M on the bins.
    std::vector<double> pm(g.size(), 0.0);
    const GridShape& m = posterior.marginal.shape;
    for (int j = 0; j < m.ny; ++j)
      for (int i = 0; i < m.nx; ++i) {
        const Vec2 c = m.centre(i, j);
        pm[g.index(std::clamp(static_cast<int>(c.x / g.dx()), 0, g.nx - 1),
                   std::clamp(static_cast<int>(c.y / g.dy()), 0, g.ny - 1))] +=
            posterior.marginal(i, j);
      }
    std::vector<double> inv(g.size(), 0.0);
    double inv_sum = 0.0;
    const int ri = static_cast<int>(robot.x / g.dx()), rj = static_cast<int>(robot.y / g.dy());
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        if (region_[k] != home || (i == ri && j == rj)) continue;
        inv[k] = 1.0 / std::max(1e-9, norm(g.centre(i, j) - robot));
        inv_sum += inv[k];
      }
    double top = -1.0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        if (region_[k] != home) continue;
        const double v = options_.beta * pm[k] +
                         (1.0 - options_.beta) * (inv_sum > 0.0 ? inv[k] / inv_sum : 0.0);
        if (v > top) top = v, d.source_target = g.centre(i, j);
      }
  }

  const double a = options_.alpha;
  Vec2 goal = robot + a * (d.kld_target - robot) + (1.0 - a) * (d.source_target - robot);
  if (!space_.contains(goal)) goal = space_.nearest_free(goal);
  if (space_.region_of(goal) != home) goal = d.candidates.empty() ? robot : d.kld_target;
  d.goal = goal;
  return d;
}

std::vector<double> gains_along_paths(const std::vector<int>& node, const std::vector<double>& gain,
                                      const std::vector<int>& previous, double weight) {
  std::vector<double> sums(node.size(), 0.0);
  if (weight <= 0.0) return sums;
  std::vector<double> at(previous.size(), 0.0);  // per roadmap node: its goal's gain
  for (std::size_t c = 0; c < node.size(); ++c)
    at[static_cast<std::size_t>(node[c])] = gain[c];
  for (std::size_t c = 0; c < node.size(); ++c)
    for (int k = previous[static_cast<std::size_t>(node[c])]; k >= 0;
         k = previous[static_cast<std::size_t>(k)])
      sums[c] += weight * at[static_cast<std::size_t>(k)];
  return sums;
}

const char* to_string(NavigationOptions::Reward reward) {
  return reward == NavigationOptions::Reward::Kl ? "kl" : "expected";
}

NavigationOptions::Reward parse_reward(const std::string& name) {
  if (name == "kl") return NavigationOptions::Reward::Kl;
  if (name == "expected") return NavigationOptions::Reward::ExpectedGain;
  throw OptionError("ste.navigation.reward", "unknown reward '" + name + "' (kl or expected)");
}

const char* to_string(NavigationOptions::Candidates candidates) {
  switch (candidates) {
    case NavigationOptions::Candidates::Lattice:
      return "lattice";
    case NavigationOptions::Candidates::Floor:
      return "floor";
    case NavigationOptions::Candidates::Auto:
      return "auto";
  }
  return "?";
}

NavigationOptions::Candidates parse_candidates(const std::string& name) {
  if (name == "lattice") return NavigationOptions::Candidates::Lattice;
  if (name == "floor") return NavigationOptions::Candidates::Floor;
  if (name == "auto") return NavigationOptions::Candidates::Auto;
  throw OptionError("ste.navigation.candidates",
                    "unknown candidates '" + name + "' (lattice, floor or auto)");
}

NavigationOptions::Candidates resolve_candidates(NavigationOptions::Candidates candidates,
                                                 const Map& map) {
  if (candidates != NavigationOptions::Candidates::Auto) return candidates;
  const double long_side = std::max(map.width, map.height);
  const double short_side = std::min(map.width, map.height);
  const double eps = map.round_off();
  return long_side > 10.0 + eps || short_side > 4.0 + eps ? NavigationOptions::Candidates::Floor
                                                          : NavigationOptions::Candidates::Lattice;
}

}  // namespace plumekit::ste
