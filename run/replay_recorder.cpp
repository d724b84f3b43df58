#include "run/replay_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dataset/plume.hpp"
#include "run/scenario.hpp"
#include "ste/posterior.hpp"

namespace plumekit::run {

ReplayRecorder::ReplayRecorder(const Map& map, int robots, double every_s, double dt,
                               int first_robot)
    : map_(map),
      robots_(robots),
      first_robot_(first_robot),
      every_steps_(std::max(1LL, std::llround(every_s / dt))),
      every_s_(static_cast<double>(every_steps_) * dt),
      plume_grid_(dataset::plume_series_grid(map)) {}

void ReplayRecorder::plume_at(long long step, double, const world::FilamentSimulation& sim) {
  const std::size_t frame = static_cast<std::size_t>(step / every_steps_);
  const std::lock_guard<std::mutex> g(lock_);
  scratch_.assign(plume_grid_.size(), 0.0);
  sim.concentration(plume_grid_, scratch_);
  if (plume_.size() <= frame) plume_.resize(frame + 1);
  plume_[frame].assign(scratch_.begin(), scratch_.end());
}

void ReplayRecorder::robot_at(int robot, long long step, double, Vec2 where) {
  const std::size_t frame = static_cast<std::size_t>(step / every_steps_);
  const std::lock_guard<std::mutex> g(lock_);
  if (where_.size() <= frame)
    where_.resize(frame + 1, std::vector<std::optional<Vec2>>(static_cast<std::size_t>(robots_)));
  where_[frame].at(static_cast<std::size_t>(robot - first_robot_)) = where;
}

void ReplayRecorder::copy_plume_frames(const ReplayRecorder& other) {
  if (&other == this) return;
  std::scoped_lock g(lock_, other.lock_);
  plume_ = other.plume_;
}

void ReplayRecorder::belief(int robot, double time_s, const methods::LocalizationMethod& method) {
  if (method.estimate()) has_estimate_ = true;
  std::optional<Grid<double>> grid;
  if (const ste::Posterior* p = method.posterior())
    grid = p->marginal;
  else
    grid = method.belief_map(map_);
  if (!grid || grid->values.empty()) return;
  const std::lock_guard<std::mutex> g(lock_);
  if (beliefs_.empty()) belief_grid_ = grid->shape;
  if (grid->shape.nx != belief_grid_.nx || grid->shape.ny != belief_grid_.ny)
    throw std::logic_error("ReplayRecorder: a belief on another grid than the first");
  const double peak = *std::max_element(grid->values.begin(), grid->values.end());
  beliefs_.push_back({robot, time_s, peak});
  for (double v : grid->values)
    belief_cells_.push_back(static_cast<std::uint8_t>(
        peak > 0.0 ? std::clamp(std::lround(255.0 * v / peak), 0L, 255L) : 0L));
}

namespace {

// The steps and readings of one robot's record.
void add_steps(Replay& r, int robot, const std::vector<Step>& steps) {
  for (const Step& s : steps) {
    for (const PassingRecord& p : s.on_the_way)
      r.readings.push_back({robot, p.position, p.time_s, p.value});
    r.stops.push_back({robot, s.position, s.arrived_s, s.time_s, s.value, s.estimate});
  }
}

}  // namespace

double replay_plume_top(const std::vector<std::vector<float>>& frames,
                        const std::vector<std::vector<float>>& more) {
  std::vector<float> seen;
  for (const auto* view : {&frames, &more})
    for (const std::vector<float>& f : *view)
      for (float c : f)
        if (c > kReplayPlumeFloor) seen.push_back(c);
  if (seen.empty()) return 10.0 * kReplayPlumeFloor;
  const std::size_t k = std::min(seen.size() - 1, static_cast<std::size_t>(0.999 * seen.size()));
  std::nth_element(seen.begin(), seen.begin() + static_cast<std::ptrdiff_t>(k), seen.end());
  return std::max(10.0 * kReplayPlumeFloor, static_cast<double>(seen[k]));
}

void fill_unseen_frames(std::vector<std::vector<float>>& frames, std::size_t count,
                        std::size_t cells) {
  frames.resize(count);
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].empty()) frames[f] = f > 0 ? frames[f - 1] : std::vector<float>(cells, 0.0f);
}

void append_plume_levels(const Replay& scale, const std::vector<std::vector<float>>& frames,
                         std::vector<std::uint8_t>& levels) {
  for (const std::vector<float>& f : frames)
    for (float c : f)
      levels.push_back(scale.plume_level(c));
}

Replay ReplayRecorder::finish(const LocalizationResult& result, Vec2 source,
                              const std::string& title) {
  const std::lock_guard<std::mutex> g(lock_);
  Replay r;
  r.title = title;
  r.map = map_;
  r.source = source;
  r.method = result.method;
  r.robots = robots_;
  r.every_s = every_s_;
  // Every frame the robots' time reached; a robot that had stopped stays where it was, and a
  // frame the plume had not been stepped to yet (nobody read it) shows the plume before it.
  std::vector<Vec2> last(static_cast<std::size_t>(robots_), result.start);
  if (result.team.size() == static_cast<std::size_t>(robots_))
    for (int k = 0; k < robots_; ++k)
      last[static_cast<std::size_t>(k)] = result.team[static_cast<std::size_t>(k)].start;
  for (const std::vector<std::optional<Vec2>>& frame : where_) {
    for (std::size_t k = 0; k < last.size(); ++k)
      if (frame[k]) last[k] = *frame[k];
    r.positions.push_back(last);
  }
  r.plume_grid = plume_grid_;
  std::vector<std::vector<float>> frames = plume_;
  fill_unseen_frames(frames, r.positions.size(), plume_grid_.size());
  r.plume_top = replay_plume_top(frames);
  r.plume.reserve(frames.size() * plume_grid_.size());
  append_plume_levels(r, frames, r.plume);
  r.belief_grid = belief_grid_;
  r.beliefs = beliefs_;
  r.belief_cells = belief_cells_;
  if (result.team.empty()) {
    add_steps(r, 0, result.steps);
  } else {
    for (std::size_t k = 0; k < result.team.size(); ++k)
      add_steps(r, static_cast<int>(k), result.team[k].steps);
  }
  std::stable_sort(r.stops.begin(), r.stops.end(),
                   [](const ReplayStop& a, const ReplayStop& b) { return a.time_s < b.time_s; });
  std::stable_sort(
      r.readings.begin(), r.readings.end(),
      [](const ReplayReading& a, const ReplayReading& b) { return a.time_s < b.time_s; });
  r.has_estimate = has_estimate_;
  r.estimate = result.estimate;
  r.declared_s = result.time_s - result.approach_s;
  r.ended_s = result.time_s;
  r.stopped_by = result.stopped_by;
  r.approach = result.approach;
  return r;
}

std::unique_ptr<ReplayRecorder> replay_recorder_for(const Scenario& scenario, int first_robot) {
  return std::make_unique<ReplayRecorder>(scenario.map(),
                                          std::max(1, scenario.options().team.robots), 1.0,
                                          scenario.options().world.filament.dt, first_robot);
}

}  // namespace plumekit::run
