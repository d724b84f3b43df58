// The LinearSolver interface: make_linear_solver picks the implementation the
// options name, and both implementations give the same Newton step; the
// nullspace solver's single-precision LU, refined, gives that step too.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "cfd/linear_solver.hpp"
#include "cfd/navier_stokes.hpp"
#include "cfd/nullspace_solver.hpp"
#include "map/map_json.hpp"

extern "C" void sgemm_(const char*, const char*, const int*, const int*, const int*, const float*,
                       const float*, const int*, const float*, const int*, const float*, float*,
                       const int*, std::size_t, std::size_t);

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

// The step of `kind` for a Jacobian of `map`'s equations at a non-trivial
// state, with a pseudo-time term, through the interface only.
Eigen::VectorXd step_of(LinearSolverKind kind, const Map& map, Convection convection,
                        std::string& name) {
  FlowOptions options;
  options.cell = 0.2;
  const GridShape shape = GridShape::with_cell(map.width, map.height, options.cell);
  const StaggeredGrid grid(map, shape, options);
  NavierStokes equations(grid, convection);
  const int n = grid.unknowns();
  Eigen::VectorXd state(n);
  for (int k = 0; k < n; ++k)
    state[k] = 0.3 + 0.2 * std::sin(0.37 * k);
  equations.update_jacobian(state.data());
  equations.add_to_momentum_diagonal(0.5);
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(kind, grid, equations.jacobian());
  name = solver->name();
  EXPECT_TRUE(solver->factorize(equations.jacobian()));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x(n);
  solver->solve(equations.jacobian(), b.data(), x.data());
  // x solves J x = b to round-off, whichever implementation ran.
  const Eigen::SparseMatrix<double>& j = equations.jacobian();
  const double terms = (j.cwiseAbs() * x.cwiseAbs()).lpNorm<Eigen::Infinity>();
  // (The coupled LU runs without iterative refinement: a few 1e-12 of the terms.)
  EXPECT_LT((j * x - b).lpNorm<Eigen::Infinity>(), 1e-10 * terms) << name;
  return x;
}

TEST(LinearSolver, BothImplementationsGiveTheSameStep) {
  for (const char* file : {"cluttered-1.json", "cluttered-3.json"})
    for (Convection convection : {Convection::Central, Convection::VanLeer}) {
      const Map map = read_map(kMaps / file);
      std::string nullspace_name, coupled_name;
      const Eigen::VectorXd a =
          step_of(LinearSolverKind::Nullspace, map, convection, nullspace_name);
      const Eigen::VectorXd b = step_of(LinearSolverKind::Coupled, map, convection, coupled_name);
      EXPECT_EQ(nullspace_name, "nullspace");
      EXPECT_EQ(coupled_name, "coupled");
      EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-10 * b.lpNorm<Eigen::Infinity>())
          << file << " " << to_string(convection);
    }
}

TEST(LinearSolver, ReusedFactorizationSolvesFurtherRightHandSides) {
  // Chord steps: one factorization, several solves.
  const Map map = read_map(kMaps / "cluttered-2.json");
  FlowOptions options;
  options.cell = 0.2;
  const StaggeredGrid grid(map, GridShape::with_cell(map.width, map.height, options.cell), options);
  NavierStokes equations(grid, Convection::Central);
  const int n = grid.unknowns();
  const Eigen::VectorXd state = Eigen::VectorXd::Constant(n, 0.5);
  equations.update_jacobian(state.data());
  for (LinearSolverKind kind : {LinearSolverKind::Nullspace, LinearSolverKind::Coupled}) {
    const auto solver = make_linear_solver(kind, grid, equations.jacobian());
    ASSERT_TRUE(solver->factorize(equations.jacobian()));
    for (int r = 0; r < 3; ++r) {
      Eigen::VectorXd b(n), x(n);
      for (int k = 0; k < n; ++k)
        b[k] = std::cos(0.1 * k * (r + 1));
      solver->solve(equations.jacobian(), b.data(), x.data());
      const Eigen::VectorXd residual = equations.jacobian() * x - b;
      EXPECT_LT(residual.lpNorm<Eigen::Infinity>(), 1e-9) << solver->name() << " rhs " << r;
    }
  }
}

// A Newton matrix of cluttered-1 at 10 cm at a non-trivial state.
struct System {
  Map map = read_map(kMaps / "cluttered-1.json");
  FlowOptions options;
  StaggeredGrid grid;
  NavierStokes equations;
  System()
      : grid(map, GridShape::with_cell(map.width, map.height, 0.1), options),
        equations(grid, Convection::Central) {
    Eigen::VectorXd state(grid.unknowns());
    for (int k = 0; k < state.size(); ++k)
      state[k] = 0.4 + 0.3 * std::sin(0.13 * k);
    equations.update_jacobian(state.data());
  }
};

TEST(NavierStokes, ContinuityMatrixIsTheContinuityRowsOfTheJacobian) {
  // The projection of a coarse start (Newton::project_start) relies on D u + c
  // being the continuity residual: D must be the Jacobian's continuity rows on
  // the velocity columns, and the residual must change by D du.
  System s;
  const Eigen::SparseMatrix<double> d = s.equations.continuity_matrix();
  const int n = s.grid.unknowns(), n_mom = s.equations.momentum_rows();
  ASSERT_EQ(d.rows(), n - n_mom);
  ASSERT_EQ(d.cols(), n_mom);
  const Eigen::SparseMatrix<double> from_jacobian =
      s.equations.jacobian().block(n_mom, 0, n - n_mom, n_mom);
  const Eigen::SparseMatrix<double> difference = d - from_jacobian;
  double largest = 0.0;
  for (int k = 0; k < difference.nonZeros(); ++k)
    largest = std::max(largest, std::abs(difference.valuePtr()[k]));
  EXPECT_EQ(largest, 0.0);
  EXPECT_GT(d.nonZeros(), 3 * d.rows());
  Eigen::VectorXd u(n), du = Eigen::VectorXd::Zero(n), r0(n), r1(n);
  for (int k = 0; k < n; ++k)
    u[k] = std::cos(0.7 * k);
  for (int k = 0; k < n_mom; ++k)
    du[k] = std::sin(0.31 * k);
  s.equations.residual(u.data(), r0.data());
  const Eigen::VectorXd moved = u + du;
  s.equations.residual(moved.data(), r1.data());
  const Eigen::VectorXd change = (r1 - r0).tail(n - n_mom);
  EXPECT_LT((change - d * du.head(n_mom)).cwiseAbs().maxCoeff(),
            1e-9 * change.cwiseAbs().maxCoeff());
}

TEST(NullSpaceSolver, SinglePrecisionStepRefinesToTheDoubleStep) {
  if (!single_precision_lu_available()) GTEST_SKIP() << "built without MUMPS";
  System s;
  const Eigen::SparseMatrix<double>& j = s.equations.jacobian();
  NullSpaceSolver single(s.grid, j, ReducedLU::Single), exact(s.grid, j, ReducedLU::Double);
  ASSERT_TRUE(single.applicable());
  EXPECT_TRUE(single.single_precision());
  EXPECT_FALSE(exact.single_precision());
  ASSERT_TRUE(single.factorize(j));
  ASSERT_TRUE(exact.factorize(j));
  const int n = s.grid.unknowns();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x(n), reference(n), correction(n);
  exact.solve(j, b.data(), reference.data());
  single.solve(j, b.data(), x.data());
  const double scale = reference.lpNorm<Eigen::Infinity>();
  // Float's LU: a step to about 1 % (1.2e-2 here, 8e-3 before MUMPS's
  // one-column products went through SGEMV, which sums in another order), not
  // to round-off...
  const double first = (x - reference).lpNorm<Eigen::Infinity>() / scale;
  EXPECT_LT(first, 3e-2);
  EXPECT_GT(first, 1e-14);
  // ...which refinement with double residuals (as Newton's next residual does)
  // takes to the double step, to the round-off of this system's conditioning:
  // 8e-11 of the step in the release build, 2.4e-10 in the sanitizer build.
  for (int it = 0; it < 4; ++it) {
    const Eigen::VectorXd r = b - j * x;
    single.solve(j, r.data(), correction.data());
    x += correction;
  }
  EXPECT_LT((x - reference).lpNorm<Eigen::Infinity>(), 1e-8 * scale);
  EXPECT_LT((x - reference).lpNorm<Eigen::Infinity>(), 1e-4 * first * scale);
}

TEST(NullSpaceSolver, OneColumnSgemmIsSgemvInEveryTransposition) {
  // single_precision_lu.cpp's SGEMM, which MUMPS's solves call with one column:
  // C = alpha op(A) op(B) + beta C, against the sums written out.
  if (!single_precision_lu_available()) GTEST_SKIP() << "built without MUMPS";
  // The process's SGEMM, the one MUMPS is linked to, is this one.
  Dl_info where{};
  ASSERT_NE(dladdr(dlsym(RTLD_DEFAULT, "sgemm_"), &where), 0);
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "sgemm_"), reinterpret_cast<void*>(&sgemm_)) << where.dli_fname;
  const int m = 5, k = 3, lda = 7, ldb = 4, one = 1;
  std::vector<float> a(lda * 7), b(ldb * 4);
  for (std::size_t i = 0; i < a.size(); ++i)
    a[i] = static_cast<float>(std::sin(0.7 * i));
  for (std::size_t i = 0; i < b.size(); ++i)
    b[i] = static_cast<float>(std::cos(1.3 * i));
  const float alpha = 1.5f, beta = -0.5f;
  for (const char ta : {'N', 'T'})
    for (const char tb : {'N', 'T'}) {
      std::vector<float> c(m), expected(m);
      for (int i = 0; i < m; ++i) {
        c[i] = static_cast<float>(i) - 2.0f;
        double sum = 0.0;
        for (int p = 0; p < k; ++p)
          sum += double(ta == 'N' ? a[i + p * lda] : a[p + i * lda]) *
                 double(tb == 'N' ? b[p] : b[p * ldb]);
        expected[i] = static_cast<float>(alpha * sum + beta * c[i]);
      }
      sgemm_(&ta, &tb, &m, &one, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &m, 1,
             1);
      for (int i = 0; i < m; ++i)
        EXPECT_NEAR(c[i], expected[i], 1e-5) << ta << tb << " row " << i;
    }
  // No columns of A: C = beta C, which SGEMV would skip.
  const int zero = 0;
  std::vector<float> c(m, 2.0f);
  sgemm_("N", "N", &m, &one, &zero, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &m, 1,
         1);
  for (const float v : c)
    EXPECT_FLOAT_EQ(v, -1.0f);
}

TEST(NullSpaceSolver, SmallGridsFactorizeInDouble) {
  // By size: every grid of a 10 x 4 m map at the default 5 cm stays in double,
  // so the shipped maps' default flows are unchanged. K has at most one unknown
  // per interior node plus one per obstacle.
  System s;
  NullSpaceSolver by_size(s.grid, s.equations.jacobian());
  ASSERT_TRUE(by_size.applicable());
  EXPECT_FALSE(by_size.single_precision());
  const GridShape five_cm = GridShape::with_cell(10.0, 4.0, 0.05);
  EXPECT_LT((five_cm.nx - 1) * (five_cm.ny - 1) + 16, kSinglePrecisionFrom);
}

}  // namespace
}  // namespace plumekit::cfd
