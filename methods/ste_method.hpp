#pragma once
// plumekit's Bayesian source term estimation as one localization method among the others
// (methods/method.hpp): a Mission (the estimator, the information-driven navigator and the stop
// rule) behind the common interface. It plans its own paths while it decides.
#include <memory>

#include "methods/method.hpp"
#include "ste/mission.hpp"

namespace plumekit::methods {

class SteMethod : public methods::LocalizationMethod, public Teammate {
 public:
  // Owns its estimator (run/scenario.cpp builds it for the map, the registry makes the method);
  // keeps references to the rest, which must outlive the method.
  // `passing` (null: ignore them) says how the readings on the way enter the posterior.
  SteMethod(std::unique_ptr<ste::Estimator> estimator, const planner::Planner& planner,
            const ste::Navigator& navigator, const ste::StopOptions& stop,
            const ste::PassingOptions* passing = nullptr)
      : estimator_(std::move(estimator)),
        mission_(*estimator_, planner, navigator, stop),
        passing_(passing) {}

  std::string name() const override { return "ste"; }
  // The stop's sample after the teammates' shared since the last and its own readings on the way
  // (one posterior update).
  void observe(const methods::Observation& o) override;
  // The partial samples the last observe() made of the readings on the way, for teammates.
  const std::vector<ste::PartialSample>& last_partial_samples() const { return partial_; }
  methods::Move next(Vec2 robot) override;
  // The posterior's expected value, once there is a sample.
  std::optional<Vec2> estimate() const override;
  std::string stopped_by() const override { return mission_.stopped_by(); }

  const ste::Mission& mission() const { return mission_; }
  const ste::Posterior* posterior() const override { return &mission_.posterior(); }

  Teammate* as_teammate() override { return this; }
  void share(const std::vector<Sample>& samples) override;
  std::vector<Sample> passing_samples() const override;
  methods::Move next_beside(Vec2 robot, const std::vector<Vec2>& virtual_points) override;

 private:
  std::unique_ptr<ste::Estimator> estimator_;  // declared before mission_, which refers to it
  ste::Mission mission_;
  std::vector<ste::Mission::Sample> shared_;  // teammates' samples not yet added
  const ste::PassingOptions* passing_;
  std::vector<ste::PartialSample> partial_;  // of the last observe()
};

}  // namespace plumekit::methods
