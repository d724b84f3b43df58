// core/fast_math: plumekit's own exp, log and sin/cos of a turn, against libm (exp, log) and
// against long double sin/cos (sincos_turn, whose argument 2 pi u libm cannot take exactly).
#include "core/fast_math.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace plumekit::fast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kLn2 = 0.69314718055994530942;
constexpr long double kTwoPi = 6.283185307179586476925286766559L;

// Points spread evenly over [lo, hi], both ends included.
std::vector<double> sweep(double lo, double hi, int count) {
  std::vector<double> xs(count);
  for (int i = 0; i < count; ++i)
    xs[i] = lo + (hi - lo) * i / (count - 1);
  return xs;
}

// Each x, and its neighbours one and two units in the last place either side.
std::vector<double> with_neighbours(const std::vector<double>& xs) {
  std::vector<double> out;
  for (double x : xs) {
    const double below = std::nextafter(x, -kInf), above = std::nextafter(x, kInf);
    out.insert(out.end(),
               {std::nextafter(below, -kInf), below, x, above, std::nextafter(above, kInf)});
  }
  return out;
}

double relative_error(double got, double want) {
  return std::fabs(got - want) / std::fabs(want);
}

TEST(FastExp, WithinOneEMinus15RelativeOfLibmOnItsRange) {
  std::vector<double> xs = sweep(-708.0, 0.0, 200001);
  // The edges of the reduction (x = n ln2 +- ln2/2, where n steps) and of the range.
  std::vector<double> edges = {0.0,         -1e-300,     -5e-324, -1e-17,        -1e-9,
                               -0.5 * kLn2, -1.5 * kLn2, -9.0,    -700.5 * kLn2, -708.0};
  for (int n = 1; n < 1021; n += 7)
    edges.push_back(-(n + 0.5) * kLn2);
  for (double x : with_neighbours(edges))
    if (x <= 0.0 && x >= -708.0) xs.push_back(x);
  double worst = 0.0, worst_x = 0.0;
  for (double x : xs) {
    const double error = relative_error(exp_neg(x), std::exp(x));
    if (error > worst) worst = error, worst_x = x;
  }
  EXPECT_LE(worst, 1e-15) << "at x = " << worst_x;
}

TEST(FastExp, ExactWhereExpIsExact) {
  EXPECT_EQ(exp_neg(0.0), 1.0);
  EXPECT_EQ(exp_neg(-0.0), 1.0);
  EXPECT_EQ(exp_neg(-1e-300), 1.0);
}

TEST(FastExp, ZeroBelowMinus708) {
  for (double x : {std::nextafter(-708.0, -kInf), -708.5, -709.0, -745.2, -1000.0, -1e300,
                   -std::numeric_limits<double>::max(), -kInf})
    EXPECT_EQ(exp_neg(x), 0.0) << x;
}

// |log_positive(x) - log x| <= 1e-15 max(1, |log x|) over the xs; the worst x is reported.
void expect_log_close(const std::vector<double>& xs) {
  double worst = 0.0, worst_x = 0.0;
  for (double x : xs) {
    const double want = std::log(x);
    const double error = std::fabs(log_positive(x) - want) / std::max(1.0, std::fabs(want));
    if (error > worst) worst = error, worst_x = x;
  }
  EXPECT_LE(worst, 1e-15) << "at x = " << worst_x;
}

TEST(FastLog, CloseToLibmOnTheUnitInterval) {
  std::vector<double> xs = sweep(0.0, 1.0, 200001);
  xs.front() = 1e-300;  // the domain is positive normals
  expect_log_close(xs);
}

TEST(FastLog, CloseToLibmFrom1EMinus300To1E300) {
  std::vector<double> xs;
  for (double t : sweep(std::log(1e-300), std::log(1e300), 200001))
    xs.push_back(std::exp(t));
  xs.front() = 1e-300;
  xs.back() = 1e300;
  expect_log_close(xs);
}

TEST(FastLog, CloseToLibmAtPowersOfTwoAndAroundSqrt2AndOne) {
  std::vector<double> centres;
  for (int e = -1022; e <= 1023; ++e) {
    centres.push_back(std::ldexp(1.0, e));
    centres.push_back(std::ldexp(1.4142135623730951, e));  // where the mantissa is halved
  }
  const std::vector<double> xs = with_neighbours(centres);
  expect_log_close(xs);
  for (double x : xs)
    EXPECT_GT(x, 0.0);
}

// Near 1, where ln x is small, relatively too (Box-Muller takes it of u0 near 1).
TEST(FastLog, RelativelyCloseToLibmNearOne) {
  double worst = 0.0, worst_x = 0.0;
  for (int i = 1; i <= 100000; ++i)
    for (double x : {1.0 + i * 0x1p-52, 1.0 - i * 0x1p-53, 1.0 + i * 1e-9, 1.0 - i * 1e-9}) {
      const double error = relative_error(log_positive(x), std::log(x));
      if (error > worst) worst = error, worst_x = x;
    }
  EXPECT_LE(worst, 1e-15) << "at x = " << worst_x;
}

TEST(FastLog, OfOneIsExactlyZero) {
  EXPECT_EQ(log_positive(1.0), 0.0);
  EXPECT_EQ(log_positive(2.0), std::log(2.0));
}

// |error| of sin and cos against long double sin/cos of 2 pi u, and of sin^2 + cos^2 - 1.
struct TurnErrors {
  double value = 0.0, value_u = 0.0, unit = 0.0, unit_u = 0.0;
};

TurnErrors turn_errors(const std::vector<double>& us) {
  TurnErrors worst;
  for (double u : us) {
    double s, c;
    sincos_turn(u, s, c);
    const long double angle = kTwoPi * u;
    const double error = static_cast<double>(
        std::max(std::fabs(s - std::sin(angle)), std::fabs(c - std::cos(angle))));
    if (error > worst.value) worst.value = error, worst.value_u = u;
    const long double ls = s, lc = c;
    const double unit = static_cast<double>(std::fabs(ls * ls + lc * lc - 1.0L));
    if (unit > worst.unit) worst.unit = unit, worst.unit_u = u;
  }
  return worst;
}

TEST(FastSinCos, CloseToSinAndCosOfTheTurn) {
  std::vector<double> us = sweep(0.0, 1.0, 200001);
  us.back() = std::nextafter(1.0, 0.0);
  // The quarter turns and the eighths between them: where q steps and where |r| is largest.
  for (double u : with_neighbours({0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875}))
    us.push_back(u);
  for (double u : {std::nextafter(0.0, 1.0), 1e-300, 1e-9})
    us.push_back(u);
  const TurnErrors worst = turn_errors(us);
  EXPECT_LE(worst.value, 2e-15) << "at u = " << worst.value_u;
  EXPECT_LE(worst.unit, 1e-15) << "at u = " << worst.unit_u;
}

TEST(FastSinCos, ExactOnTheQuarterTurns) {
  const double want[4][2] = {{0.0, 1.0}, {1.0, 0.0}, {0.0, -1.0}, {-1.0, 0.0}};
  for (int quarter = 0; quarter < 4; ++quarter) {
    double s, c;
    sincos_turn(0.25 * quarter, s, c);
    EXPECT_EQ(s, want[quarter][0]) << quarter;
    EXPECT_EQ(c, want[quarter][1]) << quarter;
  }
}

TEST(FastSinCos, JustBelowOneTurnIsJustBelowZeroAngle) {
  double s, c;
  sincos_turn(std::nextafter(1.0, 0.0), s, c);
  EXPECT_LT(s, 0.0);
  EXPECT_NEAR(s, -kTwoPi * 0x1p-53, 1e-30);
  EXPECT_EQ(c, 1.0);
}

}  // namespace
}  // namespace plumekit::fast
