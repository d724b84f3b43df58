#pragma once
// The thesis's open-field pseudo-Gaussian plume (section 7.1), in 2-D:
//
//   C = Q / (2 pi u sigma_y) exp(-(c - c_s)^2 / (2 sigma_y^2))  downwind of the source,
//   sigma_y = a d + b,                                         0 upwind,
//
// with d the downwind and c the crosswind distance from the source. The wind
// blows straight in from the inlet (its inward normal), at the inlet's mean
// speed u; obstacles are ignored. Parameters {x, y, Q, a, b}.
#include "ste/forward_model.hpp"

namespace plumekit::ste {

struct GaussianPlumeBounds {
  // Q spans the dataset's units: a release of 1000 (docs/design/dataset.md) gives
  // peaks of 1000-6000 near the source, i.e. Q of a few thousand here.
  double q_max = 10000.0;
  double a_min = 0.01, a_max = 1.0;  // sigma_y growth per metre downwind
  double b_min = 0.02, b_max = 1.0;  // sigma_y at the source, m
  // OptionError naming the field (docs/methods.md, "Options"); ste/options.cpp.
  void validate() const;
};

class GaussianPlume final : public ForwardModel {
 public:
  explicit GaussianPlume(const Map& map, const GaussianPlumeBounds& bounds = {});
  std::string name() const override { return "gaussian"; }
  const std::vector<Parameter>& parameters() const override { return parameters_; }
  std::vector<double> predict(const std::vector<double>& params,
                              const std::vector<Vec2>& points) const override;
  // One point, no allocation (the MH loop's hot path).
  double predict_at(const double* params, Vec2 p) const override;
  Vec2 wind_direction() const { return downwind_; }
  double wind_speed() const { return speed_; }

 private:
  std::vector<Parameter> parameters_;
  Vec2 downwind_;
  double speed_;
};

}  // namespace plumekit::ste
