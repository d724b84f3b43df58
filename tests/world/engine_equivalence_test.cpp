// The fast plume engine against the V1 one (issue 45). The fast engine draws its random numbers
// differently, so the two never agree byte for byte; they must agree as statistics: mean and std
// maps as close as two V1 realizations are to each other, the empty arena's centreline within the
// analytic tolerance, the same fractions of filaments leaving, dropped and stopped, and occlusion
// holding as before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cfd/advection_diffusion.hpp"
#include "cfd/flow_policy.hpp"
#include "cfd/flow_solver.hpp"
#include "core/resample.hpp"
#include "map/map_json.hpp"
#include "support/uniform_wind.hpp"
#include "world/filament_model.hpp"

namespace plumekit::world {
namespace {

using Engine = PlumeEngine;

struct Scene {
  const char* name;
  Map map;
  cfd::WindField wind;
  Vec2 source;
  GridShape sensors;
};

Scene empty_arena() {
  return {"empty",
          default_arena(10.0, 4.0),
          test::uniform_wind(10.0, 4.0, 0.1, 1.0),
          {1.0, 2.0},
          GridShape{40, 16, 10.0, 4.0}};
}

// A U-shaped room and two blocks, in its solved flow on the datasets' 5 cm grid (jets of up to
// 6.5 m/s between the obstacles): recirculation, walls that stop filaments and shadows that
// occlusion must respect.
Scene cluttered(const char* name, Vec2 source) {
  Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/test-maps/test-7-u-and-blocks.json");
  cfd::FlowOptions fo;
  fo.cell = 0.05;
  cfd::WindResult flow = cfd::solve_wind(map, fo);
  return {name, std::move(map), std::move(flow.flow.wind), source, GridShape{40, 16, 10.0, 4.0}};
}

// The faithful world (occlusion and the unsteady wind), with a fixed spin-up of 20 s (the plume
// crosses the 10 m arena in about 10 s) so that every run records the same stretch of time; 40 s
// in all, beyond a filament's 28 s lifetime, so that some are dropped for being too wide.
FilamentOptions faithful(Engine engine) {
  FilamentOptions o;
  o.engine = engine;
  o.min_spinup = 20.0;
  o.max_spinup = 20.0;
  o.record_s = 20.0;
  o.sample_rate = 5.0;
  return o;
}

std::vector<SensorRecord> realizations(const Scene& s, Engine engine,
                                       const std::vector<std::uint64_t>& seeds) {
  std::vector<SensorRecord> out;
  for (const std::uint64_t seed : seeds)
    out.push_back(simulate_filaments(s.map, s.wind, s.source, s.sensors, faithful(engine), seed));
  return out;
}

// The RMS difference of two maps over the free sensors, relative to the RMS of their mean.
double relative_rms_difference(const Scene& s, const Grid<double>& a, const Grid<double>& b) {
  double diff = 0.0, level = 0.0;
  for (int j = 0; j < s.sensors.ny; ++j)
    for (int i = 0; i < s.sensors.nx; ++i) {
      if (s.map.obstacle_at(s.sensors.centre(i, j)) >= 0) continue;
      const double d = a(i, j) - b(i, j), m = 0.5 * (a(i, j) + b(i, j));
      diff += d * d;
      level += m * m;
    }
  return std::sqrt(diff / level);
}

// The mean relative RMS difference over all pairs (a from `as`, b from `bs`), each pair once.
double pair_difference(const Scene& s, const std::vector<SensorRecord>& as,
                       const std::vector<SensorRecord>& bs, bool same, bool of_std) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < as.size(); ++p)
    for (std::size_t q = same ? p + 1 : 0; q < bs.size(); ++q, ++n)
      sum += of_std ? relative_rms_difference(s, as[p].std, bs[q].std)
                    : relative_rms_difference(s, as[p].mean, bs[q].mean);
  return sum / n;
}

// Spatial summaries of one record.
struct Moments {
  double mass = 0.0;  // the sum of the mean map
  Vec2 centroid;      // of the mean map, m
  double std_sum = 0.0;
};

Moments moments(const GridShape& g, const SensorRecord& r) {
  Moments m;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      m.mass += r.mean(i, j);
      m.centroid = m.centroid + r.mean(i, j) * g.centre(i, j);
      m.std_sum += r.std(i, j);
    }
  m.centroid = (1.0 / m.mass) * m.centroid;
  return m;
}

// Mean and standard error of a sample.
struct Sample {
  double mean = 0.0, error = 0.0;
};

Sample sample(const std::vector<double>& v) {
  Sample s;
  for (const double x : v)
    s.mean += x / v.size();
  double ss = 0.0;
  for (const double x : v)
    ss += (x - s.mean) * (x - s.mean);
  s.error = std::sqrt(ss / (v.size() - 1) / v.size());
  return s;
}

// |fast - v1| in units of the combined standard error, printed with the values. A quantity that
// never varies (no filament dropped in the empty arena) must be the same in both.
double separation(const char* what, const std::vector<double>& v1,
                  const std::vector<double>& fast) {
  const Sample a = sample(v1), b = sample(fast);
  const double error = std::hypot(a.error, b.error);
  const double z = error > 0.0        ? std::abs(a.mean - b.mean) / error
                   : a.mean == b.mean ? 0.0
                                      : HUGE_VAL;
  std::printf("  %-22s v1 %.5g +- %.2g  fast %.5g +- %.2g  (%.2f standard errors)\n", what, a.mean,
              a.error, b.mean, b.error, z);
  return z;
}

template <class F>
std::vector<double> each(const std::vector<SensorRecord>& records, F f) {
  std::vector<double> out;
  for (const SensorRecord& r : records)
    out.push_back(f(r));
  return out;
}

std::vector<std::uint64_t> seeds(std::uint64_t first, int count) {
  std::vector<std::uint64_t> out;
  for (int k = 0; k < count; ++k)
    out.push_back(first + k);
  return out;
}

// Eight plumes per engine, from independent seeds: never the same seed in both, since the
// unsteady wind's stream comes from the seed alone, so V1 and fast with one seed share their wind
// and would look closer than two V1 plumes do. (V1 never changes; the fast seeds stand for any
// fast engine's plumes.)
struct Plumes {
  std::vector<SensorRecord> v1, fast;
};

Plumes plumes(const Scene& s) {
  return {realizations(s, Engine::V1, seeds(1, 8)), realizations(s, Engine::Fast, seeds(101, 8))};
}

// The mean and std maps. The old world's two-realization noise is the mean relative RMS
// difference between two V1 plumes (28 pairs; fixed, since V1 never changes); V1 against fast (64
// pairs) must stay within 1.5 times it for the mean, 1.3 times for the std. Measured on these
// scenes with these V1 seeds and seven sets of fast seeds: at most 1.30 (mean) and 1.12 (std). And
// since two plumes of one engine differ by the same noise if the engines agree, V1 against fast
// must stay within 1.25 times the RMS of the two engines' own noises (measured: at most 1.06 for
// the mean, 1.14 for the std), which does not depend on whether V1's seeds happen to give a low
// noise. A fast engine whose walk is 20% weak or whose growth is 20% fast fails these in the
// cluttered scenes (and the summaries below); so does one with a 30% weaker meander (the std map
// in the pocket) or without occlusion (the mean map in the pocket).
void check_maps(const Scene& s, const Plumes& p) {
  for (const bool of_std : {false, true}) {
    const double v1 = pair_difference(s, p.v1, p.v1, true, of_std);
    const double cross = pair_difference(s, p.v1, p.fast, false, of_std);
    const double fast = pair_difference(s, p.fast, p.fast, true, of_std);
    const double both = std::sqrt(0.5 * (v1 * v1 + fast * fast));
    std::printf(
        "%s, %s map: v1-v1 %.4f, fast-fast %.4f, v1-fast %.4f (%.3f of v1-v1, %.3f of both)\n",
        s.name, of_std ? "std" : "mean", v1, fast, cross, cross / v1, cross / both);
    EXPECT_LT(cross, (of_std ? 1.3 : 1.5) * v1) << (of_std ? "std" : "mean");
    EXPECT_LT(cross, 1.25 * both) << (of_std ? "std" : "mean");
  }
}

// Spatial summaries and the filaments' fates, fast within 4 combined standard errors of V1 (over
// all scenes, a healthy fast engine came within 2.7).
void check_summaries(const Scene& s, const Plumes& p) {
  std::printf("%s:\n", s.name);
  auto compare = [&](const char* what, auto f) {
    EXPECT_LT(separation(what, each(p.v1, f), each(p.fast, f)), 4.0) << what;
  };
  const GridShape& g = s.sensors;
  compare("mass (sum of mean)", [&](const SensorRecord& r) { return moments(g, r).mass; });
  compare("centroid x", [&](const SensorRecord& r) { return moments(g, r).centroid.x; });
  compare("centroid y", [&](const SensorRecord& r) { return moments(g, r).centroid.y; });
  compare("sum of std", [&](const SensorRecord& r) { return moments(g, r).std_sum; });
  // Per filament released: the same count in every plume. (simulate_filaments does not count
  // filament-steps; the rejected moves per filament are the same measure on another scale.)
  auto per_filament = [](long long FilamentSummary::*count) {
    return [count](const SensorRecord& r) {
      return static_cast<double>(r.summary.*count) / static_cast<double>(r.summary.released);
    };
  };
  compare("left through outlet", per_filament(&FilamentSummary::left_through_outlet));
  compare("dropped too wide", per_filament(&FilamentSummary::dropped_too_wide));
  compare("rejected moves", per_filament(&FilamentSummary::rejected_moves));
  for (const SensorRecord& r : p.fast)
    EXPECT_EQ(r.summary.released, p.v1[0].summary.released);
}

void check_scene(const Scene& s) {
  const Plumes p = plumes(s);
  check_summaries(s, p);
  check_maps(s, p);
}

TEST(EngineEquivalence, EmptyArena) {
  check_scene(empty_arena());
}
// From inside the U's pocket: recirculation, where filaments live long, grow too wide and meet
// the walls at every step.
TEST(EngineEquivalence, InsideTheUPocket) {
  check_scene(cluttered("U pocket", {5.052, 1.985}));
}
// Just downwind of the first block, through the jets between the obstacles.
TEST(EngineEquivalence, BehindTheBlock) {
  check_scene(cluttered("behind block", {3.008, 1.075}));
}

// The analytic centreline (tests/world/filament_test.cpp), the sealed room and the block's wake
// (tests/world/occlusion_test.cpp) run there with both engines.

}  // namespace
}  // namespace plumekit::world
