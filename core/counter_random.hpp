#pragma once
// Counter-based random numbers (issue 45): draw number `counter` of stream `key` is a function of
// the two alone, so a loop may draw them in any order, on any thread, vectorized, and get the
// same numbers. They are SplitMix64's sequence from `key` (core/seed.hpp), and the normals come
// from it by Box-Muller with plumekit's own log and sin/cos (core/fast_math.hpp): the formula is
// fixed here, so the bytes do not depend on the standard library.
#include <cmath>
#include <cstdint>

#include "core/fast_math.hpp"
#include "core/seed.hpp"

namespace plumekit {

// Value `index` of SplitMix64's sequence from `key`.
inline std::uint64_t counter_bits(std::uint64_t key, std::uint64_t index) {
  return splitmix64(key + index * 0x9E3779B97F4A7C15ULL);
}

// A uniform in [0, 1) with 53 random bits: value `index` of the stream `key`.
inline double counter_uniform(std::uint64_t key, std::uint64_t index) {
  return static_cast<double>(static_cast<std::int64_t>(counter_bits(key, index) >> 11)) * 0x1p-53;
}

// Two independent standard normals, pair `counter` of the stream `key` (its values 2 counter and
// 2 counter + 1): sqrt(-2 ln u0) (cos, sin)(2 pi u1) with u0 in (0, 1], u1 in [0, 1).
inline void counter_normals(std::uint64_t key, std::uint64_t counter, double& z0, double& z1) {
  const std::uint64_t h0 = counter_bits(key, 2 * counter);
  const std::uint64_t h1 = counter_bits(key, 2 * counter + 1);
  const double u0 = static_cast<double>(static_cast<std::int64_t>(h0 >> 11) + 1) * 0x1p-53;
  const double u1 = static_cast<double>(static_cast<std::int64_t>(h1 >> 11)) * 0x1p-53;
  const double radius = std::sqrt(-2.0 * fast::log_positive(u0));
  double s, c;
  fast::sincos_turn(u1, s, c);
  z0 = radius * c;
  z1 = radius * s;
}

}  // namespace plumekit
