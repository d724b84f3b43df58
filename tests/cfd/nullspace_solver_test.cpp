// The nullspace solver: its step solves the whole Newton system J x = b (every
// momentum and continuity row), for any opening layout, in a closed box, and
// with the pseudo-time term; a flow solved with it equals the coupled one.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <filesystem>

#include "cfd/flow_solver.hpp"
#include "cfd/navier_stokes.hpp"
#include "cfd/nullspace_solver.hpp"
#include "cfd/staggered_grid.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

// Solves J x = b for a Jacobian at a non-trivial state and checks x against
// a general sparse LU of the coupled matrix.
void check_solve(const Map& map, const FlowOptions& options, Convection convection,
                 double pseudo_time = 0.0) {
  const GridShape shape = GridShape::with_cell(map.width, map.height, options.cell);
  const StaggeredGrid grid(map, shape, options);
  NavierStokes equations(grid, convection);
  const int n = grid.unknowns();
  Eigen::VectorXd state(n);
  for (int k = 0; k < n; ++k)
    state[k] = 0.3 + 0.2 * std::sin(0.37 * k);
  equations.update_jacobian(state.data());
  if (pseudo_time > 0.0) equations.add_to_momentum_diagonal(pseudo_time);
  const Eigen::SparseMatrix<double>& j = equations.jacobian();

  NullSpaceSolver solver(grid, j);
  ASSERT_TRUE(solver.applicable());
  // One streamfunction unknown per node group: far fewer than u, v and p.
  EXPECT_LT(solver.reduced_size(), n / 2);
  ASSERT_TRUE(solver.factorize(j));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x(n);
  solver.solve(j, b.data(), x.data());
  // Round-off relative to the size of the terms in each row.
  const double terms = (j.cwiseAbs() * x.cwiseAbs()).lpNorm<Eigen::Infinity>();
  EXPECT_LT((j * x - b).lpNorm<Eigen::Infinity>(), 1e-12 * terms);

  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(j);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd expected = lu.solve(b);
  EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8 * expected.lpNorm<Eigen::Infinity>());
}

FlowOptions coarse(double cell) {
  FlowOptions options;
  options.cell = cell;
  return options;
}

TEST(NullSpaceSolver, SolvesTheNewtonSystemOfAClutteredMap) {
  check_solve(read_map(kMaps / "cluttered-1.json"), coarse(0.2), Convection::Central);
  check_solve(read_map(kMaps / "cluttered-3.json"), coarse(0.2), Convection::VanLeer);
  check_solve(read_map(kMaps / "cluttered-2.json"), coarse(0.25), Convection::Upwind, 50.0);
}

TEST(NullSpaceSolver, HandlesOpeningsOnAnyWall) {
  // A partial outlet on the top, bottom or left wall: its fixed pressure
  // enters the curl projection at different nodes each time.
  Map map = read_map(kMaps / "cluttered-1.json");
  const struct {
    Side inlet_side;
    double in_from, in_to;
    Side outlet_side;
    double out_from, out_to;
  } layouts[] = {{Side::Left, 0.0, 4.0, Side::Top, 8.0, 10.0},
                 {Side::Top, 6.0, 9.0, Side::Bottom, 0.4, 2.0},
                 {Side::Left, 2.4, 4.0, Side::Left, 0.0, 1.6}};
  for (const auto& l : layouts) {
    map.openings = {wall_opening(map, l.inlet_side, l.in_from, l.in_to, OpeningKind::Inlet, 1.0,
                                 Profile::Parabolic),
                    wall_opening(map, l.outlet_side, l.out_from, l.out_to, OpeningKind::Outlet)};
    check_solve(map, coarse(0.2), Convection::Central);
  }
}

TEST(NullSpaceSolver, ClosedBoxWithItsPinnedPressure) {
  Map map = default_arena(1.0, 1.0);
  FlowOptions options;
  options.cell = 0.1;
  options.closed = true;
  options.wall_speed[static_cast<int>(Side::Top)] = 1.0;
  check_solve(map, options, Convection::Central);
}

TEST(NullSpaceSolver, FluidPocketIsSealedAndTheFlowConverges) {
  // A ring of four touching bars closes a pocket of fluid that no path joins
  // to an opening. It has no flow and no pressure level, so the grid treats
  // it as solid: the spanning tree then reaches every fluid cell.
  Map map = default_arena(4.0, 2.0);
  map.obstacles = {{{1.0, 0.5}, {3.0, 0.5}, {3.0, 0.7}, {1.0, 0.7}},
                   {{1.0, 1.3}, {3.0, 1.3}, {3.0, 1.5}, {1.0, 1.5}},
                   {{1.0, 0.7}, {1.2, 0.7}, {1.2, 1.3}, {1.0, 1.3}},
                   {{2.8, 0.7}, {3.0, 0.7}, {3.0, 1.3}, {2.8, 1.3}}};
  FlowOptions options;
  options.cell = 0.05;
  const GridShape shape = GridShape::with_cell(map.width, map.height, options.cell);
  const StaggeredGrid grid(map, shape, options);
  EXPECT_TRUE(grid.solid(shape.index(40, 20)));  // (2.0, 1.0): inside the ring, free in the map
  EXPECT_FALSE(grid.solid(shape.index(10, 20)));
  NavierStokes equations(grid, Convection::Central);
  std::vector<double> state(grid.unknowns(), 0.5);
  equations.update_jacobian(state.data());
  EXPECT_TRUE(NullSpaceSolver(grid, equations.jacobian()).applicable());

  const FlowResult r = solve(map, options);
  EXPECT_TRUE(r.summary.converged);
  EXPECT_EQ(r.summary.linear_solver, "nullspace");
  EXPECT_EQ(r.wind.at({2.0, 1.0}).x, 0.0);
  EXPECT_GT(r.wind.at({2.0, 0.25}).x, 0.5);  // the flow passes below the ring
}

TEST(NullSpaceSolver, FlowEqualsTheCoupledSolversFlow) {
  // Same Newton steps to round-off, so the same iterations and the same field.
  const Map map = read_map(kMaps / "cluttered-2.json");
  FlowOptions options;
  options.cell = 0.1;
  const FlowResult a = solve(map, options);
  options.linear_solver = plumekit::cfd::LinearSolverKind::Coupled;
  const FlowResult b = solve(map, options);
  EXPECT_EQ(a.summary.linear_solver, "nullspace");
  EXPECT_EQ(b.summary.linear_solver, "coupled");
  EXPECT_EQ(a.summary.iterations, b.summary.iterations);
  EXPECT_EQ(a.summary.factorizations, b.summary.factorizations);
  const Vec2 probes[] = {{1.0, 1.0}, {5.0, 2.0}, {8.5, 3.5}, {9.9, 0.3}};
  for (const Vec2& at : probes) {
    EXPECT_NEAR(a.wind.at(at).x, b.wind.at(at).x, 1e-9);
    EXPECT_NEAR(a.wind.at(at).y, b.wind.at(at).y, 1e-9);
  }
  EXPECT_NEAR(a.wind.cell_pressure(50, 20), b.wind.cell_pressure(50, 20), 1e-9);
}

}  // namespace
}  // namespace plumekit::cfd
