#include "methods/ste_method.hpp"

#include "methods/registry.hpp"

namespace plumekit::methods {

namespace {

methods::Move move_along(planner::PlanResult p) {
  methods::Move m;
  m.goal = p.goal;
  m.path = std::move(p.path);
  m.length = p.length;
  return m;
}

}  // namespace

void SteMethod::observe(const methods::Observation& o) {
  partial_.clear();
  if (passing_ != nullptr && !o.on_the_way.empty()) {
    std::vector<ste::PassingReading> readings;
    for (const methods::BasicPassing<Vec2>& r : o.on_the_way)
      readings.push_back({r.position, r.time_s, r.gas});
    partial_ = ste::partial_samples(readings, *passing_);
  }
  mission_.add(o.position, o.gas, shared_, partial_);
  shared_.clear();
}

methods::Move SteMethod::next(Vec2 robot) {
  return move_along(mission_.next(robot));
}

void SteMethod::share(const std::vector<Sample>& samples) {
  for (const Sample& s : samples)
    shared_.push_back({s.position, s.gas, s.weight});
}

std::vector<Teammate::Sample> SteMethod::passing_samples() const {
  std::vector<Sample> out;
  for (const ste::PartialSample& s : partial_)
    out.push_back({s.position, s.value, s.weight});
  return out;
}

methods::Move SteMethod::next_beside(Vec2 robot, const std::vector<Vec2>& virtual_points) {
  return move_along(mission_.next(robot, virtual_points));
}

std::optional<Vec2> SteMethod::estimate() const {
  if (mission_.samples() == 0) return std::nullopt;
  return mission_.posterior().expected_source();
}

// Built from the scenario's plume model, estimator and navigator (run/scenario.cpp).
MethodSpec ste_spec() {
  return {"ste",
          "source term estimation: Bayesian posterior over the source, infotaxis moves",
          "plumekit (ste/)",
          MethodTraits{true, RunEnd::OwnStopRule, true},
          {},
          {},
          [](const PlumeModelParts& parts) {
            return std::make_unique<SteMethod>(parts.estimator(), *parts.planner, *parts.navigator,
                                               *parts.stop, parts.passing);
          }};
}

}  // namespace plumekit::methods
