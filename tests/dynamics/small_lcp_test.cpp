// solveSmallLcp() and the block solving it gives the contact solver: an area's corners
// solved together carry a load evenly and at once.

#include "dynamics/small_lcp.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <random>

#include "dynamics/contact_solver.h"
#include "dynamics/mass_properties.h"

namespace polysim::dynamics {
namespace {

using V3 = Eigen::Vector3d;

// x >= 0, w = A x + b >= 0, x . w = 0, each to `tol`.
void expectComplementary(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x, double tol) {
  const Eigen::VectorXd w = A * x + b;
  for (int i = 0; i < x.size(); ++i) {
    EXPECT_GE(x(i), 0.0);
    EXPECT_GE(w(i), -tol) << "point " << i;
    EXPECT_NEAR(x(i) * w(i), 0.0, tol) << "point " << i;
  }
}

TEST(SmallLcp, DiagonalProblemPushesOnlyWhereItApproaches) {
  const Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d b(-1, 2, -3);
  const std::optional<Eigen::VectorXd> x = solveSmallLcp(A, b);
  ASSERT_TRUE(x);
  EXPECT_EQ(*x, Eigen::Vector3d(1, 0, 3));
}

// Four corners of a point mass (all rows couple fully: A = ones) approaching at unit
// speed: any impulses adding up to 1 stop it, and the least-norm answer is a quarter each.
TEST(SmallLcp, SingularProblemSpreadsTheLoadEvenly) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Ones(4, 4);
  const Eigen::VectorXd b = -Eigen::VectorXd::Ones(4);
  const std::optional<Eigen::VectorXd> x = solveSmallLcp(A, b);
  ASSERT_TRUE(x);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR((*x)(i), 0.25, 1e-12);
}

TEST(SmallLcp, RandomPositiveDefiniteProblemsAreSolvedExactly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % kMaxBlockSize;
    Eigen::MatrixXd M(n, n);
    for (int i = 0; i < n * n; ++i) M(i) = u(rng);
    const Eigen::MatrixXd A = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b(i) = u(rng);
    const std::optional<Eigen::VectorXd> x = solveSmallLcp(A, b);
    ASSERT_TRUE(x) << "trial " << trial;
    expectComplementary(A, b, *x, 1e-9);
  }
}

// Singular problems that rank-deficient contacts give (the coplanar corners of a face: A
// = J M^-1 J^T of rank 3 for 4 corners), with a random part of b the corners cannot meet
// together (along A's null space, a twist no load produces): some corner must lift off,
// and every point pushing, solved in the least-norm sense, is not an answer even where
// its impulses come out positive.
TEST(SmallLcp, RandomSingularProblemsLiftTheCornersTheyMust) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  int unmet = 0, met = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::MatrixXd J(4, 3);  // each corner's normal row: [1, y, -x] for a face in z
    for (int i = 0; i < 4; ++i) J.row(i) << 1.0, 0.5 * (i < 2 ? 1 : -1) + 0.1 * u(rng), 0.5 * (i % 2 ? 1 : -1) + 0.1 * u(rng);
    const Eigen::MatrixXd A = J * Eigen::Vector3d(1.0, 6.0, 6.0).asDiagonal() * J.transpose();
    const Eigen::VectorXd null = Eigen::FullPivLU<Eigen::MatrixXd>(J.transpose()).kernel().col(0).normalized();
    // Every fourth trial meets the corners together: no part along the null space.
    Eigen::VectorXd b = -Eigen::VectorXd::Ones(4) + (trial % 4 == 0 ? 0.0 : 0.3 * u(rng)) * null;
    const Eigen::VectorXd leastNorm = -(Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).pseudoInverse() * b);
    unmet += leastNorm.minCoeff() >= 0 && (A * leastNorm + b).minCoeff() < -1e-6;
    const bool allPushing = leastNorm.minCoeff() >= 0 && (A * leastNorm + b).cwiseAbs().maxCoeff() < 1e-9;
    met += allPushing;
    const std::optional<Eigen::VectorXd> x = solveSmallLcp(A, b);
    ASSERT_TRUE(x) << "trial " << trial;
    expectComplementary(A, b, *x, 1e-9);
    // Where every corner pushing meets every target, the answer is the least-norm one,
    // though A is singular only to round-off (its determinant is not exactly zero).
    if (allPushing) {
      EXPECT_LT((*x - leastNorm).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(unmet, 20) << "trials where every corner pushing has positive impulses yet misses a target";
  EXPECT_GT(met, 20) << "trials where every corner pushing is the answer";
}

RigidBody unitCube() {
  MassProperties props;
  props.mass = 1.0;
  props.inertia = Eigen::Matrix3d::Identity() / 6.0;
  return RigidBody::dynamic(props);
}

// A unit cube on the floor, falling at g dt, its four corners one area contact: solved as
// a block, the first sweep stops it with a quarter of the impulse at each corner and no
// spin. Solved corner by corner from a cold start, the first corner takes the load and the
// others take it back over many sweeps.
TEST(BlockSolving, ACubeOnTheFloorIsStoppedEvenlyInOneSweep) {
  for (bool blocked : {true, false}) {
    std::vector<RigidBody> bodies = {unitCube(), RigidBody::fixed()};
    bodies[0].position = V3(0, 0, 0.5);
    bodies[0].velocity = V3(0, 0, -9.81 / 60);
    std::vector<ContactPoint> contacts;
    for (double x : {-0.5, 0.5})
      for (double y : {-0.5, 0.5}) contacts.push_back({0, 1, V3(x, y, 0), V3::UnitZ(), 0.0, 0.0, 0.5, blocked ? 0 : -1});
    const SolveStats stats = solveContacts(bodies, contacts, 1.0 / 60);
    EXPECT_NEAR(bodies[0].velocity.norm(), 0.0, 1e-10);
    EXPECT_NEAR(bodies[0].angularVelocity.norm(), 0.0, 1e-10);
    if (!blocked) {
      EXPECT_GT(stats.iterations, 2);
      continue;
    }
    EXPECT_LE(stats.iterations, 2);  // one sweep solves it, the next finds nothing to change
    for (const ContactPoint& c : contacts) EXPECT_NEAR(c.normalImpulse, 9.81 / 60 / 4, 1e-12);
  }
}

}  // namespace
}  // namespace polysim::dynamics
