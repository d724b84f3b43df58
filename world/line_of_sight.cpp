#include "world/line_of_sight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plumekit::world {

namespace {

bool boxes_meet(const Box& p, const Box& q) {
  return p.lo.x <= q.hi.x && q.lo.x <= p.hi.x && p.lo.y <= q.hi.y && q.lo.y <= p.hi.y;
}

}  // namespace

LineOfSight::LineOfSight(const Map& map, double bucket) : bucket_(bucket) {
  nx_ = std::max(1, static_cast<int>(std::ceil(map.width / bucket)));
  ny_ = std::max(1, static_cast<int>(std::ceil(map.height / bucket)));
  buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
  for (const Polygon& poly : map.obstacles) {
    const bool ccw = signed_area(poly) > 0.0;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
      if (!ccw) std::swap(a, b);  // interior on the left
      const int id = static_cast<int>(edges_.size());
      edges_.push_back({a, b});
      const Box box{{std::min(a.x, b.x), std::min(a.y, b.y)},
                    {std::max(a.x, b.x), std::max(a.y, b.y)}};
      boxes_.push_back(box);
      const int c0 = column(box.lo.x), c1 = column(box.hi.x);
      const int r0 = row(box.lo.y), r1 = row(box.hi.y);
      first_bucket_.push_back(c0);
      first_bucket_.push_back(r0);
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
          buckets_[static_cast<std::size_t>(r) * nx_ + c].push_back(id);
    }
  }
}

int LineOfSight::column(double x) const {
  return std::clamp(static_cast<int>(std::floor(x / bucket_)), 0, nx_ - 1);
}
int LineOfSight::row(double y) const {
  return std::clamp(static_cast<int>(std::floor(y / bucket_)), 0, ny_ - 1);
}

void LineOfSight::facing_edges(Vec2 from, const Box& box, std::vector<Edge>& out) const {
  if (edges_.empty()) return;
  const int c0 = column(box.lo.x), c1 = column(box.hi.x);
  const int r0 = row(box.lo.y), r1 = row(box.hi.y);
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c)
      for (const int id : buckets_[static_cast<std::size_t>(r) * nx_ + c]) {
        // An edge in several buckets is reported from the first one the query shares with it.
        if (c != std::max(c0, first_bucket_[2 * id]) ||
            r != std::max(r0, first_bucket_[2 * id + 1]))
          continue;
        const Edge& e = edges_[id];
        if (boxes_meet(boxes_[id], box) && orient(e.a, e.b, from) < 0.0) out.push_back(e);
      }
}

EdgeShadow::EdgeShadow(Vec2 from, const Edge& e)
    : y_lo_(-std::numeric_limits<double>::infinity()),
      y_hi_(std::numeric_limits<double>::infinity()) {
  // orient(u, v, (x, y)) * sign = alpha x + c y + d >= 0 for the far side of
  // the edge's line and the cone's two rays; on a row it bounds x from one
  // side, or (alpha = 0) y alone.
  auto add = [this](Vec2 u, Vec2 v, double sign) {
    const Vec2 d = v - u;
    const double alpha = -sign * d.y, c = sign * d.x, off = sign * (d.y * u.x - d.x * u.y);
    if (alpha > 0.0)
      lower_[lowers_++] = {-c / alpha, -off / alpha};
    else if (alpha < 0.0)
      upper_[uppers_++] = {-c / alpha, -off / alpha};
    else if (c > 0.0)
      y_lo_ = std::max(y_lo_, -off / c);
    else if (c < 0.0)
      y_hi_ = std::min(y_hi_, -off / c);
    else if (off < 0.0)
      y_hi_ = -std::numeric_limits<double>::infinity();  // never: a degenerate edge
  };
  add(e.a, e.b, 1.0);
  add(from, e.a, -1.0);
  add(from, e.b, 1.0);
  // The shadow lies beyond the edge: on its far side of `from` in y too.
  if (from.y <= std::min(e.a.y, e.b.y)) y_lo_ = std::max(y_lo_, std::min(e.a.y, e.b.y));
  if (from.y >= std::max(e.a.y, e.b.y)) y_hi_ = std::min(y_hi_, std::max(e.a.y, e.b.y));
  const double inf = std::numeric_limits<double>::infinity();
  for (int k = lowers_; k < 3; ++k)
    lower_[k] = {0.0, -inf};
  for (int k = uppers_; k < 3; ++k)
    upper_[k] = {0.0, inf};
}

bool EdgeShadow::on_row(double y, double& lo, double& hi) const {
  if (y < y_lo_ || y > y_hi_) return false;
  lo = -std::numeric_limits<double>::infinity();
  hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < lowers_; ++k)
    lo = std::max(lo, lower_[k].slope * y + lower_[k].offset);
  for (int k = 0; k < uppers_; ++k)
    hi = std::min(hi, upper_[k].slope * y + upper_[k].offset);
  return lo <= hi;
}

void EdgeShadow::on_rows(int first, int n, double dy, double* lo, double* hi) const {
  const double inf = std::numeric_limits<double>::infinity();
  const Bound l0 = lower_[0], l1 = lower_[1], l2 = lower_[2];
  const Bound u0 = upper_[0], u1 = upper_[1], u2 = upper_[2];
  for (int r = 0; r < n; ++r) {
    const double y = (first + r + 0.5) * dy;
    const double l = std::max(std::max(l0.slope * y + l0.offset, l1.slope * y + l1.offset),
                              l2.slope * y + l2.offset);
    const double h = std::min(std::min(u0.slope * y + u0.offset, u1.slope * y + u1.offset),
                              u2.slope * y + u2.offset);
    const bool in = y >= y_lo_ && y <= y_hi_;
    lo[r] = in ? l : inf;
    hi[r] = in ? h : -inf;
  }
}

bool hides(Vec2 from, const Edge& e, Vec2 p) {
  return segments_intersect(from, p, e.a, e.b);
}

}  // namespace plumekit::world
