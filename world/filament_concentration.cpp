// What a robot's sensor reads from the filaments: the plume captured as a frame (filaments in
// buckets) and the concentration at one point, with line of sight when occlusion is on. The
// sensor grid's (datasets' frames) is world/grid_concentration.cpp.
#include <algorithm>
#include <cmath>

#include "core/fast_math.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {

namespace {

// Where a box lies against the shadow an edge facing `from` casts (the points q for which the
// segment from `from` to q crosses the edge): the shadow is convex, the far side of the edge's
// line inside the cone from `from` through its ends, three half-planes a x + b y + c >= 0, set up
// once per sensor and edge. A box beyond one of them is outside the shadow; a box inside all
// three is inside it. Near a boundary (within rounding) the box counts as cut, so that the
// filaments there take the exact test.
enum class Shade { None, Part, All };

class ShadowPlanes {
 public:
  ShadowPlanes(Vec2 from, const Edge& e) {
    set(0, e.a, e.b, 1.0);
    set(1, from, e.a, -1.0);
    set(2, from, e.b, 1.0);
  }
  Shade of(const Box& box) const {
    bool all = true;
    for (int h = 0; h < 3; ++h) {
      // The plane's largest and smallest value over the box, at its corners.
      const double x_hi = a_[h] > 0.0 ? box.hi.x : box.lo.x,
                   x_lo = a_[h] > 0.0 ? box.lo.x : box.hi.x;
      const double y_hi = b_[h] > 0.0 ? box.hi.y : box.lo.y,
                   y_lo = b_[h] > 0.0 ? box.lo.y : box.hi.y;
      const double most = a_[h] * x_hi + b_[h] * y_hi + c_[h];
      const double least = a_[h] * x_lo + b_[h] * y_lo + c_[h];
      if (most < -tolerance_[h]) return Shade::None;
      all = all && least > tolerance_[h];
    }
    return all ? Shade::All : Shade::Part;
  }

 private:
  // sign * orient(u, v, q) = a q.x + b q.y + c.
  void set(int h, Vec2 u, Vec2 v, double sign) {
    const double dx = v.x - u.x, dy = v.y - u.y;
    a_[h] = -sign * dy;
    b_[h] = sign * dx;
    c_[h] = sign * (dy * u.x - dx * u.y);
    tolerance_[h] = 1e-9 * (std::abs(dx) + std::abs(dy)) * (1.0 + std::abs(u.x) + std::abs(u.y));
  }
  double a_[3], b_[3], c_[3], tolerance_[3];
};

}  // namespace

void FilamentSimulation::capture(PlumeFrame& frame) const {
  frame.sim_ = this;
  frame.step_ = steps_;
  frame.time_ = time_;
  frame.meander_ = meander_;
  if (fluctuation_)
    frame.amplitudes_ = fluctuation_->amplitudes();
  else
    frame.amplitudes_.clear();
  const std::size_t n = x_.size();
  if (o_.engine == PlumeEngine::V1) {
    frame.x_ = x_;
    frame.y_ = y_;
    frame.r2_ = r2_;
    return;
  }
  frame.nx_ = std::max(1, static_cast<int>(std::ceil(map_.width / frame.bucket_)));
  frame.ny_ = std::max(1, static_cast<int>(std::ceil(map_.height / frame.bucket_)));
  const std::size_t buckets = static_cast<std::size_t>(frame.nx_) * frame.ny_;
  // A counting sort by bucket, stable: filaments keep their order within a bucket.
  std::vector<int> of(n);
  std::vector<int>& start = frame.start_;
  start.assign(buckets + 1, 0);
  const double inv = 1.0 / frame.bucket_;
  for (std::size_t k = 0; k < n; ++k) {
    const int i = std::min(frame.nx_ - 1, static_cast<int>(x_[k] * inv));
    const int j = std::min(frame.ny_ - 1, static_cast<int>(y_[k] * inv));
    of[k] = j * frame.nx_ + i;
    ++start[static_cast<std::size_t>(of[k]) + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b)
    start[b + 1] += start[b];
  std::vector<int> next(start.begin(), start.end() - 1);
  frame.x_.resize(n);
  frame.y_.resize(n);
  frame.r2_.resize(n);
  frame.max_r2_.assign(buckets, 0.0);
  frame.max_r2_all_ = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t b = static_cast<std::size_t>(of[k]);
    const int at = next[b]++;
    frame.x_[at] = x_[k];
    frame.y_[at] = y_[k];
    frame.r2_[at] = r2_[k];
    frame.max_r2_[b] = std::max(frame.max_r2_[b], r2_[k]);
    frame.max_r2_all_ = std::max(frame.max_r2_all_, r2_[k]);
  }
}

double FilamentSimulation::concentration_at(Vec2 p) const {
  const PlumeFrame* frame;
  {
    std::lock_guard<std::mutex> g(now_lock_);
    if (now_.step_ != steps_ || now_.sim_ != this) capture(now_);
    frame = &now_;
  }
  // The plume does not step while its sensors read (world/shared_plume.hpp).
  return frame->concentration_at(p);
}

Vec2 PlumeFrame::wind_at(Vec2 p) const {
  return sim_->wind_then(p, amplitudes_.data(), meander_);
}

double PlumeFrame::concentration_at(Vec2 p) const {
  return sim_->o_.engine == PlumeEngine::V1 ? concentration_v1(p) : concentration_fast(p);
}

double PlumeFrame::bucket_sum(Vec2 p, int first, int last, const std::vector<Edge>& part) const {
  const double cut2 = sim_->o_.cutoff * sim_->o_.cutoff;
  // Eight running sums, each filament's kernel (0 out of its reach or out of sight) into sum
  // k mod 8, added up in a fixed order: the loop vectorizes where no shadow cuts the bucket.
  double lane[8] = {};
  auto kernel = [&](int k) {
    const double dx = p.x - x_[k], dy = p.y - y_[k];
    const double inv = 1.0 / r2_[k];
    const double lim = cut2 * r2_[k];
    const bool reach = dx * dx <= lim && dy * dy <= lim;
    return reach ? fast::exp_neg(-(dx * dx + dy * dy) * inv) * inv : 0.0;
  };
  if (part.empty()) {
    int k = first;
    for (; k + 8 <= last; k += 8)
      for (int l = 0; l < 8; ++l)
        lane[l] += kernel(k + l);
    for (; k < last; ++k)
      lane[(k - first) % 8] += kernel(k);
  } else {
    for (int k = first; k < last; ++k) {
      const Vec2 f{x_[k], y_[k]};
      if (std::any_of(part.begin(), part.end(), [&](const Edge& e) { return hides(p, e, f); }))
        continue;
      lane[(k - first) % 8] += kernel(k);
    }
  }
  return ((lane[0] + lane[4]) + (lane[2] + lane[6])) + ((lane[1] + lane[5]) + (lane[3] + lane[7]));
}

double PlumeFrame::concentration_fast(Vec2 p) const {
  const FilamentOptions& o = sim_->o_;
  const double cut2 = o.cutoff * o.cutoff;
  const double reach = o.cutoff * std::sqrt(max_r2_all_);
  const Box query{{p.x - reach, p.y - reach}, {p.x + reach, p.y + reach}};
  std::vector<Edge> edges, part;
  if (sim_->sight_) sim_->sight_->facing_edges(p, query, edges);
  std::vector<ShadowPlanes> shadows;
  shadows.reserve(edges.size());
  for (const Edge& e : edges)
    shadows.emplace_back(p, e);
  const int i0 = std::max(0, static_cast<int>(std::floor(query.lo.x / bucket_)));
  const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor(query.hi.x / bucket_)));
  const int j0 = std::max(0, static_cast<int>(std::floor(query.lo.y / bucket_)));
  const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor(query.hi.y / bucket_)));
  double c = 0.0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t b = static_cast<std::size_t>(j) * nx_ + i;
      const int first = start_[b], last = start_[b + 1];
      if (first == last) continue;
      // The bucket's box, and whether any of its filaments can reach p.
      const Box box{{i * bucket_, j * bucket_}, {(i + 1) * bucket_, (j + 1) * bucket_}};
      const double gx = std::max({0.0, box.lo.x - p.x, p.x - box.hi.x});
      const double gy = std::max({0.0, box.lo.y - p.y, p.y - box.hi.y});
      const double far = cut2 * max_r2_[b];
      if (gx * gx > far || gy * gy > far) continue;
      // Edges whose shadow covers the bucket hide it; those that cut it are tested per filament.
      part.clear();
      bool hidden = false;
      for (std::size_t e = 0; e < edges.size(); ++e) {
        const Shade s = shadows[e].of(box);
        if (s == Shade::All) {
          hidden = true;
          break;
        }
        if (s == Shade::Part) part.push_back(edges[e]);
      }
      if (hidden) continue;
      c += bucket_sum(p, first, last, part);
    }
  return c * sim_->mass_ / kPi;
}

}  // namespace plumekit::world
