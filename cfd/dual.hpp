#pragma once
// Forward-mode automatic differentiation over a row's few unknowns.
// Each residual row of the flow equations depends on at most kMaxLocal
// unknowns; evaluating the row with Dual values gives the row of the exact
// Jacobian, whatever the convection scheme or boundary treatment.
#include <array>
#include <cmath>

namespace plumekit::cfd {

inline constexpr int kMaxLocal = 16;

struct Dual {
  double v = 0.0;
  std::array<double, kMaxLocal> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants mix freely with duals
};

inline Dual operator+(const Dual& a, const Dual& b) {
  Dual r(a.v + b.v);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = a.d[k] + b.d[k];
  return r;
}
inline Dual operator-(const Dual& a, const Dual& b) {
  Dual r(a.v - b.v);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = a.d[k] - b.d[k];
  return r;
}
inline Dual operator-(const Dual& a) {
  Dual r(-a.v);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = -a.d[k];
  return r;
}
inline Dual operator*(const Dual& a, const Dual& b) {
  Dual r(a.v * b.v);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return r;
}
inline Dual operator*(double s, const Dual& a) {
  Dual r(s * a.v);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = s * a.d[k];
  return r;
}
inline Dual operator*(const Dual& a, double s) {
  return s * a;
}
inline Dual operator/(const Dual& a, const Dual& b) {
  const double inv = 1.0 / b.v;
  Dual r(a.v * inv);
  for (int k = 0; k < kMaxLocal; ++k)
    r.d[k] = (a.d[k] - r.v * b.d[k]) * inv;
  return r;
}
inline Dual abs(const Dual& a) {
  return a.v < 0.0 ? -a : a;
}

inline double value(double x) {
  return x;
}
inline double value(const Dual& x) {
  return x.v;
}
using std::abs;

}  // namespace plumekit::cfd
