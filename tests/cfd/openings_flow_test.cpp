// Flows on plumekit-map/2 maps: several inlets and outlets, one of them a vent
// on an obstacle's edge. Mass balances, every inlet delivers its profile,
// every outlet carries flow out, and both linear solvers agree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cfd/flow_output.hpp"
#include "cfd/flow_solver.hpp"
#include "cfd/staggered_grid.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

const std::filesystem::path kBuilding =
    std::filesystem::path(PLUMEKIT_TEST_DATA) / "maps-v2" / "building.json";

FlowOptions coarse() {
  FlowOptions o;
  o.cell = 0.1;
  o.nu = 0.05;
  return o;
}

// The flux an inlet delivers on the grid: its profile at the face centres.
double discrete_inflow(const Opening& o, double h) {
  double q = 0.0;
  for (double s = o.lo() + 0.5 * h; s < o.hi(); s += h)
    q += o.speed_at(s) * h;
  return q;
}

TEST(OpeningsFlow, SeveralInletsAndOutletsBalanceMass) {
  const Map map = read_map(kBuilding);
  const FlowResult r = solve(map, coarse());
  const FlowSummary& s = r.summary;
  ASSERT_TRUE(s.converged);
  double expected = 0.0;
  for (const Opening& o : map.openings)
    if (o.is_inlet()) expected += discrete_inflow(o, 0.1);
  EXPECT_NEAR(s.inflow, expected, 1e-9);
  EXPECT_GT(s.inflow, 1.3);  // 1 m/s over 1 m plus a parabolic 0.5 m/s peak over 1 m
  EXPECT_NEAR(s.outflow, s.inflow, 1e-9 * s.inflow);
  EXPECT_LT(s.mass_imbalance, 1e-12);
}

TEST(OpeningsFlow, EveryOutletCarriesFlowOutAndTheVentIsNotAWall) {
  const Map map = read_map(kBuilding);
  const FlowResult r = solve(map, coarse());
  const WindField& w = r.wind;
  const GridShape& g = w.shape();
  // The vent on the outer wall's inner edge (y = 3.6 m, x 4..5 m): v faces of row 36.
  double vent = 0.0, beside = 0.0;
  for (int i = 0; i < g.nx; ++i) {
    const double v = w.face_v()[36 * g.nx + i];
    (i >= 40 && i < 50 ? vent : beside) += v * g.dx();
  }
  EXPECT_GT(vent, 0.1);  // upward, out through the vent
  EXPECT_EQ(beside, 0.0);
  // The outlet on the right wall (y 1..2 m): u faces at i = nx.
  double right = 0.0;
  for (int j = 10; j < 20; ++j)
    right += w.face_u()[j * (g.nx + 1) + g.nx] * g.dy();
  EXPECT_GT(right, 0.1);
  EXPECT_NEAR(vent + right, r.summary.inflow, 1e-9);
  // No flow inside the outer wall band.
  EXPECT_EQ(w.cell_velocity(45, 38).x, 0.0);
  EXPECT_EQ(w.cell_velocity(45, 38).y, 0.0);
}

TEST(OpeningsFlow, ParaViewFilesSitAtTheMapFramesOrigin) {
  const Map map = read_map(kBuilding);  // framed at (-3, -2)
  const FlowResult r = solve(map, coarse());
  EXPECT_NE(wind_vti(r.wind, map.frame).find("Origin=\"-3 -2 0\""), std::string::npos);
  EXPECT_NE(wind_vti(r.wind).find("Origin=\"0 0 0\""), std::string::npos);
}

TEST(OpeningsFlow, NullspaceAndCoupledSolversAgree) {
  const Map map = read_map(kBuilding);
  FlowOptions a = coarse(), b = coarse();
  b.linear_solver = LinearSolverKind::Coupled;
  const FlowResult ra = solve(map, a), rb = solve(map, b);
  ASSERT_TRUE(ra.summary.converged && rb.summary.converged);
  double diff = 0.0, size = 0.0;
  for (std::size_t k = 0; k < ra.wind.u().size(); ++k) {
    diff = std::max(diff, std::abs(ra.wind.u()[k] - rb.wind.u()[k]) +
                              std::abs(ra.wind.v()[k] - rb.wind.v()[k]));
    size = std::max(size, std::abs(ra.wind.u()[k]) + std::abs(ra.wind.v()[k]));
  }
  EXPECT_LT(diff, 1e-6 * size);
  EXPECT_EQ(ra.summary.linear_solver, "nullspace");  // the vent did not force the fallback
}

TEST(OpeningsFlow, AnInletOnAnObstacleEdgeBlowsAwayFromTheObstacle) {
  // A 4 x 2 m room whose left 0.5 m is a solid block; the inlet is the
  // block's right edge (x = 0.5 m), the outlet the right wall.
  Map map = default_arena(4.0, 2.0);
  map.obstacles.push_back({{0, 0}, {0.5, 0}, {0.5, 2}, {0, 2}});
  Opening in;
  in.from = {0.5, 0.0};
  in.to = {0.5, 2.0};
  in.speed = 0.4;
  map.openings[0] = in;
  const FlowResult r = solve(map, coarse());
  ASSERT_TRUE(r.summary.converged);
  EXPECT_NEAR(r.summary.inflow, 0.8, 1e-9);
  EXPECT_LT(r.summary.mass_imbalance, 1e-12);
  // Through the section at x = 2 m passes all of it, in the +x direction,
  // faster at the middle than the mean (the walls are no-slip).
  const GridShape& g = r.wind.shape();
  double flux = 0.0;
  for (int j = 0; j < g.ny; ++j)
    flux += r.wind.face_u()[j * (g.nx + 1) + 20] * g.dy();
  EXPECT_NEAR(flux, 0.8, 1e-9);
  const Vec2 mid = r.wind.at({2.0, 1.0});
  EXPECT_GT(mid.x, 0.4);
  EXPECT_LT(mid.x, 0.6);  // below the developed parabola's peak, 1.5 x the mean
}

}  // namespace
}  // namespace plumekit::cfd
