// The single-precision LU (MUMPS) from several threads at once: sequential MUMPS keeps process-wide
// state, so without its lock two factorizations at once corrupted the heap (dataset generate -j 2
// on random buildings crashed, "PB allocation in SMUMPS_LOAD_INIT").
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <thread>
#include <vector>

#include "cfd/single_precision_lu.hpp"

namespace {

using plumekit::cfd::SinglePrecisionLU;

// A 2-D advection-diffusion operator on an n x n grid: unsymmetric, diagonally dominant.
Eigen::SparseMatrix<double> operator_of(int n, double wind) {
  std::vector<Eigen::Triplet<double>> t;
  auto at = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      t.emplace_back(at(i, j), at(i, j), 4.0 + wind);
      if (i > 0) t.emplace_back(at(i, j), at(i - 1, j), -1.0 - wind);
      if (i + 1 < n) t.emplace_back(at(i, j), at(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(at(i, j), at(i, j - 1), -1.0);
      if (j + 1 < n) t.emplace_back(at(i, j), at(i, j + 1), -1.0);
    }
  Eigen::SparseMatrix<double> a(n * n, n * n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

// max |A x - b| / max |b| of one analyse-factorize-solve, repeated.
double worst_residual(int n, double wind, int rounds) {
  const Eigen::SparseMatrix<double> a = operator_of(n, wind);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), 1.0, 2.0), x(a.rows());
  double worst = 0.0;
  for (int r = 0; r < rounds; ++r) {
    SinglePrecisionLU lu;
    lu.analyze(a);
    if (!lu.factorize(a)) return INFINITY;
    lu.solve(b.data(), x.data());
    worst = std::max(worst, (a * x - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(SinglePrecisionLU, FactorizationsInSeveralThreadsAtOnce) {
  if (!plumekit::cfd::single_precision_lu_available()) GTEST_SKIP() << "built without MUMPS";
  constexpr int kThreads = 3;
  std::vector<double> residual(kThreads);
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreads; ++k)
    threads.emplace_back([&, k] { residual[k] = worst_residual(120 + 10 * k, 0.5 * k, 4); });
  for (auto& t : threads)
    t.join();
  for (int k = 0; k < kThreads; ++k)
    EXPECT_LT(residual[k], 1e-2) << "thread " << k;  // float factors: about 1e-3 here
}

}  // namespace
