#include "run/scenario.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "cfd/flow_policy.hpp"
#include "cfd/gap_closing.hpp"
#include "cfd/wind_file.hpp"
#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/random.hpp"
#include "core/resample.hpp"
#include "map/connectivity.hpp"
#include "map/rasterize.hpp"
#include "ste/cached_readings.hpp"
#include "ste/grid_estimator.hpp"
#include "ste/surrogate_plume.hpp"
#include "surrogate/model_file.hpp"
#include "surrogate/plume_network.hpp"
#include "world/random_streams.hpp"

namespace plumekit::run {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Bytes per candidate source cell: the estimators' sums and likelihoods and
// one table column, a few doubles each. The surrogate also ties each candidate
// to up to four table cells (32 bytes each); its table, one mean and std plume
// per table cell, is checked where it is built (SurrogatePlume).
constexpr double kBytesPerSourceCell = 128.0;
constexpr double kSurrogateBytesPerSourceCell = kBytesPerSourceCell + 4 * 32;
// The physics model adds its resampling weights (four per cell) and the readings and gains it
// makes per decision: peak RSS grows by 216-221 bytes per cell (10 x 4 m, 1.6 and 3.3 million
// cells, issue 44), where 128 let 4e7 cells of 1 mm pass a 5.5 GB limit and then run out of memory.
constexpr double kPhysicsBytesPerSourceCell = 256.0;

void check_source_grid(const Map& map, double cell, const std::string& field,
                       double bytes_per_cell) {
  const double cells = std::round(map.width / cell) * std::round(map.height / cell);
  const double most = std::min(1e8, memory_limit() / bytes_per_cell);
  const std::string fit = compact(1.01 * std::sqrt(map.width * map.height / most));
  if (cells > 1e8)
    throw OptionError(field, compact(cell) + " m gives " + compact(cells) +
                                 " candidate source cells, more than 1e+08; use at least " + fit +
                                 " m");
  check_memory(cells * bytes_per_cell,
               "the source grid of " + compact(cells) + " cells of " + compact(cell) + " m",
               "use a larger " + field + " (" + fit + " m fits)");
}

// The plume model of `options.model` on `map` (a surrogate's table on `table_cell`); `from_cache`
// says whether a surrogate table came from its cache.
std::unique_ptr<ste::ForwardModel> make_model(const Map& map, const cfd::WindField& wind,
                                              const SteOptions& options, double table_cell,
                                              bool& from_cache) {
  switch (options.model) {
    case PlumeModelKind::Gaussian:
      return std::make_unique<ste::GaussianPlume>(map, options.gaussian);
    case PlumeModelKind::Physics: {
      ste::PhysicsPlumeOptions po = options.physics;
      po.source_cell = options.source_cell_in_use();
      return std::make_unique<ste::PhysicsPlume>(map, wind, po);
    }
    case PlumeModelKind::Surrogate:
      break;
  }
  ste::SurrogatePlumeOptions so;
  so.model = options.model_path;
  so.source_cell = options.source_cell_in_use();
  so.table_cell = table_cell;
  so.threads = options.threads;
  so.cache_dir = options.table_cache;
  so.scale_lo = options.physics.scale_lo;
  so.scale_hi = options.physics.scale_hi;
  so.wind = &wind;
  auto m = std::make_unique<ste::SurrogatePlume>(map, so);
  from_cache = m->from_cache();
  return m;
}

}  // namespace

const char* to_string(PlumeModelKind kind) {
  switch (kind) {
    case PlumeModelKind::Surrogate:
      return "surrogate";
    case PlumeModelKind::Gaussian:
      return "gaussian";
    case PlumeModelKind::Physics:
      return "physics";
  }
  return "?";
}

const char* to_string(SamplingProtocol protocol) {
  return protocol == SamplingProtocol::Thesis ? "thesis" : "moving";
}

SamplingProtocol parse_sampling_protocol(const std::string& name) {
  if (name == "moving") return SamplingProtocol::Moving;
  if (name == "thesis") return SamplingProtocol::Thesis;
  throw OptionError("ste.protocol", "unknown protocol '" + name + "'; use moving or thesis");
}

world::WorldOptions protocol_world(SamplingProtocol protocol) {
  world::WorldOptions w;
  w.read_while_moving = w.adaptive_stop = protocol == SamplingProtocol::Moving;
  return w;
}

ste::StopOptions protocol_stop(SamplingProtocol protocol) {
  ste::StopOptions stop;
  if (protocol == SamplingProtocol::Moving) {
    stop.confidence_radius = 0.3;
    stop.confidence_mass = 0.95;
  }
  return stop;
}

void set_protocol(SteOptions& options, SamplingProtocol protocol) {
  options.protocol = protocol;
  const world::WorldOptions w = protocol_world(protocol);
  options.world.read_while_moving = w.read_while_moving;
  options.world.adaptive_stop = w.adaptive_stop;
  const ste::StopOptions stop = protocol_stop(protocol);
  options.stop.confidence_radius = stop.confidence_radius;
  options.stop.confidence_mass = stop.confidence_mass;
  options.approach = protocol == SamplingProtocol::Moving;
}

ste::LikelihoodOptions default_likelihood(PlumeModelKind kind, SamplingProtocol protocol) {
  ste::LikelihoodOptions l;
  if (kind == PlumeModelKind::Surrogate) {
    l.sigma_m = 200.0;
    l.sigma_std = protocol == SamplingProtocol::Thesis ? 2.0 : 1.0;
  } else if (kind == PlumeModelKind::Physics) {
    l.sigma_m = 150.0;
    l.sigma_rel = 0.15;
  }
  return l;
}

PlumeModelKind parse_plume_model_kind(const std::string& name) {
  if (name == "surrogate") return PlumeModelKind::Surrogate;
  if (name == "gaussian") return PlumeModelKind::Gaussian;
  if (name == "physics") return PlumeModelKind::Physics;
  throw OptionError("ste.model",
                    "unknown plume model '" + name + "'; use surrogate, gaussian or physics");
}

std::string run_label(const SteOptions& options) {
  return uses_plume_model(options.method.name) ? std::string(to_string(options.model))
                                               : options.method.name;
}

Scenario::Scenario(const Map& map, const SteOptions& options) : Scenario(map, options, nullptr) {}

Scenario::Scenario(const Map& map, const SteOptions& options, const Scenario& same_map)
    : Scenario(map, options, &same_map) {}

Scenario::Scenario(const Map& map, const SteOptions& options, const Scenario* same_map)
    : map_(map), options_(options), passing_(options.passing_options()) {
  options.validate();
  options_.navigation.candidates = resolve_candidates(options.navigation.candidates, map);
  const bool model = uses_plume_model(options.method.name);
  if (model && options.model == PlumeModelKind::Physics)
    check_source_grid(map_, options.source_cell_in_use(), "ste.source_cell",
                      kPhysicsBytesPerSourceCell);
  if (options.uses_cnn())
    check_source_grid(map_, options.source_cell_in_use(), "ste.source_cell",
                      kSurrogateBytesPerSourceCell);
  // A fixed-grid model on a map of another size is refused before the wind is solved.
  if (options.uses_cnn())
    surrogate::check_map_size(surrogate::read_model_file(options.model_path).features, map_);
  auto t0 = Clock::now();
  if (same_map) {
    wind_ = same_map->wind_;
    wind_s_ = same_map->wind_s_;
  } else {
    wind_ = options.wind_dir.empty() ? cfd::solve_wind(map_, options.flow).flow.wind  // the policy
                                     : cfd::read_wind(options.wind_dir, map_);
    wind_s_ = since(t0);
  }
  t0 = Clock::now();
  if (model) {
    table_cell_ = options.table_cell_in_use(map_);  // counts the free space once
    model_ = make_model(map_, wind_, options, table_cell_, table_from_cache_);
  }
  model_build_s_ = since(t0);
  planner::PlannerOptions po;
  po.margin = options.margin;
  planner_ = planner::make_planner(map_, po);
  space_ = std::make_unique<planner::FreeSpace>(map_, po.margin, po.arc_segments);
  if (space_->empty()) throw InputError("map " + map_.name + ": no free space at the margin");
  bins_ = ste::make_bins(map_, options.bins);
  navigator_ =
      std::make_unique<ste::Navigator>(*space_, bins_, options_.navigation, options.mission_pace());
  options_.stop.max_samples =
      ste::resolve_max_samples(options.stop.max_samples, navigator_->floor_goals().size(),
                               options_.navigation.floor_spacing);
  // The floor's goals are scored at every decision: their readings are tabulated once here, as
  // part of the model's build.
  const ste::SourceTableModel* table_model = model_ ? model_->as_source_table() : nullptr;
  if (!navigator_->floor_goals().empty() && table_model) {
    t0 = Clock::now();
    const double goals = static_cast<double>(navigator_->floor_goals().size());
    const double cells = static_cast<double>(table_model->candidates().size());
    check_memory(goals * ste::CachedReadings::bytes_per_point(*table_model) +
                     ste::CachedReadings::kRecentBytes,
                 "the readings at " + compact(goals) + " floor goals for " + compact(cells) +
                     " source cells, and the recent moves' readings",
                 "use a larger ste.navigation.floor_spacing or ste.source_cell");
    std::unique_ptr<ste::SourceTableModel> table(
        static_cast<ste::SourceTableModel*>(model_.release()));
    model_ = std::make_unique<ste::CachedReadings>(std::move(table), navigator_->floor_goals(),
                                                   options.threads);
    model_build_s_ += since(t0);
  }
}

Scenario::~Scenario() = default;

namespace {

// Why the wind leaves a source `p` (free in the map) no free cell near it, or
// "": its gas would have nowhere to go, and the mean plume (advection-diffusion)
// no cell to release it in. The flow grid makes solid what no outlet drains.
std::string flow_grid_fault(const Map& map, const cfd::WindField& wind, Vec2 p) {
  if (!free_bilinear_weights(wind.shape(), wind.solid_cells(), p).empty()) return "";
  Grid<std::uint8_t> solid = rasterize_occupancy(map, wind.shape());
  cfd::close_narrow_gaps(map, wind.shape(), solid.values);  // as the flow grid does
  const std::string at = to_string(map.to_frame(p));
  if (in_sealed_pocket(rasterize_labels(map, solid), {p}).front())
    return at + " " + kSealedPocket + " (on the flow grid's " + compact(wind.shape().dx()) +
           " m cells); move the source, or add an opening on the pocket's boundary";
  return at + " lies in no free cell of the flow grid (" + compact(wind.shape().dx()) +
         " m): its free space is closed off by gaps narrower than a cell, or no outlet drains it";
}

}  // namespace

Vec2 Scenario::check_source(Vec2 source) const {
  if (const std::string fault = point_fault(map_, source); !fault.empty())
    throw OptionError("ste.source", fault);
  if (const std::string fault = flow_grid_fault(map_, wind_, source); !fault.empty())
    throw OptionError("ste.source", fault);
  return source;
}

Vec2 Scenario::check_start(Vec2 start) const {
  if (const std::string fault = point_fault(map_, start); !fault.empty())
    throw OptionError("ste.start", fault);
  return space_->contains(start) ? start : space_->nearest_free(start);
}

int Scenario::region_reaching(Vec2 p) const {
  return space_->region_of(space_->nearest_free(p));
}

Vec2 Scenario::random_start(Vec2 source, std::uint64_t seed) const {
  const int region = region_reaching(source);
  std::mt19937_64 rng(seed);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const double x = uniform(rng, 0.0, map_.width);  // x first: the committed starts' order
    const Vec2 p{x, uniform(rng, 0.0, map_.height)};
    if (norm(p - source) < options_.min_start_distance) continue;
    if (space_->contains(p) && space_->region_of(p) == region) return p;
  }
  throw InputError("map " + map_.name + ": no free start found " +
                   compact(options_.min_start_distance) + " m from the source");
}

Vec2 Scenario::run_start(Vec2 source, int run, std::uint64_t seed) const {
  if (map_.starts.empty()) return random_start(source, seed);
  const int region = region_reaching(source);
  std::vector<Vec2> usable;
  for (Vec2 p : map_.starts)
    if (norm(p - source) >= options_.min_start_distance && region_reaching(p) == region)
      usable.push_back(p);
  if (usable.empty())
    throw InputError("map " + map_.name + ": none of its " + std::to_string(map_.starts.size()) +
                     " starts is " + compact(options_.min_start_distance) +
                     " m or more from the source " + to_string(map_.to_frame(source)) +
                     " and connected to it");
  return usable[static_cast<std::size_t>(run) % usable.size()];
}

std::unique_ptr<ste::Estimator> Scenario::make_estimator(std::uint64_t seed) const {
  if (!model_)
    throw InputError("the " + options_.method.name +
                     " method has no plume model to estimate with: STE's estimator and Mission "
                     "need --method ste");
  ste::LikelihoodOptions likelihood = options_.likelihood_options();
  if (const ste::SourceTableModel* table = model_->as_source_table()) {
    // A mean-only CNN predicts no std: the likelihood then uses sigma_M (and sigma_rel) alone,
    // unless --sigma-std was given, which the estimator refuses for such a model.
    if (!table->has_spreads() && !options_.likelihood.sigma_std) likelihood.sigma_std = 0.0;
    return std::make_unique<ste::GridEstimator>(*table, likelihood, bins_);
  }
  return std::make_unique<ste::MhEstimator>(
      *model_, map_, likelihood, bins_, options_.mh,
      splitmix64(world::stream_seed(seed, world::SteStream::Mh)));
}

const ste::ForwardModel& Scenario::model() const {
  if (!model_) throw std::logic_error("the " + options_.method.name + " method has no plume model");
  return *model_;
}

std::vector<Vec2> Scenario::team_starts(Vec2 first, Vec2 source) const {
  std::vector<Vec2> starts{first};
  const int robots = options_.team.robots;
  const double spacing = options_.team.separation;
  if (robots == 1) return starts;
  if (spacing <= 0.0) return std::vector<Vec2>(static_cast<std::size_t>(robots), first);
  const int region = region_reaching(source);
  std::vector<std::pair<std::pair<double, double>, Vec2>> lattice;
  const int reach = 2 * robots + 8;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j) {
      if (i == 0 && j == 0) continue;
      double angle = std::atan2(static_cast<double>(j), static_cast<double>(i));
      if (angle < 0.0) angle += 2.0 * kPi;
      lattice.push_back({{std::hypot(i, j), angle}, first + spacing * Vec2{double(i), double(j)}});
    }
  std::sort(lattice.begin(), lattice.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [key, p] : lattice) {
    if (static_cast<int>(starts.size()) == robots) break;
    if (!map_.in_arena(p) || !space_->contains(p) || space_->region_of(p) != region) continue;
    bool apart = true;
    for (Vec2 q : starts)
      apart = apart && norm(p - q) >= spacing - 1e-9;
    if (apart) starts.push_back(p);
  }
  if (static_cast<int>(starts.size()) < robots)
    throw InputError("map " + map_.name + ": no room for " + std::to_string(robots) + " robots " +
                     compact(spacing) + " m apart near the start " +
                     to_string(map_.to_frame(first)));
  return starts;
}

LocalizationResult Scenario::run_team(Vec2 source, const std::vector<Vec2>& starts,
                                      std::uint64_t seed, ReplayRecorder* recorder) const {
  check_source(source);
  const auto t0 = Clock::now();
  world::SharedPlume plume(map_, wind_, source, options_.world.filament, seed,
                           static_cast<int>(starts.size()));
  const double spin_up = since(t0);
  std::vector<std::unique_ptr<methods::LocalizationMethod>> members;
  std::vector<methods::LocalizationMethod*> pointers;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const std::uint64_t robot_seed = world::team_robot_seed(seed, static_cast<int>(k));
    const methods::PlumeModelParts model{[this, robot_seed] { return make_estimator(robot_seed); },
                                         planner_.get(), navigator_.get(), &options_.stop,
                                         passing()};
    members.push_back(make_method(options_.method, {&map_},
                                  world::stream_seed(robot_seed, world::SteStream::Method),
                                  &model));
    pointers.push_back(members.back().get());
  }
  MethodRunOptions o;
  if (options_.success_radius > 0.0) o.disc = SourceDisc{source, options_.success_radius};
  o.recorder = recorder;
  TeamSetup setup;
  setup.map = &map_;
  setup.source = source;
  setup.world = &options_.world;
  setup.planner = planner_.get();
  setup.space = space_.get();
  LocalizationResult r = run::run_team(plume, starts, pointers, seed, setup, options_.team, o);
  add_mission_times(r, source);
  r.plume_s += spin_up;
  r.run_s = since(t0);
  return r;
}

LocalizationResult Scenario::run(Vec2 source, Vec2 start, std::uint64_t seed,
                                 ReplayRecorder* recorder) const {
  const auto t0 = Clock::now();
  check_source(source);
  start = check_start(start);
  if (options_.team.robots > 1) {
    LocalizationResult r = run_team(source, team_starts(start, source), seed, recorder);
    r.run_s = since(t0);
    return r;
  }
  const auto t1 = Clock::now();
  world::SimulatedWorld world(map_, wind_, source, options_.world, seed);  // spins the plume up
  const double spin_up = since(t1);
  LocalizationResult r = run(world, start, seed, recorder);
  r.plume_s += spin_up;
  r.run_s = since(t0);
  return r;
}

LocalizationResult Scenario::run(world::SimulatedWorld& world, Vec2 start, std::uint64_t seed,
                                 ReplayRecorder* recorder) const {
  const auto t0 = Clock::now();
  const double busy = world.busy_s();
  LocalizationResult r = run_in(world, start, seed, recorder);
  add_mission_times(r, world.source());
  r.plume_s = world.busy_s() - busy;
  r.run_s = since(t0);
  return r;
}

LocalizationResult Scenario::run_in(world::SimulatedWorld& world, Vec2 start, std::uint64_t seed,
                                    ReplayRecorder* recorder) const {
  const Vec2 source = check_source(world.source());
  start = check_start(start);
  MethodRunOptions o;
  if (options_.success_radius > 0.0)
    o.disc = SourceDisc{source, options_.success_radius};
  else if (find_method(options_.method.name).traits.ends == methods::RunEnd::SourceDisc)
    o.disc = SourceDisc{source};
  const methods::PlumeModelParts model{[this, seed] { return make_estimator(seed); },
                                       planner_.get(), navigator_.get(), &options_.stop, passing()};
  const std::unique_ptr<methods::LocalizationMethod> method = make_method(
      options_.method, {&map_}, world::stream_seed(seed, world::SteStream::Method), &model);
  o.space = space_.get();
  o.approach = options_.approach;
  o.recorder = recorder;
  if (stops_in_source_box(options_.method.name)) o.box = source_box(source);
  return run_method(start, *method, world, *planner_, o);
}

double Scenario::optimum_path_m(Vec2 start, Vec2 source) const {
  const Vec2 goal = space_->contains(source) ? source : space_->nearest_free(source);
  try {
    return planner_->plan(check_start(start), goal).length + norm(source - goal);
  } catch (const InputError&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

void Scenario::add_mission_times(LocalizationResult& r, Vec2 source) const {
  const double speed = options_.world.speed;
  const double threshold = options_.method.tracking.detection_threshold;
  MissionTimes& t = r.times;
  t = MissionTimes{};
  t.declared_s = r.time_s - r.approach_s;
  t.ended_s = r.time_s;
  // A team: the earliest of its robots, and the optimum of the one that starts nearest.
  std::vector<const std::vector<Step>*> robots;
  std::vector<Vec2> starts;
  if (r.team.empty()) {
    robots.push_back(&r.steps);
    starts.push_back(r.start);
  }
  for (const TeamRobot& m : r.team) {
    robots.push_back(&m.steps);
    starts.push_back(m.start);
  }
  // fmin takes the number of a number and a NaN ("never").
  for (const std::vector<Step>* steps : robots) {
    t.first_detection_s = std::fmin(t.first_detection_s, first_detection(*steps, threshold));
    // The drive to the estimate after the last step (empty for a team, which does not approach).
    t.within_1m_s =
        std::fmin(t.within_1m_s, first_within(*steps, source, kGslBenchRadius, speed, r.approach));
    t.within_0_5m_s =
        std::fmin(t.within_0_5m_s, first_within(*steps, source, 0.5, speed, r.approach));
  }
  for (Vec2 s : starts)
    t.optimum_s = std::fmin(t.optimum_s, optimum_path_m(s, source) / speed);
}

SourceBox Scenario::source_box(Vec2 source) const {
  SourceBox box;
  box.source = source;
  const Vec2 w = wind_.at(source);
  if (norm(w) > 1e-9) box.downwind = (1.0 / norm(w)) * w;
  return box;
}

Grid<double> Scenario::mean_plume(Vec2 source) const {
  const cfd::AdvectionDiffusion ad(wind_, options_.physics.advection_diffusion);
  return ad.solve(source);
}

}  // namespace plumekit::run
