// The filament model: its long-time mean against the advection-diffusion
// plume with the equivalent diffusivity, and obstacles it must never enter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cfd/advection_diffusion.hpp"
#include "cfd/flow_solver.hpp"
#include "core/error.hpp"
#include "core/resample.hpp"
#include "map/map_json.hpp"
#include "support/uniform_wind.hpp"
#include "world/filament_model.hpp"

namespace plumekit::dataset {
namespace {

// The long-time mean along the empty arena's centreline, 1 to 8.5 m downwind, within 15 % of the
// advection-diffusion plume with the equivalent diffusivity.
void centreline_within_15_percent(world::PlumeEngine engine) {
  const Map map = default_arena(10.0, 4.0);
  const cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  world::FilamentOptions o;
  o.engine = engine;
  o.meander_speed = 0.0;  // the equivalence holds for the per-filament walk and growth
  o.record_s = 40.0;
  o.sample_rate = 2.0;
  const Vec2 source{1.0, 2.0};
  const GridShape sensors{64, 64, 10.0, 4.0};
  const world::SensorRecord rec = world::simulate_filaments(map, wind, source, sensors, o, 42);
  EXPECT_TRUE(rec.summary.steady);
  EXPECT_GT(rec.summary.left_through_outlet, 0);

  const cfd::AdvectionDiffusion ad(wind, {o.equivalent_diffusivity(), o.release_rate});
  const Grid<double> exact =
      GridResampler(ad.shape(), ad.solid_mask(), sensors).apply(ad.solve(source));
  // Centreline: the two sensor rows either side of y = 2, averaged.
  int checked = 0;
  double worst = 0.0;
  for (int i = 0; i < sensors.nx; ++i) {
    const double x = sensors.centre(i, 0).x;
    if (x < source.x + 1.0 || x > 8.5) continue;
    const double f = 0.5 * (rec.mean(i, 31) + rec.mean(i, 32));
    const double a = 0.5 * (exact(i, 31) + exact(i, 32));
    EXPECT_NEAR(f, a, 0.15 * a) << world::to_string(engine) << ", x = " << x;
    worst = std::max(worst, std::abs(f - a) / a);
    ++checked;
  }
  EXPECT_GE(checked, 40);
  std::printf("%s: centreline, %d sensors, worst relative difference %.4f\n",
              world::to_string(engine), checked, worst);
}

// Both engines (issue 45: the same physics in the fast one as in V1).
TEST(FilamentModel, LongTimeMeanMatchesAdvectionDiffusionAlongTheCentreline) {
  for (const world::PlumeEngine engine : {world::PlumeEngine::V1, world::PlumeEngine::Fast})
    centreline_within_15_percent(engine);
}

TEST(FilamentModel, NoFilamentIsEverInsideAnObstacle) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json");
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  const cfd::FlowResult flow = cfd::solve(map, fo);
  world::FilamentOptions o;
  o.sigma_walk = 0.5;  // a wide walk, to push filaments at the obstacles often
  world::FilamentSimulation sim(map, flow.wind, {2.8, 1.0}, o, 7);
  long long checked = 0;
  for (int s = 0; s < 300; ++s) {
    sim.step();
    for (const world::Filament& f : sim.filaments()) {
      ASSERT_LT(map.obstacle_at(f.position), 0) << "step " << s << " at " << to_string(f.position);
      ASSERT_TRUE(map.in_arena(f.position));
      ++checked;
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(sim.summary().rejected_moves, 100);  // the test did meet the obstacles
}

// Seed 002's circular source (source_radius): filaments leave from uniform points of the disc,
// never outside the arena where the disc crosses a wall.
TEST(FilamentModel, ASourceDiscReleasesUniformlyOverItsFreePart) {
  const Map map = default_arena(10.0, 4.0);
  const cfd::WindField still = test::uniform_wind(10.0, 4.0, 0.05, 0.0);
  world::FilamentOptions o;
  o.unsteady_wind = false;
  o.meander_speed = 0.0;
  o.sigma_walk = 0.0;  // the filaments stay where they were released
  o.release_per_second = 4000.0;
  o.source_radius = 0.2;
  world::FilamentSimulation sim(map, still, {5.0, 2.0}, o, 3);
  sim.step();
  ASSERT_EQ(sim.filaments().size(), 200u);
  Vec2 mean;
  double square = 0.0;
  for (const world::Filament& f : sim.filaments()) {
    const Vec2 d = f.position - Vec2{5.0, 2.0};
    EXPECT_LE(norm(d), 0.2);
    mean = mean + (1.0 / 200.0) * d;
    square += dot(d, d) / 200.0;
  }
  EXPECT_NEAR(mean.x, 0.0, 0.03);  // std of the mean: 0.1 / sqrt(200) = 0.007
  EXPECT_NEAR(mean.y, 0.0, 0.03);
  EXPECT_NEAR(square, 0.5 * 0.04, 0.005);  // a uniform disc's mean r^2 is R^2 / 2; std 0.0008
  world::FilamentSimulation at_wall(map, still, {0.05, 2.0}, o, 3);
  at_wall.step();
  for (const world::Filament& f : at_wall.filaments())
    EXPECT_GE(f.position.x, 0.0);
  o.source_radius = -0.1;
  EXPECT_THROW(world::FilamentSimulation(map, still, {5.0, 2.0}, o, 3), OptionError);
}

TEST(FilamentModel, SameSeedSameRecordAndSensorsInObstaclesReadZero) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json");
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  const cfd::FlowResult flow = cfd::solve(map, fo);
  world::FilamentOptions o;
  o.max_spinup = 6.0;
  o.record_s = 1.0;
  const GridShape sensors{64, 64, 10.0, 4.0};
  const world::SensorRecord a =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 3);
  const world::SensorRecord b =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 3);
  const world::SensorRecord c =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 4);
  EXPECT_EQ(a.mean.values, b.mean.values);
  EXPECT_EQ(a.std.values, b.std.values);
  EXPECT_NE(a.mean.values, c.mean.values);
  for (int j = 0; j < sensors.ny; ++j)
    for (int i = 0; i < sensors.nx; ++i)
      if (map.obstacle_at(sensors.centre(i, j)) >= 0) {
        EXPECT_EQ(a.mean(i, j), 0.0);
      }
}

}  // namespace
}  // namespace plumekit::dataset

namespace plumekit {
namespace {

// Issue 45: one plume may step on several threads, and it is the same plume, bit for bit.
TEST(FilamentModel, AStepOnTwoThreadsMovesTheSameFilaments) {
  const Map map = default_arena(10.0, 4.0);
  const cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  world::FilamentOptions o;
  o.release_per_second = 2000.0;  // some 18,000 filaments: past where threads start
  o.max_spinup = 12.0;            // the first ones reach the outlet after about 9 s
  std::vector<world::Filament> after[2];
  world::FilamentSummary summary[2];
  std::vector<double> grid[2];
  const GridShape sensors{64, 64, 10.0, 4.0};
  for (const int threads : {1, 2}) {
    o.threads = threads;
    world::FilamentSimulation sim(map, wind, {1.0, 2.0}, o, 17);
    world::spin_up(sim, o);
    for (int s = 0; s < 10; ++s)
      sim.step();
    after[threads - 1] = sim.filaments();
    summary[threads - 1] = sim.summary();
    grid[threads - 1].assign(sensors.size(), 0.0);
    sim.concentration(sensors, grid[threads - 1]);
  }
  ASSERT_GT(after[0].size(), 8000u);
  ASSERT_EQ(after[0].size(), after[1].size());
  for (std::size_t k = 0; k < after[0].size(); ++k) {
    ASSERT_EQ(after[0][k].position.x, after[1][k].position.x) << k;
    ASSERT_EQ(after[0][k].position.y, after[1][k].position.y) << k;
    ASSERT_EQ(after[0][k].radius2, after[1][k].radius2) << k;
  }
  EXPECT_EQ(summary[0].released, summary[1].released);
  EXPECT_EQ(summary[0].left_through_outlet, summary[1].left_through_outlet);
  EXPECT_GT(summary[0].left_through_outlet, 0);
  EXPECT_EQ(summary[0].rejected_moves, summary[1].rejected_moves);
  EXPECT_EQ(summary[0].dropped_too_wide, summary[1].dropped_too_wide);
  EXPECT_EQ(grid[0], grid[1]);
}

}  // namespace
}  // namespace plumekit
