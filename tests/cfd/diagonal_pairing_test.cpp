// The row pairing that gives the coupled Newton matrix a full diagonal: every
// row keeps its equation, only its place changes, so P J x = P b has J's
// solution.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <filesystem>

#include "cfd/diagonal_pairing.hpp"
#include "cfd/navier_stokes.hpp"
#include "cfd/staggered_grid.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

int zero_diagonals(const Eigen::SparseMatrix<double>& a) {
  int zeros = 0;
  for (int k = 0; k < a.rows(); ++k)
    if (a.coeff(k, k) == 0.0) ++zeros;
  return zeros;
}

// A Jacobian at a non-trivial state: every unknown set to a smooth pattern.
Eigen::SparseMatrix<double> jacobian_of(NavierStokes& equations, int n) {
  Eigen::VectorXd x(n);
  for (int k = 0; k < n; ++k)
    x[k] = 0.3 + 0.2 * std::sin(0.37 * k);
  equations.update_jacobian(x.data());
  return equations.jacobian();
}

void check_pairing(const Map& map, const FlowOptions& options) {
  const GridShape shape = GridShape::with_cell(map.width, map.height, options.cell);
  const StaggeredGrid grid(map, shape, options);
  NavierStokes equations(grid, Convection::Central);
  const int n = grid.unknowns();
  const Eigen::SparseMatrix<double> j = jacobian_of(equations, n);
  ASSERT_GT(zero_diagonals(j), 0);  // the continuity rows

  DiagonalPairing pairing(grid, j);
  EXPECT_EQ(pairing.unpaired(), 0);
  Eigen::SparseMatrix<double> pj = pairing.permuted(j);
  EXPECT_EQ(zero_diagonals(pj), 0);
  EXPECT_EQ(pj.nonZeros(), j.nonZeros());

  // The same solution, and row by row the same equations.
  Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd b = j * expected;
  Eigen::VectorXd pb(n);
  pairing.permute(b.data(), pb.data());
  EXPECT_LT((pj * expected - pb).lpNorm<Eigen::Infinity>(), 1e-9 * b.lpNorm<Eigen::Infinity>());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(pj);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd x = lu.solve(pb);
  EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-8);

  // New values in the same pattern land in the same places.
  const Eigen::SparseMatrix<double> doubled = 2.0 * j;
  EXPECT_LT((Eigen::MatrixXd(pairing.permuted(doubled)) - 2.0 * Eigen::MatrixXd(pj)).norm(), 1e-12);
}

TEST(DiagonalPairing, ClutteredMapGetsAFullDiagonalAndTheSameSolution) {
  FlowOptions options;
  options.cell = 0.2;
  check_pairing(read_map(kMaps / "cluttered-3.json"), options);
}

TEST(DiagonalPairing, ClosedBoxKeepsItsPinnedPressure) {
  // The lid-driven cavity: no openings, one pressure pinned by its own row.
  Map map = default_arena(1.0, 1.0);
  FlowOptions options;
  options.cell = 0.1;
  options.closed = true;
  options.wall_speed[static_cast<int>(Side::Top)] = 1.0;
  check_pairing(map, options);
}

}  // namespace
}  // namespace plumekit::cfd
