#include "methods/ste_method.hpp"

#include "methods/registry.hpp"

namespace plumekit::methods {

methods::Move SteMethod::next(Vec2 robot) {
  planner::PlanResult p = mission_.next(robot);
  methods::Move m;
  m.goal = p.goal;
  m.path = std::move(p.path);
  m.length = p.length;
  return m;
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
          MethodTraits{true, RunEnd::OwnStopRule},
          {},
          {},
          [](const PlumeModelParts& parts) {
            return std::make_unique<SteMethod>(parts.estimator(), *parts.planner, *parts.navigator,
                                               *parts.stop);
          }};
}

}  // namespace plumekit::methods
