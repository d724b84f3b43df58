// The unsteady wind's fluctuation (issue 18): every mode is exactly
// divergence-free, moves no air through walls, obstacles or openings and is
// zero inside obstacles; away from walls each component fluctuates with the
// asked std and correlation time, and it fades towards the walls.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cfd/flow_solver.hpp"
#include "map/map_json.hpp"
#include "world/wind_fluctuation.hpp"

namespace plumekit::cfd {
namespace {

WindField coarse_flow(const std::string& name) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/test-maps/" + name + ".json");
  FlowOptions o;
  o.cell = 0.1;
  o.nu = 0.05;
  FlowResult r = solve(map, o);
  EXPECT_TRUE(r.summary.converged);
  return r.wind;
}

TEST(WindFluctuation, ModesAreDivergenceFreeAndMoveNoAirThroughAnySurface) {
  const WindField steady = coarse_flow("test-3-two-blocks");
  const world::FluctuatingWind wind(steady, world::FluctuationOptions{}, 7);
  const GridShape& s = steady.shape();
  const int nx = s.nx, ny = s.ny;
  ASSERT_EQ(wind.modes(), 8);
  for (int k = 0; k < wind.modes(); ++k) {
    const WindField mode = wind.mode(k);
    const std::vector<double>&fu = mode.face_u(), &fv = mode.face_v();
    double largest = 0.0, worst_divergence = 0.0;
    for (double u : fu)
      largest = std::max(largest, std::abs(u));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double div = (fu[j * (nx + 1) + i + 1] - fu[j * (nx + 1) + i]) / s.dx() +
                           (fv[(j + 1) * nx + i] - fv[j * nx + i]) / s.dy();
        worst_divergence = std::max(worst_divergence, std::abs(div));
        if (steady.solid(i, j)) {
          // A solid cell's four faces carry nothing, so neither does the obstacle's outline.
          EXPECT_EQ(fu[j * (nx + 1) + i], 0.0);
          EXPECT_EQ(fu[j * (nx + 1) + i + 1], 0.0);
          EXPECT_EQ(fv[j * nx + i], 0.0);
          EXPECT_EQ(fv[(j + 1) * nx + i], 0.0);
          EXPECT_EQ(mode.cell_velocity(i, j).x, 0.0);
        }
      }
    EXPECT_GT(largest, 0.5);  // a mode of unit strength is not empty
    EXPECT_LT(worst_divergence, 1e-12 * largest / s.dx());
    // Walls, the inlet and the outlet alike: no normal flow on the arena's boundary.
    for (int j = 0; j < ny; ++j) {
      EXPECT_EQ(fu[j * (nx + 1)], 0.0);
      EXPECT_EQ(fu[j * (nx + 1) + nx], 0.0);
    }
    for (int i = 0; i < nx; ++i) {
      EXPECT_EQ(fv[i], 0.0);
      EXPECT_EQ(fv[ny * nx + i], 0.0);
    }
  }
  // Inside the first block (x 3.0..3.6, y 0..2.2) the wind is exactly zero.
  EXPECT_EQ(wind.at({3.3, 1.0}).x, 0.0);
  EXPECT_EQ(wind.at({3.3, 1.0}).y, 0.0);
}

TEST(WindFluctuation, StdAwayFromWallsCorrelationTimeAndFadingAtWalls) {
  const WindField steady = coarse_flow("test-0-empty");
  world::FluctuationOptions o;
  o.intensity = 0.2;
  o.time_scale = 2.0;
  world::FluctuatingWind wind(steady, o, 11);
  const double dt = 0.1;
  const int steps = 40000;  // 4000 s, 2000 correlation times
  const int lag = static_cast<int>(std::lround(o.time_scale / dt));
  // Interior: x 2..8 m, y 1.5..2.5 m (beyond the 1 m wall layer); a profile
  // from the bottom wall, averaged along x.
  const std::vector<Vec2> interior = {{2.0, 2.0}, {3.5, 1.6}, {5.0, 2.4}, {6.5, 2.0}, {8.0, 1.5}};
  const std::vector<double> depths = {0.05, 0.15, 0.25, 0.4, 0.5, 0.6, 0.8, 1.0, 1.5, 2.0};
  std::vector<double> profile(depths.size(), 0.0);
  double interior_square = 0.0;
  double a0_sum = 0.0, a0_square = 0.0, a0_lagged = 0.0;
  std::vector<double> a0(static_cast<std::size_t>(steps));
  for (int t = 0; t < steps; ++t) {
    wind.advance(dt);
    for (Vec2 p : interior) {
      const Vec2 d = wind.at(p) - steady.at(p);
      interior_square += 0.5 * (d.x * d.x + d.y * d.y);
    }
    a0[static_cast<std::size_t>(t)] = wind.amplitudes()[0];
    for (std::size_t d = 0; d < depths.size(); ++d)
      for (double x : {2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0}) {
        const Vec2 e = wind.at({x, depths[d]}) - steady.at({x, depths[d]});
        profile[d] += 0.5 * (e.x * e.x + e.y * e.y) / (7.0 * steps);
      }
  }
  for (int t = 0; t < steps; ++t) {
    a0_sum += a0[t];
    a0_square += a0[t] * a0[t];
    if (t >= lag) a0_lagged += a0[t] * a0[t - lag];
  }
  const double interior_std = std::sqrt(interior_square / (steps * interior.size()));
  for (std::size_t d = 0; d < depths.size(); ++d) {
    profile[d] = std::sqrt(profile[d]);
    std::printf("%.2f m from the wall: std %.3f\n", depths[d], profile[d]);
  }
  // It fades towards the wall without a jet beside it: rising from the wall,
  // never above the interior's.
  EXPECT_LT(profile[0], 0.2 * o.intensity);
  for (std::size_t d = 0; d < depths.size(); ++d) {
    if (d > 0 && depths[d] <= 0.6) {
      EXPECT_GT(profile[d], 0.97 * profile[d - 1]);
    }
    EXPECT_LT(profile[d], 1.1 * o.intensity) << depths[d] << " m from the wall";
  }
  // Five points sample the plane waves' pattern, so the std is the asked one within ~20 %.
  EXPECT_NEAR(interior_std, o.intensity, 0.2 * o.intensity);
  // Ornstein-Uhlenbeck: correlation e^-1 one time scale apart.
  const double mean = a0_sum / steps;
  const double variance = a0_square / steps - mean * mean;
  const double correlation = (a0_lagged / (steps - lag) - mean * mean) / variance;
  EXPECT_NEAR(correlation, std::exp(-1.0), 0.08);
  EXPECT_NEAR(std::sqrt(variance), o.intensity / std::sqrt(8.0),
              0.1 * o.intensity / std::sqrt(8.0));
}

TEST(WindFluctuation, TheSeedFixesTheWindAndAnotherSeedChangesIt) {
  const WindField steady = coarse_flow("test-1-block");
  world::FluctuatingWind a(steady, {}, 3), b(steady, {}, 3), c(steady, {}, 4);
  for (int t = 0; t < 50; ++t) {
    a.advance(0.05);
    b.advance(0.05);
    c.advance(0.05);
  }
  const Vec2 p{6.0, 1.0};
  EXPECT_EQ(a.at(p).x, b.at(p).x);
  EXPECT_EQ(a.at(p).y, b.at(p).y);
  EXPECT_NE(a.at(p).x, c.at(p).x);
}

}  // namespace
}  // namespace plumekit::cfd
