#include "methods/ste_3d_method.hpp"

#include <cmath>

#include "core/error.hpp"
#include "methods/registry.hpp"

namespace plumekit::methods {

Ste3dMethod::Ste3dMethod(const Box3& tunnel, const ste::Ste3dOptions& options, double margin,
                         std::uint64_t seed)
    : tunnel_(tunnel), options_(options), margin_(margin), estimator_(tunnel, options, seed) {}

void Ste3dMethod::observe(const Observation3& o) {
  estimator_.add(o.position, o.gas, norm(o.wind));
  posterior_ = estimator_.posterior();
  if (posterior_->entropy < options_.entropy_fraction * posterior_->max_entropy)
    stopped_by_ = "entropy";
  else if (estimator_.samples() >= options_.max_samples)
    stopped_by_ = "max_samples";
}

Move3 Ste3dMethod::next(Vec3 robot) {
  if (!posterior_) throw std::logic_error("Ste3dMethod::next before any observation");
  return Move3::to(ste::decide_3d(robot, estimator_, *posterior_, tunnel_, options_, margin_).goal);
}

std::optional<Vec3> Ste3dMethod::estimate() const {
  if (!posterior_) return std::nullopt;
  return posterior_->expected_source();
}

const ste::Posterior3* Ste3dMethod::posterior() const {
  return posterior_ ? &*posterior_ : nullptr;
}

TunnelMethodSpec ste_3d_spec() {
  return {"ste-3d",
          "3-D source term estimation",
          "seed 004 ch. 11",
          false,
          false,
          [](const TunnelMethodInputs& in) {
            return std::make_unique<Ste3dMethod>(in.tunnel, in.ste, in.margin, in.chain_seed);
          }};
}

}  // namespace plumekit::methods
