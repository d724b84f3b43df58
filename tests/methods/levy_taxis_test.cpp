// Adaptive Lévy taxis (seed 004 ch. 16): the move-length power law, the wrapped Cauchy turns and
// their adaptation to the change of the reading, each against its closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "methods/levy_taxis.hpp"

namespace plumekit::methods {
namespace {

constexpr double kPiHere = 3.141592653589793;

// Eq. 16.1 is the inverse of P(M > x) = (x / L_min)^(1 - mu): the share of a fine grid of u whose
// move exceeds x is that probability, up to the cut at max_move.
TEST(LevyTaxis, MoveLengthsFollowThePowerLawAndStopAtTheLongestMove) {
  const double mu = 2.0, lo = 0.1, hi = 2.0;
  const int n = 100000;
  for (double x : {0.15, 0.3, 1.0, 1.9}) {
    int longer = 0;
    for (int k = 0; k < n; ++k)
      longer += levy_move_length((k + 0.5) / n, mu, lo, hi) > x;
    EXPECT_NEAR(static_cast<double>(longer) / n, std::pow(x / lo, 1.0 - mu), 1e-4) << x;
  }
  EXPECT_DOUBLE_EQ(levy_move_length(1.0, mu, lo, hi), lo);   // the shortest move
  EXPECT_DOUBLE_EQ(levy_move_length(1e-9, mu, lo, hi), hi);  // cut
  EXPECT_DOUBLE_EQ(levy_move_length(0.0, mu, lo, hi), hi);
  // A steeper law (mu near 3) keeps moves short; a flat one (near 1) makes them long.
  EXPECT_LT(levy_move_length(0.5, 2.9, lo, hi), levy_move_length(0.5, 1.1, lo, hi));
}

// Eq. 16.2 is the wrapped Cauchy's inverse distribution function: its mean resultant length
// E[cos T] is gamma, its sine mean 0; gamma = 0 is uniform on the circle, gamma = 1 no turn.
TEST(LevyTaxis, TurnsAreWrappedCauchyOfMeanResultantLengthGamma) {
  const int n = 200000;
  for (double gamma : {0.0, 0.3, 0.6, 0.9}) {
    double c = 0.0, s = 0.0;
    int in_quarter = 0;
    for (int k = 0; k < n; ++k) {
      const double t = wrapped_cauchy_turn((k + 0.5) / n, gamma);
      ASSERT_LE(std::abs(t), kPiHere + 1e-12);
      c += std::cos(t) / n;
      s += std::sin(t) / n;
      in_quarter += std::abs(t) <= kPiHere / 4;
    }
    EXPECT_NEAR(c, gamma, 1e-3) << gamma;
    EXPECT_NEAR(s, 0.0, 1e-9) << gamma;
    // P(|T| <= a) = (2 / pi) atan((1 + gamma) / (1 - gamma) tan(a / 2)) for the wrapped Cauchy.
    const double p = 2.0 / kPiHere * std::atan((1 + gamma) / (1 - gamma) * std::tan(kPiHere / 8));
    EXPECT_NEAR(static_cast<double>(in_quarter) / n, p, 1e-4) << gamma;
  }
  for (double u : {0.01, 0.3, 0.77})
    EXPECT_DOUBLE_EQ(wrapped_cauchy_turn(u, 1.0), 0.0);
}

// Eqs. 16.3: no change explores (mu_max, gamma_min), a change of theta or more exploits
// (mu_min, gamma_max), linear between, whatever the sign.
TEST(LevyTaxis, TheShapeFollowsTheChangeOfTheReading) {
  LevyTaxisOptions o;
  o.gradient_threshold = 100.0;
  LevyShape s = adapt_levy_shape(0.0, o);
  EXPECT_DOUBLE_EQ(s.mu, 2.9);
  EXPECT_DOUBLE_EQ(s.gamma, 0.0);
  s = adapt_levy_shape(-250.0, o);
  EXPECT_DOUBLE_EQ(s.mu, 1.1);
  EXPECT_DOUBLE_EQ(s.gamma, 1.0);
  s = adapt_levy_shape(25.0, o);
  EXPECT_DOUBLE_EQ(s.mu, 2.9 - 0.25 * 1.8);
  EXPECT_DOUBLE_EQ(s.gamma, 0.25);
}

// The bias: upwind after a falling or first reading; the mean of the last move's heading and
// upwind after a rising one. With gamma_max = 1 a strong rise turns exactly onto the bias.
TEST(LevyTaxis, ARisingReadingLeansTheBiasTowardTheHeading) {
  LevyTaxisOptions o;
  o.gradient_threshold = 10.0;
  AdaptiveLevyTaxis alt(o, 5);
  const Vec2 wind{1.0, 0.0};  // upwind is -x: pi
  alt.observe({{5.0, 2.0}, 0.0, wind, 0.0, 5.0});
  EXPECT_NEAR(std::abs(alt.bias()), kPiHere, 1e-12);
  EXPECT_DOUBLE_EQ(alt.shape().mu, 2.9);  // nothing to compare with: explore
  const double heading = std::atan2(alt.step().y, alt.step().x);
  alt.observe({Vec2{5.0, 2.0} + alt.step(), 500.0, wind, 0.0, 10.0});  // a strong rise
  const double expected =
      std::atan2(std::sin(heading) + std::sin(kPiHere), std::cos(heading) + std::cos(kPiHere));
  EXPECT_NEAR(alt.bias(), expected, 1e-9);
  EXPECT_NEAR(std::atan2(alt.step().y, alt.step().x), expected, 1e-9);  // gamma = 1: no turn
  alt.observe({{4.0, 2.0}, 100.0, wind, 0.0, 15.0});                    // falling: upwind alone
  EXPECT_NEAR(std::abs(alt.bias()), kPiHere, 1e-12);
  // The move is carried out from where the robot truly stands.
  EXPECT_EQ(alt.next({1.0, 1.0}).goal.x, 1.0 + alt.step().x);
}

TEST(LevyTaxis, StopsAtItsBudgetAndRefusesBadInput) {
  LevyTaxisOptions o;
  o.max_steps = 2;
  AdaptiveLevyTaxis alt(o, 1);
  alt.observe({{5.0, 2.0}, 0.0, {1.0, 0.0}, 0.0, 5.0});
  EXPECT_FALSE(alt.stopped());
  alt.observe({{5.0, 2.0}, 0.0, {1.0, 0.0}, 0.0, 10.0});
  EXPECT_EQ(alt.stopped_by(), "max_samples");
  EXPECT_THROW(alt.observe({{NAN, 2.0}, 0.0, {1.0, 0.0}, 0.0, 5.0}), InputError);
  o.mu_min = 1.0;  // mu must exceed 1
  EXPECT_THROW(AdaptiveLevyTaxis(o, 1), OptionError);
}

}  // namespace
}  // namespace plumekit::methods
