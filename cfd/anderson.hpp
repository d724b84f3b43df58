#pragma once
// Anderson acceleration (type II, Walker & Ni 2011) of a fixed-point
// iteration x <- x + s(x). Two iterations use it:
//  - the chord iteration s = -M^-1 F(x) with a stale Newton matrix M. Mixing
//    the last few steps is, for a linear problem, GMRES preconditioned by M:
//    the few modes where M and the current Jacobian differ most, which set the
//    chord iteration's rate, are removed in a few steps instead of decaying
//    geometrically;
//  - the lagged mixing-length eddy viscosity (eddy_viscosity.hpp), whose
//    relaxed updates otherwise settle slowly.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>

namespace plumekit::cfd {

class AndersonMixing {
 public:
  explicit AndersonMixing(int depth) : depth_(depth) {}

  // Forget the history (the fixed-point map changed: a new factorization).
  void reset() {
    count_ = 0;
    has_previous_ = false;
  }

  // Takes the plain step s at iterate x and turns it into the mixed step:
  // x + s is then the Anderson iterate. The history records x and the
  // plain s.
  // Returns whether the step was changed (there was a history to mix).
  bool mix(const Eigen::VectorXd& x, Eigen::VectorXd& s) {
    const Eigen::Index n = x.size();
    if (dx_.rows() != n) {
      dx_.resize(n, depth_);
      ds_.resize(n, depth_);
    }
    if (has_previous_) {
      const int k = next_;
      dx_.col(k) = x - x_previous_;
      ds_.col(k) = s - s_previous_;
      next_ = (next_ + 1) % depth_;
      count_ = std::min(count_ + 1, depth_);
    }
    x_previous_ = x;
    s_previous_ = s;
    has_previous_ = true;
    if (count_ == 0) return false;
    // gamma = argmin |s - dS gamma|, by the normal equations of the few
    // columns, with a small ridge against nearly dependent ones.
    const auto dS = ds_.leftCols(count_);
    Eigen::MatrixXd gram = dS.transpose() * dS;
    gram.diagonal().array() += 1e-12 * gram.diagonal().maxCoeff() + 1e-300;
    const Eigen::VectorXd gamma = gram.ldlt().solve(dS.transpose() * s);
    s -= (dx_.leftCols(count_) + dS) * gamma;
    return true;
  }

 private:
  int depth_;
  int count_ = 0, next_ = 0;
  bool has_previous_ = false;
  Eigen::MatrixXd dx_, ds_;
  Eigen::VectorXd x_previous_, s_previous_;
};

}  // namespace plumekit::cfd
