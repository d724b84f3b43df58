#include "world/simulated_world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"
#include "core/random.hpp"
#include "world/random_streams.hpp"

namespace plumekit::world {

namespace {

// Every option checked before the plume is built (its spin-up is the costly part).
const WorldOptions& checked(const WorldOptions& options) {
  options.validate();
  return options;
}

}  // namespace

SimulatedWorld::SimulatedWorld(const Map& map, const cfd::WindField& wind, Vec2 source,
                               const WorldOptions& options, std::uint64_t seed)
    : SimulatedWorld(
          std::make_unique<SharedPlume>(map, wind, source, checked(options).filament, seed, 1),
          nullptr, 0, map, source, options, seed) {}

SimulatedWorld::SimulatedWorld(SharedPlume& plume, int robot, const Map& map, Vec2 source,
                               const WorldOptions& options, std::uint64_t seed)
    : SimulatedWorld(nullptr, &plume, robot, map, source, options, seed) {}

SimulatedWorld::SimulatedWorld(std::unique_ptr<SharedPlume> own, SharedPlume* shared, int robot,
                               const Map& map, Vec2 source, const WorldOptions& options,
                               std::uint64_t seed)
    : own_(std::move(own)),
      plume_(own_ ? *own_ : *shared),
      robot_(robot),
      source_(source),
      options_(options),
      map_(map),
      // Independent streams for the sensors, so noise never shifts the plume.
      noise_rng_(stream_seed(seed, SteStream::SensorNoise)),
      wind_rng_(stream_seed(seed, SteStream::WindNoise)),
      position_rng_(stream_seed(seed, SteStream::PositionNoise)),
      spread_rng_(stream_seed(seed, SteStream::WindSpread)),
      odometry_rng_(stream_seed(seed, SteStream::Odometry)),
      transit_noise_rng_(stream_seed(seed, SteStream::TransitNoise)),
      transit_position_rng_(stream_seed(seed, SteStream::TransitPosition)),
      gas_(options.sensor, 1.0 / options.sample_rate),
      time_(plume_.spinup_s()) {
  try {
    checked(options);
  } catch (...) {
    plume_.leave(robot_);  // the other robots must not wait for this one
    throw;
  }
}

SimulatedWorld::~SimulatedWorld() {
  plume_.leave(robot_);
}

class SimulatedWorld::Busy {
 public:
  explicit Busy(SimulatedWorld& w) : w_(w) {
    if (w_.busy_depth_++ == 0) t0_ = std::chrono::steady_clock::now();
  }
  ~Busy() {
    if (--w_.busy_depth_ == 0)
      w_.busy_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  SimulatedWorld& w_;
  std::chrono::steady_clock::time_point t0_;
};

namespace {

// The whole plume steps of `dt` in `debt` seconds, taken off it: what advance() steps.
long long take_steps(double& debt, double dt) {
  long long steps = 0;
  while (debt >= dt - 1e-12) {
    ++steps;
    debt -= dt;
  }
  return steps;
}

}  // namespace

long long SimulatedWorld::steps_after(double seconds) const {
  double debt = debt_ + seconds;
  return steps_ + take_steps(debt, options_.filament.dt);
}

void SimulatedWorld::advance(double seconds) {
  // Only counted here: the plume steps when this robot next reads it.
  debt_ += seconds;
  const double dt = options_.filament.dt;
  const long long steps = take_steps(debt_, dt);
  for (long long k = 0; k < steps; ++k) {  // summed step by step, as the plume sums its own time
    time_ += dt;
    ++steps_;
    if (watcher_ != nullptr && steps_ % watcher_->every_steps() == 0) notify_watcher();
  }
}

void SimulatedWorld::watch(WorldWatcher* watcher, Vec2 where) {
  watcher_ = watcher;
  where_ = where;
  if (own_) own_->watch(watcher);
  if (watcher_ != nullptr && steps_ % watcher_->every_steps() == 0) notify_watcher();
}

void SimulatedWorld::notify_watcher() {
  Vec2 at = where_;
  if (way_.path != nullptr)
    at = point_along(*way_.path, std::min(way_.metres, (time_ - way_.set_off) * options_.speed));
  watcher_->robot_at(robot_, steps_, time_, at);
}

void SimulatedWorld::travel(const std::vector<Vec2>& path, double metres) {
  const Busy busy(*this);
  const Vec2 drift_before = odometry_error_;
  if (options_.odometry_drift > 0.0 && metres > 0.0) {
    NormalSampler draw;
    const double sd = options_.odometry_drift * std::sqrt(metres);
    odometry_error_ = odometry_error_ + Vec2{normal(draw, odometry_rng_, 0.0, sd),
                                             normal(draw, odometry_rng_, 0.0, sd)};
  }
  const double seconds = metres / options_.speed;
  if (!path.empty()) way_ = {&path, metres, time_};
  if (!reads_while_travelling() || path.size() < 2) {
    advance(seconds);
  } else {
    const double interval = reading_interval();
    const int readings = static_cast<int>(std::floor(seconds / interval));
    leg_ = {drift_before, odometry_error_, metres, true};
    for (int k = 1; k <= readings; ++k)
      pass(path, k * interval * options_.speed);
    leg_.active = false;
    advance(seconds - readings * interval);
  }
  if (!path.empty()) where_ = path.back();
  way_ = {};
}

void SimulatedWorld::pass(const std::vector<Vec2>& path, double along) {
  const Busy busy(*this);
  if (way_.path == nullptr && !path.empty()) where_ = point_along(path, along);  // a team's
  advance(reading_interval());
  if (!reads_while_travelling() || path.empty()) return;
  const Vec2 p = point_along(path, along);
  const double value = gas_.read(exposure(plume(), p));
  if (options_.read_while_moving) record_transit(p, along, value);
}

void SimulatedWorld::record_transit(Vec2 p, double along, double value) {
  TransitReading r;
  r.position = p;
  r.recorded = p;
  if (options_.position_noise > 0.0)
    r.recorded = fix(p, options_.position_noise, transit_position_rng_);
  if (options_.odometry_drift > 0.0) {
    // Outside travel() (a team's pass(), which runs without odometry) the drift so far.
    Vec2 drift = odometry_error_;
    if (leg_.active && leg_.metres > 0.0)
      drift = leg_.from + std::clamp(along / leg_.metres, 0.0, 1.0) * (leg_.to - leg_.from);
    r.recorded = r.recorded + drift;
  }
  r.time_s = time_;
  r.value = value;
  if (options_.noise > 0.0)
    r.value =
        std::max(0.0, value + normal(transit_noise_, transit_noise_rng_, 0.0, options_.noise));
  transit_.push_back(r);
}

std::vector<TransitReading> SimulatedWorld::take_transit_readings() {
  std::vector<TransitReading> taken;
  taken.swap(transit_);
  return taken;
}

std::vector<Vec2> disc_points(Vec2 centre, double radius) {
  std::vector<Vec2> points{centre};
  // Ring k stands for the annulus between the areas of (sum of earlier points) and (that plus
  // its own) nineteenths of the disc, and lies at that annulus's area midpoint.
  const struct {
    int count;
    double radius2, offset;
  } rings[] = {{6, 4.0 / 19.0, 0.0}, {12, 13.0 / 19.0, kPi / 12.0}};
  for (const auto& ring : rings)
    for (int k = 0; k < ring.count; ++k) {
      const double a = ring.offset + 2.0 * kPi * k / ring.count;
      const double r = radius * std::sqrt(ring.radius2);
      points.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a)});
    }
  return points;
}

double SimulatedWorld::exposure(const world::PlumeFrame& plume, Vec2 p) const {
  if (options_.rotor_disc <= 0.0) return plume.concentration_at(p);
  // The downwash mixes the air it reaches: the disc's points outside walls and obstacles do not
  // count (the robot's own position always does).
  const std::vector<Vec2> points = disc_points(p, options_.rotor_disc);
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (k == 0 || map_.is_free(points[k])) {  // points[0] is p
      sum += plume.concentration_at(points[k]);
      ++n;
    }
  return sum / n;
}

Vec2 SimulatedWorld::fix(Vec2 p, double sd, std::mt19937_64& rng) const {
  NormalSampler draw;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const Vec2 q{p.x + normal(draw, rng, 0.0, sd), p.y + normal(draw, rng, 0.0, sd)};
    if (map_.is_free(q)) return q;
  }
  return p;
}

Reading SimulatedWorld::stop(Vec2 p) {
  const Busy busy(*this);
  begin_stop(p);
  while (!stop_reading()) {
  }
  return end_stop();
}

void SimulatedWorld::begin_stop(Vec2 p) {
  where_ = p;
  stop_ = StopState{};
  stop_.p = p;
  stop_.readings =
      std::max(1, static_cast<int>(std::lround(options_.sample_s * options_.sample_rate)));
}

bool SimulatedWorld::stop_reading() {
  const Busy busy(*this);
  if (stop_.taken >= stop_.readings)
    throw std::logic_error("SimulatedWorld: a reading after the stop's last (begin_stop first)");
  const Vec2 p = stop_.p;
  const world::PlumeFrame& plume_now = plume();
  double c = gas_.read(exposure(plume_now, p));
  if (options_.noise > 0.0)
    c = std::max(0.0, c + normal(stop_.noise, noise_rng_, 0.0, options_.noise));
  stop_.sum += c;
  if (options_.adaptive_stop) stop_.values.push_back(c);
  const Vec2 w = plume_now.wind_at(p);
  stop_.wind_sum = stop_.wind_sum + w;
  if (options_.wind_variance_noise_deg > 0.0) {
    const double a =
        std::atan2(w.y, w.x) +
        normal(stop_.spread, spread_rng_, 0.0, options_.wind_variance_noise_deg) * kPi / 180.0;
    stop_.direction_sum = stop_.direction_sum + Vec2{std::cos(a), std::sin(a)};
  } else if (const double speed = norm(w); speed > 0.0) {
    stop_.direction_sum = stop_.direction_sum + (1.0 / speed) * w;
  }
  advance(reading_interval());
  if (++stop_.taken == stop_.readings) return true;
  if (!options_.adaptive_stop || !stop_settled()) return false;
  stop_.readings = stop_.taken;  // the stop ends here: its mean is of the readings taken
  return true;
}

bool SimulatedWorld::stop_settled() const {
  const int per_second = std::max(1, static_cast<int>(std::lround(options_.sample_rate)));
  if (stop_.taken % per_second != 0 ||
      stop_.taken * reading_interval() < options_.stop_min_s - 1e-9)
    return false;
  const std::size_t per_half = static_cast<std::size_t>(std::max(1, per_second / 2));
  const std::size_t m = stop_.values.size() / per_half;
  if (m < 2) return false;
  std::vector<double> means(m, 0.0);
  for (std::size_t k = 0; k < m * per_half; ++k)
    means[k / per_half] += stop_.values[k] / static_cast<double>(per_half);
  double mean = 0.0, ss = 0.0;
  for (double x : means)
    mean += x / static_cast<double>(m);
  for (double x : means)
    ss += (x - mean) * (x - mean);
  const double standard_error = std::sqrt(ss / static_cast<double>(m - 1) / static_cast<double>(m));
  return standard_error <= options_.stop_tolerance;
}

Reading SimulatedWorld::end_stop() {
  if (stop_.readings == 0 || stop_.taken < stop_.readings)
    throw std::logic_error("SimulatedWorld: end_stop before the stop's readings are taken");
  const Vec2 p = stop_.p;
  const int n = stop_.readings;
  Reading r;
  r.gas = stop_.sum / n;
  r.wind = (1.0 / n) * stop_.wind_sum;
  r.wind_variance = std::clamp(1.0 - norm((1.0 / n) * stop_.direction_sum), 0.0, 1.0);
  stop_.readings = 0;
  if (const double sigma = options_.direction_noise_deg(); sigma > 0.0) {
    NormalSampler draw;
    const double a = normal(draw, wind_rng_, 0.0, sigma) * kPi / 180.0;
    r.wind = {std::cos(a) * r.wind.x - std::sin(a) * r.wind.y,
              std::sin(a) * r.wind.x + std::cos(a) * r.wind.y};
  }
  r.position = p;
  if (options_.position_noise > 0.0) {
    // The mean of n independent fixes is drawn at once, with its std.
    const double sd = options_.position_noise_per_fix
                          ? options_.position_noise / std::sqrt(static_cast<double>(n))
                          : options_.position_noise;
    r.position = fix(p, sd, position_rng_);
  }
  if (options_.odometry_drift > 0.0) r.position = r.position + odometry_error_;
  return r;
}

double WorldOptions::direction_noise_deg() const {
  return wind_noise_from_table35 ? table35_direction_noise(sample_s) : wind_direction_noise_deg;
}

double table35_direction_noise(double averaging_s) {
  const double t[] = {0.0, 5.0, 10.0, 20.0}, rmse[] = {29.12, 22.26, 17.76, 14.02};
  if (averaging_s <= 0.0) return rmse[0];
  for (int k = 1; k < 4; ++k)
    if (averaging_s <= t[k])
      return rmse[k - 1] + (rmse[k] - rmse[k - 1]) * (averaging_s - t[k - 1]) / (t[k] - t[k - 1]);
  return rmse[3];
}

}  // namespace plumekit::world
