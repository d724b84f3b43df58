#include "world/shared_plume.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace plumekit::world {

namespace {
constexpr long long kGone = std::numeric_limits<long long>::max();
}

SharedPlume::SharedPlume(const Map& map, const cfd::WindField& wind, Vec2 source,
                         const world::FilamentOptions& options, std::uint64_t seed, int robots)
    : sim_(map, wind, source, options, seed) {
  if (robots < 1) throw std::logic_error("SharedPlume: at least one robot");
  world::spin_up(sim_, options);
  spinup_s_ = sim_.time();
  need_.assign(static_cast<std::size_t>(robots), 0);
}

const world::FilamentSimulation& SharedPlume::at(long long step, int robot) {
  std::unique_lock<std::mutex> g(lock_);
  long long& need = need_.at(static_cast<std::size_t>(robot));
  if (step < need || need == kGone)
    throw std::logic_error("SharedPlume: robot " + std::to_string(robot) + " asked for step " +
                           std::to_string(step) + " after step " + std::to_string(need));
  need = step;
  // Invariant: the plume is never past any robot's need, so nobody reads while it steps.
  while (step_ < step) {
    const long long earliest = *std::min_element(need_.begin(), need_.end());
    if (earliest > step_) {
      while (step_ < earliest) {
        sim_.step();
        ++step_;
      }
      moved_.notify_all();
    } else {
      moved_.wait(g);
    }
  }
  return sim_;
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

}  // namespace plumekit::world
