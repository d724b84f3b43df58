// The filament plume in the unsteady wind (issue 18): filaments still never
// enter obstacles, the seed fixes the record, and the meandering field gives a
// mean plume and fluctuations like the uniform meander's in the open.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cfd/flow_solver.hpp"
#include "map/map_json.hpp"
#include "support/uniform_wind.hpp"
#include "world/filament_model.hpp"

namespace plumekit::dataset {
namespace {

world::FilamentOptions unsteady() {
  world::FilamentOptions o;
  o.unsteady_wind = true;
  return o;
}

TEST(UnsteadyWind, NoFilamentEntersAnObstacleAndTheSeedFixesTheRecord) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json");
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  const cfd::FlowResult flow = cfd::solve(map, fo);
  world::FilamentSimulation sim(map, flow.wind, {2.8, 1.0}, unsteady(), 7);
  ASSERT_TRUE(sim.unsteady());
  long long checked = 0;
  for (int s = 0; s < 300; ++s) {
    sim.step();
    for (const world::Filament& f : sim.filaments()) {
      ASSERT_LT(map.obstacle_at(f.position), 0) << "step " << s << " at " << to_string(f.position);
      ++checked;
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_EQ(sim.meander().x, 0.0);  // the swing is in the field, not uniform
  EXPECT_EQ(sim.wind_at({6.8, 3.0}).x, 0.0) << "inside an obstacle";

  world::FilamentOptions o = unsteady();
  o.max_spinup = 6.0;
  o.record_s = 1.0;
  const GridShape sensors{64, 64, 10.0, 4.0};
  const world::SensorRecord a =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 3);
  const world::SensorRecord b =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 3);
  o.unsteady_wind = false;
  const world::SensorRecord steady =
      world::simulate_filaments(map, flow.wind, {1.5, 1.0}, sensors, o, 3);
  EXPECT_EQ(a.mean.values, b.mean.values);
  EXPECT_NE(a.mean.values, steady.mean.values);
}

TEST(UnsteadyWind, InTheOpenThePlumeIsLikeTheUniformMeanders) {
  const Map map = default_arena(10.0, 4.0);
  const cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  const Vec2 source{1.0, 2.0};
  const GridShape sensors{64, 64, 10.0, 4.0};
  world::FilamentOptions o;
  o.record_s = 60.0;
  o.sample_rate = 2.0;
  o.unsteady_wind = false;  // the uniform meander (the default is the unsteady wind)
  const world::SensorRecord steady = world::simulate_filaments(map, wind, source, sensors, o, 42);
  o.unsteady_wind = true;
  const world::SensorRecord moving = world::simulate_filaments(map, wind, source, sensors, o, 42);
  // Along the centreline, 2 to 8 m downwind: the mean within a third of the
  // uniform meander's, and a fluctuating signal (std over mean) like it.
  double worst = 0.0, steady_ratio = 0.0, moving_ratio = 0.0;
  int n = 0;
  for (int i = 0; i < sensors.nx; ++i) {
    const double x = sensors.centre(i, 0).x;
    if (x < source.x + 2.0 || x > 8.0) continue;
    const double s = 0.5 * (steady.mean(i, 31) + steady.mean(i, 32));
    const double m = 0.5 * (moving.mean(i, 31) + moving.mean(i, 32));
    worst = std::max(worst, std::abs(m - s) / s);
    steady_ratio += 0.5 * (steady.std(i, 31) + steady.std(i, 32)) / s;
    moving_ratio += 0.5 * (moving.std(i, 31) + moving.std(i, 32)) / m;
    ++n;
  }
  steady_ratio /= n;
  moving_ratio /= n;
  std::printf("centreline: worst mean difference %.3f; std/mean steady %.3f, unsteady %.3f\n",
              worst, steady_ratio, moving_ratio);
  EXPECT_LT(worst, 0.33);
  EXPECT_GT(moving_ratio, 0.5 * steady_ratio);
  EXPECT_LT(moving_ratio, 2.0 * steady_ratio);
}

}  // namespace
}  // namespace plumekit::dataset
