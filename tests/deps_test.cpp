// The build finds and links every dependency the stages use: each test makes
// one real call through the library and checks its answer.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <Eigen/UmfPackSupport>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace {

// The 1-D Poisson matrix tridiag(-1, 2, -1): symmetric positive definite.
Eigen::SparseMatrix<double> poisson(int n) {
  Eigen::SparseMatrix<double> a(n, n);
  for (int i = 0; i < n; ++i) {
    a.insert(i, i) = 2.0;
    if (i > 0) a.insert(i, i - 1) = -1.0;
    if (i + 1 < n) a.insert(i, i + 1) = -1.0;
  }
  a.makeCompressed();
  return a;
}

TEST(Deps, UmfpackSolvesASparseSystem) {
  const auto a = poisson(50);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(50, -1.0, 1.0);
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu(a);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd b = a * x;
  EXPECT_LT((lu.solve(b) - x).norm(), 1e-10);
}

TEST(Deps, CholmodSolvesASparseSystem) {
  const auto a = poisson(50);
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(50);
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>> llt(a);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const Eigen::VectorXd b = a * x;
  EXPECT_LT((llt.solve(b) - x).norm(), 1e-10);
}

TEST(Deps, CgalPredicatesAreExact) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  // 0.1 + 0.2 != 0.3 in doubles; the point (0.3, 0.3) is still exactly collinear
  // with (0.1, 0.1) and (0.2, 0.2) as CGAL reads them.
  EXPECT_EQ(CGAL::orientation(K::Point_2(0.1, 0.1), K::Point_2(0.2, 0.2), K::Point_2(0.3, 0.3)),
            CGAL::COLLINEAR);
  EXPECT_EQ(CGAL::orientation(K::Point_2(0, 0), K::Point_2(1, 0), K::Point_2(0, 1)),
            CGAL::LEFT_TURN);
}

TEST(Deps, OmplBuildsAStateSpace) {
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
  ompl::base::RealVectorBounds bounds(2);
  bounds.setLow(0.0);
  bounds.setHigh(0, 10.0);
  bounds.setHigh(1, 4.0);
  space->setBounds(bounds);
  EXPECT_EQ(space->getDimension(), 2u);
  EXPECT_DOUBLE_EQ(space->getMaximumExtent(), std::hypot(10.0, 4.0));
}

}  // namespace
