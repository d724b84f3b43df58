#include "world/filament_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/seed.hpp"
#include "world/option_tables.hpp"

namespace plumekit::world {

namespace {

// Mixed into the plume's seed for the unsteady wind's own random stream.
constexpr std::uint64_t kFluctuationStream = 0x77696e64;  // "wind"

// Whether an outlet on an arena wall covers position s along that wall.
bool outlet_on_wall(const Map& map, Side side, double s) {
  const int k = map.opening_on_wall(side, s);
  return k >= 0 && !map.openings[static_cast<std::size_t>(k)].is_inlet();
}

// Whether the move from a to b crosses an outlet on an obstacle's edge.
bool through_obstacle_outlet(const Map& map, Vec2 a, Vec2 b) {
  for (const Opening& o : map.openings)
    if (!o.is_inlet() && !map.wall_of(o) && segments_intersect(a, b, o.from, o.to)) return true;
  return false;
}

}  // namespace

// Bounds well beyond any useful setting: they catch NaN, signs and unit
// mistakes (docs/design/dataset.md, "Options").
namespace {

using Entries = std::vector<OptionEntry<FilamentOptions>>;

// The release and the filaments' motion.
Entries filament_motion_entries() {
  using O = FilamentOptions;
  return {
      {"plume.filaments_per_second", "--filaments-per-second", &O::release_per_second,
       positive(1e5, "per second"), "filament: filaments released per second",
       "the default is {default} (more only lowers the sampling noise)"},
      {"plume.release_rate", "", &O::release_rate, positive(1e9, "concentration units * m^2/s"),
       "Release rate per metre of depth (concentration units * m^2/s)", "the default is {default}"},
      {"plume.initial_radius", "", &O::initial_radius, positive(10.0, "m"),
       "Filament radius at release, m"},
      {"plume.source_radius", "", &O::source_radius, non_negative(100.0, "m"),
       "Radius of the source disc the filaments leave from, m (0: its point)",
       "0 releases at the source's point; seed 002's source is 0.2 m"},
      {"plume.growth", "", &O::growth, non_negative(100.0, "m^2/s"), "dR^2/dt, m^2/s"},
      {"plume.sigma_walk", "", &O::sigma_walk, non_negative(100.0, "m/sqrt(s)"),
       "Random walk of each filament, m/sqrt(s)"},
      {"plume.meander_speed", "", &O::meander_speed, non_negative(100.0, "m/s"),
       "Meander std per axis, m/s"},
      {"plume.meander_time", "", &O::meander_time, positive(1e4, "s"),
       "Meander correlation time, s"},
      {"plume.meander_length", "", &O::meander_length, positive(1e4, "m"),
       "Unsteady wind: meander wavelength, m"},
      {"plume.meander_wall_layer", "", &O::meander_wall_layer, positive(1e4, "m"),
       "Unsteady wind: meander fade distance at walls, m"},
      {"plume.dt", "", &O::dt, positive(10.0, "s"), "Integration step, s"},
      {"plume.max_radius",
       "",
       &O::max_radius,
       {},
       "Filaments wider than this are dropped, m",
       "",
       "more than plume.initial_radius and at most 1000 m"},
      {"plume.occlusion",
       "",
       &O::occlusion,
       {},
       "Gas stops at walls (line of sight; --world, --occlusion)"},
      {"plume.unsteady_wind",
       "",
       &O::unsteady_wind,
       {},
       "Meander as a field fading at walls (--world, --wind-model)"},
      {"plume.threads", "", &O::threads, count_range(0, 1024),
       "Threads of one plume's step, 0: one per core (the plume does not depend on it)"},
      {"plume.engine",
       "",
       enum_field(&O::engine, &to_string, &parse_plume_engine, "fast, v1"),
       {},
       "How the plume is computed: fast, or v1 (before issue 45; --world faithful-v1)"}};
}

// The spin-up to a statistically steady plume and the recording.
Entries filament_time_entries() {
  using O = FilamentOptions;
  return {{"plume.steady_window", "", &O::steady_window, positive(1e4, "s"),
           "Spin-up steadiness window, s"},
          {"plume.steady_tolerance", "", &O::steady_tolerance, positive(1.0, ""),
           "Spin-up steadiness tolerance"},
          {"plume.min_spinup", "", &O::min_spinup, non_negative(1e5, "s"), "Shortest spin-up, s"},
          {"plume.max_spinup",
           "",
           &O::max_spinup,
           {},
           "Longest spin-up, s",
           "",
           "from plume.min_spinup to 100000 s"},
          {"plume.record_s", "", &O::record_s, positive(1e5, "s"), "Recording length, s"},
          {"plume.sample_rate", "", &O::sample_rate, positive(1e3, "Hz"),
           "Sensor reads per second, Hz"},
          {"plume.cutoff", "", &O::cutoff, positive(10.0, "filament radii"),
           "Kernels are summed out to this many radii", "the default is {default}"}};
}

}  // namespace

const OptionTable<FilamentOptions>& filament_option_table() {
  static const OptionTable<FilamentOptions> table = [] {
    OptionTable<FilamentOptions> t{"Filament plume (world::FilamentOptions)",
                                   filament_motion_entries()};
    for (auto& e : filament_time_entries())
      t.entries.push_back(e);
    return t;
  }();
  return table;
}

void FilamentOptions::validate() const {
  const OptionTable<FilamentOptions>& table = filament_option_table();
  plumekit::validate(table, *this);
  check_range("plume.max_radius", max_radius, initial_radius, 1e3, "m",
              "it must exceed plume.initial_radius; the default is " +
                  default_text(table.entry("plume.max_radius")) + " m",
              true);
  check_range("plume.max_spinup", max_spinup, min_spinup, 1e5, "s",
              "it must be at least plume.min_spinup; the default is " +
                  default_text(table.entry("plume.max_spinup")) + " s");
  // The step count bounds the run time: a tiny dt over a long spin-up never ends.
  const double steps = (max_spinup + record_s) / dt;
  if (steps > 1e8)
    throw OptionError("plume.dt", compact(dt) + " s gives " + compact(steps) +
                                      " steps over the spin-up and the recording, more than "
                                      "1e+08; use a larger dt or shorter times");
}

const char* to_string(PlumeEngine engine) {
  return engine == PlumeEngine::V1 ? "v1" : "fast";
}

PlumeEngine parse_plume_engine(const std::string& name) {
  if (name == "fast") return PlumeEngine::Fast;
  if (name == "v1") return PlumeEngine::V1;
  throw OptionError("plume.engine", "unknown engine '" + name + "'; use fast or v1");
}

void set_world(FilamentOptions& options, const std::string& name) {
  const bool v1 = name.size() > 3 && name.compare(name.size() - 3, 3, "-v1") == 0;
  const std::string preset = v1 ? name.substr(0, name.size() - 3) : name;
  if (preset != "faithful" && preset != "thesis" && preset != "neumann")
    throw OptionError("plume.world", "unknown world '" + name +
                                         "'; use faithful, thesis or neumann, or one of them "
                                         "with -v1 (faithful-v1: the world before issue 45)");
  options.engine = v1 ? PlumeEngine::V1 : PlumeEngine::Fast;
  options.occlusion = options.unsteady_wind = preset == "faithful";
  if (preset != "neumann") return;
  // Seed 000 Eqs. 4.1-4.2 with its step taken as 0.1 s (the seed gives none), also the
  // integration step (5 cm at 0.5 m/s: one flow cell): a walk of
  // sigma_p = 0.1 m per step is 0.1 / sqrt(0.1) m/sqrt(s), and R grows by gamma / (2 R) per step
  // with gamma = 4e-7, i.e. dR^2/dt = gamma / 0.1 s. "Predominantly laminar": no meander.
  constexpr double kSeedStep = 0.1;
  options.release_per_second = 500.0;
  options.initial_radius = 0.2;
  options.source_radius = 0.2;
  options.sigma_walk = 0.1 / std::sqrt(kSeedStep);
  options.growth = 4e-7 / kSeedStep;
  options.meander_speed = 0.0;
  options.dt = kSeedStep;
  // The plume takes 64 s to cross the tunnel at 0.5 m/s (the seed shows it at 99 s).
  options.min_spinup = 100.0;
  options.max_spinup = 200.0;
}

double FilamentOptions::max_filaments() const {
  return release_per_second * (max_spinup + record_s) + 1.0;
}

FilamentSimulation::FilamentSimulation(const Map& map, const cfd::WindField& wind, Vec2 source,
                                       const FilamentOptions& options, std::uint64_t seed)
    : map_(map),
      wind_(wind),
      source_(source),
      o_(options),
      seed_(seed),
      rng_(seed),
      obstacles_(map, wind.shape()) {
  o_.validate();
  // The filament arrays at their largest (position, R^2, release number, and the sensor index's
  // copies), twice over for their growth by doubling.
  constexpr double kBytesPerFilament = 2.0 * (7 * sizeof(double) + sizeof(std::uint64_t));
  const double bytes = kBytesPerFilament * o_.max_filaments();
  if (!fits_in_memory(bytes)) {
    const double fits = memory_limit() / (kBytesPerFilament * (o_.max_spinup + o_.record_s));
    check_memory(
        bytes, "the filament model at " + compact(o_.release_per_second) + " filaments per second",
        "use fewer plume.filaments_per_second (" + compact(std::floor(0.9 * fits)) + " fits)");
  }
  if (!map.is_free(source))
    throw InputError("filament model: source " + to_string(source) +
                     " is outside the arena or inside an obstacle");
  mass_ = o_.release_rate / o_.release_per_second;
  if (o_.engine == PlumeEngine::V1) clear_ = clear_cells_v1(map, wind.shape());
  if (o_.engine == PlumeEngine::Fast && o_.threads != 1)
    pool_ = std::make_unique<ThreadPool>(o_.threads);
  if (o_.occlusion) sight_ = std::make_unique<LineOfSight>(map);
  if (o_.unsteady_wind) {
    world::FluctuationOptions f;
    f.intensity = o_.meander_speed;
    f.time_scale = o_.meander_time;
    f.length_scale = o_.meander_length;
    f.wall_layer = o_.meander_wall_layer;
    // Its own stream, derived from the plume's seed.
    fluctuation_ =
        std::make_unique<world::FluctuatingWind>(wind, f, splitmix64(seed ^ kFluctuationStream));
  }
}

std::vector<Filament> FilamentSimulation::filaments() const {
  std::vector<Filament> out;
  out.reserve(x_.size());
  for (std::size_t k = 0; k < x_.size(); ++k)
    out.push_back(filament(k));
  return out;
}

bool FilamentSimulation::free_at(Vec2 p) const {
  if (!map_.in_arena(p)) return false;
  if (o_.engine == PlumeEngine::Fast) return obstacles_.free(p);
  // V1 as it was, cost included (bench/world_bench measures the fast engine against it).
  const GridShape& s = wind_.shape();
  const int i = std::min(s.nx - 1, static_cast<int>(p.x / s.dx()));
  const int j = std::min(s.ny - 1, static_cast<int>(p.y / s.dy()));
  return clear_[s.index(i, j)] || map_.obstacle_at(p) < 0;
}

void FilamentSimulation::add_filament(Vec2 p) {
  x_.push_back(p.x);
  y_.push_back(p.y);
  r2_.push_back(o_.initial_radius * o_.initial_radius);
  serial_.push_back(static_cast<std::uint64_t>(summary_.released));
  ++summary_.released;
}

void FilamentSimulation::release_filaments(double dt) {
  release_debt_ += o_.release_per_second * dt;
  while (release_debt_ >= 1.0) {
    add_filament(o_.engine == PlumeEngine::V1
                     ? release_point_v1()
                     : release_point_fast(static_cast<std::uint64_t>(summary_.released)));
    release_debt_ -= 1.0;
  }
}

FilamentSimulation::Move FilamentSimulation::settle(Vec2 from, Vec2& p) const {
  const double W = map_.width, H = map_.height;
  // Through an arena wall: gone if through the outlet, else reflected.
  bool gone = false;
  if (p.x < 0.0 || p.x > W) {
    const Side side = p.x < 0.0 ? Side::Left : Side::Right;
    if (outlet_on_wall(map_, side, std::clamp(p.y, 0.0, H))) gone = true;
    p.x = p.x < 0.0 ? -p.x : 2.0 * W - p.x;
  }
  if (p.y < 0.0 || p.y > H) {
    const Side side = p.y < 0.0 ? Side::Bottom : Side::Top;
    if (outlet_on_wall(map_, side, std::clamp(p.x, 0.0, W))) gone = true;
    p.y = p.y < 0.0 ? -p.y : 2.0 * H - p.y;
  }
  if (gone) return Move::Left;
  p.x = std::clamp(p.x, 0.0, W);
  p.y = std::clamp(p.y, 0.0, H);
  if (free_at(p)) return Move::Kept;
  // Out through a door or vent in an obstacle's edge, or into an obstacle: the move is not taken.
  return through_obstacle_outlet(map_, from, p) ? Move::Left : Move::Rejected;
}

void FilamentSimulation::close_up(std::size_t n, const Moved& fates) {
  x_.resize(n);
  y_.resize(n);
  r2_.resize(n);
  serial_.resize(n);
  summary_.left_through_outlet += fates.left;
  summary_.rejected_moves += fates.rejected;
  summary_.dropped_too_wide += fates.dropped;
}

void FilamentSimulation::step() {
  if (o_.engine == PlumeEngine::V1)
    step_v1();
  else
    step_fast();
  ++steps_;
}

namespace {

// The sensor grid's concentrations, frame after frame of simulate_filaments' record.
class FrameSampler {
 public:
  FrameSampler(FilamentSimulation& sim, const GridShape& sensors, int steps_per_frame)
      : sim_(sim), sensors_(sensors), steps_per_frame_(steps_per_frame), frame_(sensors.size()) {}
  // The concentrations of the next frame, one frame's time after the last (the first: now).
  const std::vector<double>& next() {
    if (!first_)
      for (int s = 0; s < steps_per_frame_; ++s)
        sim_.step();
    first_ = false;
    std::fill(frame_.begin(), frame_.end(), 0.0);
    sim_.concentration(sensors_, frame_);
    return frame_;
  }

 private:
  FilamentSimulation& sim_;
  const GridShape& sensors_;
  int steps_per_frame_;
  std::vector<double> frame_;
  bool first_ = true;
};

// One gas sensor per cell, or none when the model reads the concentration as it is. A sensor with
// memory is settled in the first frame and read through its warm-up before the record starts,
// whose time goes to summary.sensor_warmup_s.
std::vector<GasSensor> warmed_up_sensors(FrameSampler& frames, std::size_t cells,
                                         const GasSensorModel& sensor,
                                         const FilamentOptions& options, FilamentSummary& summary) {
  std::vector<GasSensor> readers;
  if (sensor.ideal() && sensor.baseline == 0.0) return readers;
  readers.assign(cells, GasSensor(sensor, 1.0 / options.sample_rate));
  if (sensor.ideal()) return readers;
  const std::vector<double>& frame = frames.next();
  for (std::size_t k = 0; k < frame.size(); ++k)
    readers[k].settle(frame[k]);
  const int warmup = static_cast<int>(std::lround(sensor_warmup_s(sensor) * options.sample_rate));
  for (int w = 0; w < warmup; ++w) {
    frames.next();
    for (std::size_t k = 0; k < frame.size(); ++k)
      readers[k].read(frame[k]);
  }
  summary.sensor_warmup_s = (warmup + 1) / options.sample_rate;
  return readers;
}

// The record's mean and standard deviation from the readings' sums over `frames` frames; zero
// for a sensor inside an obstacle.
void set_statistics(const Map& map, const GridShape& sensors, const std::vector<double>& sum,
                    const std::vector<double>& sum2, int frames, SensorRecord& rec) {
  rec.mean = Grid<double>(sensors, 0.0);
  rec.std = Grid<double>(sensors, 0.0);
  for (int j = 0; j < sensors.ny; ++j)
    for (int i = 0; i < sensors.nx; ++i) {
      if (map.obstacle_at(sensors.centre(i, j)) >= 0) continue;  // a sensor inside an obstacle
      const std::size_t k = sensors.index(i, j);
      const double m = sum[k] / frames;
      rec.mean.values[k] = m;
      rec.std.values[k] = std::sqrt(std::max(0.0, sum2[k] / frames - m * m));
    }
}

}  // namespace

SensorRecord simulate_filaments(const Map& map, const cfd::WindField& wind, Vec2 source,
                                const GridShape& sensors, const FilamentOptions& options,
                                std::uint64_t seed, const GasSensorModel& sensor) {
  const auto t0 = std::chrono::steady_clock::now();
  FilamentSimulation sim(map, wind, source, options, seed);
  const bool steady = spin_up(sim, options);
  SensorRecord rec;
  rec.summary = sim.summary();
  rec.summary.spinup_s = sim.time();
  rec.summary.steady = steady;

  const int frames =
      std::max(1, static_cast<int>(std::lround(options.record_s * options.sample_rate)));
  const int steps_per_frame =
      std::max(1, static_cast<int>(std::lround(1.0 / (options.sample_rate * options.dt))));
  std::vector<double> sum(sensors.size(), 0.0), sum2(sensors.size(), 0.0);
  FrameSampler sampler(sim, sensors, steps_per_frame);
  std::vector<GasSensor> readers =
      warmed_up_sensors(sampler, sensors.size(), sensor, options, rec.summary);
  for (int f = 0; f < frames; ++f) {
    const std::vector<double>& frame = sampler.next();
    for (std::size_t k = 0; k < frame.size(); ++k) {
      const double c = readers.empty() ? frame[k] : readers[k].read(frame[k]);
      sum[k] += c;
      sum2[k] += c * c;
    }
  }
  set_statistics(map, sensors, sum, sum2, frames, rec);
  const FilamentSummary& end = sim.summary();
  rec.summary.released = end.released;
  rec.summary.rejected_moves = end.rejected_moves;
  rec.summary.left_through_outlet = end.left_through_outlet;
  rec.summary.dropped_too_wide = end.dropped_too_wide;
  rec.summary.filaments_at_end = static_cast<int>(sim.filament_count());
  rec.summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rec;
}

}  // namespace plumekit::world
