#include "planner/ompl_planner.hpp"

#include <atomic>
#include <chrono>
#include <mutex>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "core/error.hpp"
#include "planner/endpoints.hpp"

namespace plumekit::planner {

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// OMPL draws every planner's seed from one global generator, which can be
// seeded once, before its first use: runs are then repeatable in order.
constexpr std::uint_fast32_t kOmplSeed = 20211;

Vec2 to_vec(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return {v->values[0], v->values[1]};
}

// The motion validator: the same exact segment test the VG uses, so OMPL and
// the VG search exactly the same free space.
class ExactMotionValidator : public ob::MotionValidator {
 public:
  ExactMotionValidator(const ob::SpaceInformationPtr& si, const FreeSpace& space)
      : ob::MotionValidator(si), space_(space) {}

  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    const bool ok = free(to_vec(a), to_vec(b));
    (ok ? valid_ : invalid_)++;
    return ok;
  }

  bool checkMotion(const ob::State* a, const ob::State* b,
                   std::pair<ob::State*, double>& last_valid) const override {
    const Vec2 p = to_vec(a), q = to_vec(b);
    if (free(p, q)) {
      ++valid_;
      return true;
    }
    ++invalid_;
    // The last free point along the motion, by bisection.
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (free(p, p + mid * (q - p)) ? lo : hi) = mid;
    }
    if (last_valid.first) si_->getStateSpace()->interpolate(a, b, lo, last_valid.first);
    last_valid.second = lo;
    return false;
  }

 private:
  bool free(Vec2 p, Vec2 q) const {
    return space_.contains(p) && space_.contains(q) && space_.segment_free(p, q);
  }
  const FreeSpace& space_;
};

}  // namespace

OmplPlanner::OmplPlanner(const Map& map, const PlannerOptions& options, PlannerKind kind)
    : space_(map, options.margin, options.arc_segments), options_(options), kind_(kind) {
  if (kind != PlannerKind::RRTstar && kind != PlannerKind::PRMstar)
    throw InputError("planner: OmplPlanner runs rrtstar or prmstar, not " +
                     std::string(to_string(kind)));
  if (options.ompl_iterations < 1 || !(options.ompl_time_limit_s > 0.0))
    throw InputError(
        "planner: the OMPL budget (ompl_iterations, ompl_time_limit_s) must be positive");
  static std::once_flag once;
  std::call_once(once, [] {
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    ompl::RNG::setSeed(kOmplSeed);
  });
}

PlanResult OmplPlanner::plan(Vec2 start, Vec2 goal) const {
  PlanResult r;
  place_endpoints(space_, start, goal, r);
  if (r.start == r.goal) {
    r.path = {r.start, r.goal};
    return r;
  }
  const Map& map = space_.map();
  auto state_space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, 0.0);
  bounds.setHigh(0, map.width);
  bounds.setLow(1, 0.0);
  bounds.setHigh(1, map.height);
  state_space->setBounds(bounds);

  auto si = std::make_shared<ob::SpaceInformation>(state_space);
  si->setStateValidityChecker([this](const ob::State* s) { return space_.contains(to_vec(s)); });
  si->setMotionValidator(std::make_shared<ExactMotionValidator>(si, space_));
  si->setup();

  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> from(state_space), to(state_space);
  from[0] = r.start.x;
  from[1] = r.start.y;
  to[0] = r.goal.x;
  to[1] = r.goal.y;
  pdef->setStartAndGoalStates(from, to);
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
  // A threshold of 0 is never met: the planner refines for its whole budget.
  objective->setCostThreshold(ob::Cost(options_.ompl_target_length));
  pdef->setOptimizationObjective(objective);

  ob::PlannerPtr planner;
  if (kind_ == PlannerKind::RRTstar)
    planner = std::make_shared<og::RRTstar>(si);
  else
    planner = std::make_shared<og::PRMstar>(si);
  planner->setProblemDefinition(pdef);
  planner->setup();

  // The budget counts evaluations of the termination condition: once per
  // iteration for RRT*; PRM* also polls it from a helper thread every
  // millisecond, so its count (and result) can vary a little between runs.
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.ompl_time_limit_s);
  std::atomic<int> iterations{0};
  const int budget = options_.ompl_iterations;
  ob::PlannerTerminationCondition ptc(
      [&] { return ++iterations > budget || std::chrono::steady_clock::now() > deadline; });
  const ob::PlannerStatus status = planner->solve(ptc);
  if (status != ob::PlannerStatus::EXACT_SOLUTION || !pdef->hasExactSolution())
    throw_unreachable(space_, r);

  og::PathGeometric path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  if (options_.ompl_simplify) {
    og::PathSimplifier simplifier(si, pdef->getGoal(), objective);
    simplifier.simplifyMax(path);
  }
  r.path.clear();
  for (std::size_t k = 0; k < path.getStateCount(); ++k) {
    const Vec2 p = to_vec(path.getState(k));
    if (r.path.empty() || r.path.back() != p) r.path.push_back(p);
  }
  // OMPL's path starts at the start state and ends at the goal state itself
  // (the goal region is that one state); make sure before reporting it.
  if (r.path.empty() || r.path.front() != r.start) r.path.insert(r.path.begin(), r.start);
  if (r.path.back() != r.goal) {
    if (!space_.segment_free(r.path.back(), r.goal)) throw_unreachable(space_, r);
    r.path.push_back(r.goal);
  }
  for (std::size_t k = 1; k < r.path.size(); ++k)
    r.length += norm(r.path[k] - r.path[k - 1]);
  r.expanded = iterations.load();
  return r;
}

}  // namespace plumekit::planner
