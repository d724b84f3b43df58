#include "world/shared_plume.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace plumekit::world {

namespace {
constexpr long long kGone = std::numeric_limits<long long>::max();
}

namespace {

// Frames kept: as many as fit in this many bytes, estimated from the filaments after the spin-up
// (with room for them to grow by half), between 2 and 256 (12.8 s at the default dt).
constexpr double kRingBytes = 32e6;

int ring_frames(std::size_t filaments, int robots) {
  if (robots == 1) return 2;  // a robot alone reads only the plume's newest frame
  const double frame = 1.5 * static_cast<double>(filaments) * 3 * sizeof(double) + 4096.0;
  return static_cast<int>(std::clamp(kRingBytes / frame, 2.0, 256.0));
}

}  // namespace

SharedPlume::SharedPlume(const Map& map, const cfd::WindField& wind, Vec2 source,
                         const world::FilamentOptions& options, std::uint64_t seed, int robots)
    : sim_(map, wind, source, options, seed) {
  if (robots < 1) throw std::logic_error("SharedPlume: at least one robot");
  world::spin_up(sim_, options);
  spinup_s_ = sim_.time();
  need_.assign(static_cast<std::size_t>(robots), 0);
  ring_.resize(static_cast<std::size_t>(ring_frames(sim_.filament_count(), robots)));
  sim_.capture(ring_[0]);
}

long long SharedPlume::earliest_need() const {
  return *std::min_element(need_.begin(), need_.end());
}

void SharedPlume::advance_to(long long step, std::unique_lock<std::mutex>& g) {
  const long long frames = static_cast<long long>(ring_.size());
  while (step_ < step) {
    // Step s overwrites the frame of s - frames: wait until nobody may still read it.
    if (stepping_ || earliest_need() <= step_ + 1 - frames) {
      moved_.wait(g);
      continue;
    }
    stepping_ = true;
    const long long to = std::min(step, earliest_need() + frames - 1);
    g.unlock();
    // A robot alone reads only the step it asked for; robots together may read any.
    const bool every = need_.size() > 1;
    for (long long s = step_ + 1; s <= to; ++s) {
      sim_.step();
      if (watcher_ != nullptr && s % watcher_->every_steps() == 0)
        watcher_->plume_at(s, sim_.time(), sim_);
      if (every || s == to) sim_.capture(ring_[static_cast<std::size_t>(s % frames)]);
    }
    g.lock();
    step_ = to;
    stepping_ = false;
    moved_.notify_all();
  }
}

const world::PlumeFrame& SharedPlume::at(long long step, int robot) {
  std::unique_lock<std::mutex> g(lock_);
  long long& need = need_.at(static_cast<std::size_t>(robot));
  if (step < need || need == kGone)
    throw std::logic_error("SharedPlume: robot " + std::to_string(robot) + " asked for step " +
                           std::to_string(step) + " after step " + std::to_string(need));
  const bool freed = step > need && need == earliest_need();
  need = step;
  // This robot was the slowest: a robot waiting for room in the ring may go on.
  if (freed) moved_.notify_all();
  advance_to(step, g);
  return ring_[static_cast<std::size_t>(step % static_cast<long long>(ring_.size()))];
}

void SharedPlume::promise(int robot, long long step) {
  std::lock_guard<std::mutex> g(lock_);
  long long& need = need_.at(static_cast<std::size_t>(robot));
  if (need == kGone)
    throw std::logic_error("SharedPlume: robot " + std::to_string(robot) + " left");
  if (step < need)
    throw std::logic_error("SharedPlume: robot " + std::to_string(robot) + " promised step " +
                           std::to_string(step) + " after asking for step " + std::to_string(need));
  need = step;
  moved_.notify_all();
}

void SharedPlume::leave(int robot) {
  std::lock_guard<std::mutex> g(lock_);
  need_.at(static_cast<std::size_t>(robot)) = kGone;
  // A robot waiting for this one's steps to pass steps the plume itself when it wakes.
  moved_.notify_all();
}

void SharedPlume::watch(PlumeWatcher* watcher) {
  std::unique_lock<std::mutex> g(lock_);
  while (stepping_)
    moved_.wait(g);
  watcher_ = watcher;
  if (watcher_ != nullptr && step_ % watcher_->every_steps() == 0)
    watcher_->plume_at(step_, sim_.time(), sim_);
}

}  // namespace plumekit::world
