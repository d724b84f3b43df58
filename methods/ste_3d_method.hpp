#pragma once
// Seed 004 ch. 11's 3-D source term estimation (ste/ste_3d.hpp) as a tunnel method: it stops to
// sample, adds each stop's mean reading and wind speed to its posterior, declares its expected
// source when the entropy falls below options.entropy_fraction of its maximum ("entropy") or
// when its sample budget is spent ("max_samples"), and else moves to the best of its 6 candidate
// goals.
#include <cstdint>
#include <optional>

#include "methods/method.hpp"
#include "ste/ste_3d.hpp"

namespace plumekit::methods {

class Ste3dMethod : public LocalizationMethod3 {
 public:
  // `tunnel`: the prior's box; goals stay `margin` inside its walls; `seed` seeds the chain.
  Ste3dMethod(const Box3& tunnel, const ste::Ste3dOptions& options, double margin,
              std::uint64_t seed);

  std::string name() const override { return "ste-3d"; }
  void observe(const Observation3& o) override;
  Move3 next(Vec3 robot) override;
  std::optional<Vec3> estimate() const override;
  std::string stopped_by() const override { return stopped_by_; }
  bool reads_while_moving() const override { return false; }
  std::string phase() const override { return "sample"; }
  const ste::Posterior3* posterior() const override;

 private:
  Box3 tunnel_;
  ste::Ste3dOptions options_;
  double margin_;
  ste::Ste3dEstimator estimator_;
  std::optional<ste::Posterior3> posterior_;
  std::string stopped_by_;
};

}  // namespace plumekit::methods
