#pragma once
// exp, log and sin/cos of a turn written out in plumekit (issue 45): branch-free, so that loops
// calling them vectorize, and the same bits wherever plumekit is built with the same compiler
// flags, whatever libm the machine has. Each is within a few units in the last place of libm's
// over the range it is used on (tests/core/fast_math_test.cpp).
#include <cstdint>
#include <cstring>

namespace plumekit::fast {

namespace detail {

inline double from_bits(std::uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}
inline std::uint64_t to_bits(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

constexpr double kLn2Hi = 6.93147180369123816490e-01;  // ln 2 in two parts: n * hi is exact
constexpr double kLn2Lo = 1.90821492927058770002e-10;

// The nearest integer (ties to even) of |x| < 2^51, by adding and taking away 1.5 * 2^52: two
// additions, which vectorize where a call to rint or round may not.
inline double round_nearest(double x) {
  constexpr double kMagic = 6755399441055744.0;
  return (x + kMagic) - kMagic;
}

}  // namespace detail

// e^x for x <= 0 (the Gaussian kernel's argument); 0 below -708, where e^x is subnormal.
inline double exp_neg(double x) {
  using namespace detail;
  const double clamped = x < -708.0 ? -708.0 : x;
  // x = n ln 2 + r, |r| <= ln 2 / 2; e^r by its Taylor series to r^13 (error below 1e-17).
  const double n = round_nearest(clamped * 1.4426950408889634);
  const double r = (clamped - n * kLn2Hi) - n * kLn2Lo;
  double p = 1.0 / 6227020800.0;  // 1/13!
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^n by its exponent bits (n >= -1022 here).
  const double scale =
      from_bits(static_cast<std::uint64_t>(static_cast<std::int64_t>(n) + 1023) << 52);
  return x < -708.0 ? 0.0 : p * scale;
}

// ln x for a positive normal x.
inline double log_positive(double x) {
  using namespace detail;
  const std::uint64_t bits = to_bits(x);
  // x = m 2^e with m in [sqrt(1/2), sqrt(2)).
  std::int64_t e = static_cast<std::int64_t>(bits >> 52) - 1023;
  double m = from_bits((bits & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL);
  const bool high = m > 1.4142135623730951;
  m = high ? 0.5 * m : m;
  e += high ? 1 : 0;
  // ln m = 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.1716: the odd series to s^23.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double p = 1.0 / 23.0;
  p = p * s2 + 1.0 / 21.0;
  p = p * s2 + 1.0 / 19.0;
  p = p * s2 + 1.0 / 17.0;
  p = p * s2 + 1.0 / 15.0;
  p = p * s2 + 1.0 / 13.0;
  p = p * s2 + 1.0 / 11.0;
  p = p * s2 + 1.0 / 9.0;
  p = p * s2 + 1.0 / 7.0;
  p = p * s2 + 1.0 / 5.0;
  p = p * s2 + 1.0 / 3.0;
  const double de = static_cast<double>(e);
  return de * kLn2Hi + (2.0 * s + (2.0 * s * s2 * p + de * kLn2Lo));
}

// sin and cos of the angle 2 pi u, for u in [0, 1).
inline void sincos_turn(double u, double& sin_out, double& cos_out) {
  // 2 pi u = q pi/2 + r with q the nearest quarter turn, |r| <= pi/4.
  const double quarters = 4.0 * u;
  const double q = detail::round_nearest(quarters);
  const double r = (quarters - q) * 1.5707963267948966;
  const double r2 = r * r;
  // Taylor series: sin to r^17, cos to r^18 (error below 1e-17 on |r| <= pi/4).
  double s = -1.0 / 355687428096000.0;  // -1/17!
  s = s * r2 + 1.0 / 1307674368000.0;
  s = s * r2 - 1.0 / 6227020800.0;
  s = s * r2 + 1.0 / 39916800.0;
  s = s * r2 - 1.0 / 362880.0;
  s = s * r2 + 1.0 / 5040.0;
  s = s * r2 - 1.0 / 120.0;
  s = s * r2 + 1.0 / 6.0;
  s = r - r * r2 * s;
  double c = 1.0 / 6402373705728000.0;  // 1/18!
  c = c * r2 - 1.0 / 20922789888000.0;
  c = c * r2 + 1.0 / 87178291200.0;
  c = c * r2 - 1.0 / 479001600.0;
  c = c * r2 + 1.0 / 3628800.0;
  c = c * r2 - 1.0 / 40320.0;
  c = c * r2 + 1.0 / 720.0;
  c = c * r2 - 1.0 / 24.0;
  c = c * r2 + 0.5;
  c = 1.0 - r2 * c;
  // Rotate by q quarter turns.
  const int k = static_cast<int>(q) & 3;
  sin_out = k == 0 ? s : k == 1 ? c : k == 2 ? -s : -c;
  cos_out = k == 0 ? c : k == 1 ? -s : k == 2 ? -c : s;
}

}  // namespace plumekit::fast
