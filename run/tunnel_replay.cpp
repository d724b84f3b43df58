#include "run/tunnel_replay.hpp"

#include <algorithm>
#include <cmath>

#include "core/option_check.hpp"
#include "run/replay_recorder.hpp"

namespace plumekit::run {

namespace {

// The replay's cells: about 0.1 m, at most 200 along a side.
GridShape plane_grid(double width, double height) {
  return GridShape::with_cell(width, height, std::max({0.1, width / 200.0, height / 200.0}));
}

std::uint8_t belief_level(double v, double peak) {
  return static_cast<std::uint8_t>(peak > 0.0 ? std::clamp(std::lround(255.0 * v / peak), 0L, 255L)
                                              : 0L);
}

// A marginal summed over one axis, as 8-bit levels up to its peak; returns the peak.
double add_levels(const std::vector<double>& sums, std::vector<std::uint8_t>& levels) {
  const double peak = *std::max_element(sums.begin(), sums.end());
  for (double v : sums)
    levels.push_back(belief_level(v, peak));
  return peak;
}

// STE's samples are stops (of `sample_s`); a tracker's readings (the means of its moves) are
// readings on the way.
void add_readings(Replay& r, const TunnelRun& run, double sample_s) {
  for (const TunnelStep& step : run.steps) {
    const Vec2 at{step.position.x, step.position.y};
    if (is_tracker(run.method)) {
      r.readings.push_back({0, at, step.time_s, step.gas, step.position.z});
    } else {
      const Vec3 e = step.estimate;
      r.stops.push_back({0, at, std::max(0.0, step.time_s - sample_s), step.time_s, step.gas,
                         Vec2{e.x, e.y}, step.position.z, e.z});
    }
  }
}

}  // namespace

Map tunnel_map(const world::Tunnel& t) {
  Map m;
  m.name = "tunnel";
  m.generated_by = "plumekit localize tunnel";
  m.width = t.length;
  m.height = t.width;
  m.openings = {{OpeningKind::Inlet, {0.0, 0.0}, {0.0, t.width}, t.speed, Profile::Uniform},
                {OpeningKind::Outlet, {t.length, 0.0}, {t.length, t.width}, 0.0, Profile::Uniform}};
  return m;
}

TunnelReplayRecorder::TunnelReplayRecorder(const world::Tunnel& tunnel, Vec3 source, double every_s,
                                           double dt, double sample_s)
    : tunnel_(tunnel),
      source_(source),
      every_steps_(std::max(1LL, std::llround(every_s / dt))),
      every_s_(static_cast<double>(every_steps_) * dt),
      sample_s_(sample_s),
      top_grid_(plane_grid(tunnel.length, tunnel.width)),
      side_grid_(plane_grid(tunnel.length, tunnel.height)) {}

void TunnelReplayRecorder::frame(long long step, double, const world::TunnelPlume& plume,
                                 Vec3 robot) {
  const std::size_t f = static_cast<std::size_t>(step / every_steps_);
  if (top_.size() <= f) {
    top_.resize(f + 1);
    side_.resize(f + 1);
    where_.resize(f + 1);
  }
  plume.concentration_on(top_grid_, world::TunnelPlume::Plane::Top, source_.z, top_[f]);
  plume.concentration_on(side_grid_, world::TunnelPlume::Plane::Side, source_.y, side_[f]);
  where_[f] = robot;
}

void TunnelReplayRecorder::belief(double time_s, const ste::Posterior3* p) {
  if (!p || p->marginal.empty()) return;
  // The (x, y, z) marginal summed over z (from above) and over y (from the side).
  std::vector<double> top(static_cast<std::size_t>(p->nx) * p->ny, 0.0),
      side(static_cast<std::size_t>(p->nx) * p->nz, 0.0);
  for (int k = 0; k < p->nz; ++k)
    for (int j = 0; j < p->ny; ++j)
      for (int i = 0; i < p->nx; ++i) {
        const double v = p->marginal[(static_cast<std::size_t>(k) * p->ny + j) * p->nx + i];
        top[static_cast<std::size_t>(j) * p->nx + i] += v;
        side[static_cast<std::size_t>(k) * p->nx + i] += v;
      }
  belief_top_grid_ = {p->nx, p->ny, tunnel_.length, tunnel_.width};
  belief_side_grid_ = {p->nx, p->nz, tunnel_.length, tunnel_.height};
  beliefs_.push_back({0, time_s, add_levels(top, belief_top_)});
  side_peaks_.push_back(add_levels(side, belief_side_));
}

Replay TunnelReplayRecorder::finish(const TunnelRun& run, const std::string& title) const {
  Replay r;
  r.title = title;
  r.map = tunnel_map(tunnel_);
  r.source = {run.source.x, run.source.y};
  r.method = run.method;
  r.every_s = every_s_;
  ReplaySide& s = r.side.emplace();
  s.height = tunnel_.height;
  s.plane_y = source_.y;
  s.plane_z = source_.z;
  s.source_z = run.source.z;
  s.estimate_z = run.estimate.z;
  // Every frame the run reached, with the robot where the world showed it.
  Vec3 last = run.start;
  for (const std::optional<Vec3>& at : where_) {
    if (at) last = *at;
    r.positions.push_back({Vec2{last.x, last.y}});
    s.z.push_back({last.z});
  }
  std::vector<std::vector<float>> top = top_, side = side_;
  fill_unseen_frames(top, where_.size(), top_grid_.size());
  fill_unseen_frames(side, where_.size(), side_grid_.size());
  r.plume_top = replay_plume_top(top, side);  // both views on one scale
  r.plume_grid = top_grid_;
  s.plume_grid = side_grid_;
  append_plume_levels(r, top, r.plume);
  append_plume_levels(r, side, s.plume);
  r.belief_grid = belief_top_grid_;
  r.beliefs = beliefs_;
  r.belief_cells = belief_top_;
  s.belief_grid = belief_side_grid_;
  s.belief_peaks = side_peaks_;
  s.belief_cells = belief_side_;
  const bool tracker = is_tracker(run.method);
  add_readings(r, run, tracker ? 0.0 : sample_s_);
  r.has_estimate = !tracker;
  r.estimate = {run.estimate.x, run.estimate.y};
  r.declared_s = run.mission_s;
  r.ended_s = run.mission_s;
  r.stopped_by = run.stopped_by;
  return r;
}

TunnelReplayRecorder tunnel_replay_recorder(const TunnelOptions& o, Vec3 source) {
  return TunnelReplayRecorder(o.tunnel, source, 1.0, o.world.filament.dt, o.world.sample_s);
}

std::string tunnel_replay_title(const TunnelOptions& o, Vec3 source, std::uint64_t seed) {
  return "tunnel " + compact(o.tunnel.length) + " x " + compact(o.tunnel.width) + " x " +
         compact(o.tunnel.height) + " m, wind " + compact(o.tunnel.speed) + " m/s, " + o.method +
         ", source (" + compact(source.x) + ", " + compact(source.y) + ", " + compact(source.z) +
         "), seed " + std::to_string(seed);
}

}  // namespace plumekit::run
