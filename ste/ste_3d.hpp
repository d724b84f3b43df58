#pragma once
// The thesis's 3-D source term estimation (seed 004 ch. 11): the pseudo-Gaussian plume of Eq. 7.1,
//
//   C = Q / (2 pi u sigma^2) exp(-((y - y_s)^2 + (z - z_s)^2) / (2 sigma^2))  for d = x - x_s > 0,
//   sigma = a d + b (isotropic: sigma_y = sigma_z),                          0 upwind,
//
// its 6-D posterior over {x_s, y_s, z_s, Q, a, b} sampled by Metropolis-Hastings (the 2-D
// estimator's chain, mh_chain.hpp), and navigation by 6 candidate moves, one axis at a time (ch.
// 7.3: "4 candidates in 2D and 6 in 3D"), V = alpha V_KLD + (1 - alpha) V_MAP with the MAP of ch.
// 11 (the ch. 13 inverse-distance target is a later, 2-D addition). The wind blows along the
// tunnel's +x at the anemometer's mean speed. The entropy is that of the (x, y, z) marginal on
// bins of 0.5 x 0.2 x 0.2 m (the 2-D bins, with z as fine as y), and the stopping rule the 2-D
// one: below 2 % of its maximum, or the sample budget.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "ste/gaussian_plume.hpp"
#include "ste/mh_estimator.hpp"
#include "ste/posterior.hpp"
#include "ste/stop_rule.hpp"

namespace plumekit::ste {

struct Ste3dOptions {
  // sigma_M 30 and sigma_D 0 (the thesis in simulation), plus a model error of half the predicted
  // concentration (sigma_rel 0.5; not the thesis's): the tunnel's 5 s means 4 m behind the source
  // read thousands and scatter in proportion, and with the constant error alone the chain
  // freezes on its first good state and declares after a few samples, metres off (docs/methods.md,
  // "The 3-D tunnel": median error 2.9 m against 0.2 m).
  LikelihoodOptions likelihood{30.0, 0.0, 0.5, 0.0};
  MhOptions mh;
  GaussianPlumeBounds bounds;
  double bin_x = 0.5, bin_y = 0.2, bin_z = 0.2;  // m
  double step = 0.5;                             // m, the candidate moves' length
  double alpha = 0.5;                            // weight of the KL move against the MAP move
  double entropy_fraction = 0.02;
  // Not in the thesis for simulation (50 in its tunnel); one more dimension to settle, so 80.
  int max_samples = 80;
  // OptionError naming "tunnel.ste.<field>" (the nested options their own fields).
  void validate() const;
};

// Eq. 7.1 at p for m = {x_s, y_s, z_s, Q, a, b} in a wind of `speed` m/s along +x.
double gaussian_plume_3d(const double* m, Vec3 p, double speed);

struct Posterior3 {
  std::vector<double> expected;             // of {x_s, y_s, z_s, Q, a, b}: the declared estimate
  Vec3 map;                                 // the most probable source visited (navigation)
  std::vector<double> marginal;             // the (x, y, z) marginal on the bins (sums to 1)
  int nx = 0, ny = 0, nz = 0;               // its bins along x, y, z; bin (i, j, k) is
                                            // marginal[(k * ny + j) * nx + i]
  double entropy = 0.0, max_entropy = 0.0;  // nats
  Vec3 expected_source() const { return {expected.at(0), expected.at(1), expected.at(2)}; }
};

class Ste3dEstimator {
 public:
  // `tunnel`: the prior's box for the source.
  Ste3dEstimator(const Box3& tunnel, const Ste3dOptions& options, std::uint64_t seed);
  // A sample: the mean concentration at p, and the anemometer's mean wind speed there.
  void add(Vec3 p, double value, double wind_speed);
  int samples() const { return static_cast<int>(points_.size()); }
  // The posterior given all samples so far (the chain continues from where it stopped).
  Posterior3 posterior();
  // Eq. 7.6: KL(P || Q), Q the posterior after a sample at p reading what the expected parameters
  // predict there.
  double information_gain(Vec3 p, const Posterior3& current) const;
  double predicted_reading(Vec3 p, const Posterior3& current) const;
  const std::vector<Parameter>& parameters() const { return parameters_; }
  int bin_count() const { return nx_ * ny_ * nz_; }

 private:
  double log_posterior(const std::vector<double>& m) const;
  int bin_of(const std::vector<double>& m) const;
  double speed() const;  // ū: the mean of the samples' wind speeds

  Box3 tunnel_;
  Ste3dOptions options_;
  std::vector<Parameter> parameters_;
  int nx_, ny_, nz_;
  std::mt19937_64 rng_;
  std::vector<Vec3> points_;
  std::vector<double> values_, speeds_;
  std::vector<double> state_;
  std::vector<std::vector<double>> chain_;
  double u_ = 0.0;  // the speed the chain ran with
};

// One decision (ch. 7.3 in 3-D).
struct Decision3 {
  Vec3 goal, kld_target, source_target;
  std::vector<Vec3> candidates;  // the moves that stay in the tunnel
  std::vector<double> gains;     // their KL divergences, nats
};
// `margin`: goals stay this far inside the tunnel's walls.
Decision3 decide_3d(Vec3 robot, const Ste3dEstimator& estimator, const Posterior3& posterior,
                    const Box3& tunnel, const Ste3dOptions& options, double margin);

}  // namespace plumekit::ste
