#pragma once
// Prandtl's mixing-length closure: nu_t = lm^2 |S|, |S| = sqrt(2 S_ij S_ij),
// lm = min(kappa d, lm_max), d the distance from a cell centre to the nearest
// no-slip surface (obstacles and walls; not the inlet or outlet). It is lagged:
// recomputed from the latest velocity before each Newton step, under-relaxed,
// and Anderson-accelerated over the previous updates.
#include <Eigen/Core>
#include <vector>

#include "cfd/anderson.hpp"
#include "cfd/options.hpp"
#include "cfd/staggered_grid.hpp"

namespace plumekit::cfd {

class EddyViscosity {
 public:
  EddyViscosity(const StaggeredGrid& grid, const FlowOptions& options);

  // Writes nu + nu_t per cell (nu in solid cells).
  void update(const double* x, std::vector<double>& nu_cell);
  // Whether the last update changed nu_t by less than 1e-6 relative.
  bool settled() const { return change_ < 1e-6; }
  double max_eddy_viscosity() const;
  const std::vector<double>& wall_distance() const { return distance_; }

 private:
  double face_value(int c, std::size_t f, const double* x) const;

  // Each update moves nu_t this fraction of the way to lm^2 |S|.
  static constexpr double kRelaxation = 0.5;
  // Updates are Anderson-mixed over this many previous ones.
  static constexpr int kAndersonDepth = 4;

  const StaggeredGrid& grid_;
  double nu_;
  std::vector<double> distance_, mixing_length_;
  Eigen::VectorXd nu_t_;
  AndersonMixing anderson_{kAndersonDepth};
  double change_ = 1.0;
};

}  // namespace plumekit::cfd
