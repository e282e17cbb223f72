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

// A face's four corners (A = J M^-1 J^T, of rank 3) solved again and again by one
// SmallLcp, as a block is through a solve's sweeps: a load that first lifts a corner and
// then comes down evenly must be spread evenly again, whatever set held the time before
// (three corners of a rectangle, or two across it, also meet every target: the answer a
// block would keep were the set that held last tried before larger ones).
TEST(SmallLcp, AFaceLoadedEvenlyAfterATiltSpreadsItsLoadEvenly) {
  Eigen::MatrixXd J(4, 3);  // each corner's normal row [1, y, -x] on a unit square in z
  for (int i = 0; i < 4; ++i) J.row(i) << 1.0, i < 2 ? 0.5 : -0.5, i % 2 ? -0.5 : 0.5;
  const BlockMatrix A = J * Eigen::Vector3d(1.0, 6.0, 6.0).asDiagonal() * J.transpose();
  const Eigen::Vector4d null(1, -1, -1, 1);  // the twist no load produces: J^T null = 0
  ASSERT_LT((J.transpose() * null).norm(), 1e-15);
  const SmallLcp lcp(A);
  for (double twist : {0.3, -0.3, 0.6}) {
    const std::optional<BlockVector> tilted = lcp.solve(BlockVector(-Eigen::Vector4d::Ones() + twist * null));
    ASSERT_TRUE(tilted);
    ASSERT_LT(tilted->minCoeff(), 1e-12) << "twist " << twist << ": a corner lifts";
    const std::optional<BlockVector> even = lcp.solve(BlockVector(-Eigen::Vector4d::Ones()));
    ASSERT_TRUE(even);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR((*even)(i), 0.25, 1e-12) << "twist " << twist << ", corner " << i;
  }
}

// One SmallLcp through a random sequence of problems answers each as a fresh one does:
// the same velocities (w = A x + b is one for every answer of a semidefinite problem),
// and the same impulses wherever the fresh answer has every corner pushing.
TEST(SmallLcp, ASequenceOfProblemsIsSolvedAsEachAlone) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  int everyPushing = 0, someLifting = 0;
  for (int face = 0; face < 20; ++face) {
    Eigen::MatrixXd J(4, 3);
    for (int i = 0; i < 4; ++i) J.row(i) << 1.0, 0.5 * (i < 2 ? 1 : -1) + 0.1 * u(rng), 0.5 * (i % 2 ? 1 : -1) + 0.1 * u(rng);
    const BlockMatrix A = J * Eigen::Vector3d(1.0, 6.0, 6.0).asDiagonal() * J.transpose();
    const Eigen::Vector4d null = Eigen::FullPivLU<Eigen::MatrixXd>(J.transpose()).kernel().col(0).normalized();
    const SmallLcp reused(A);
    for (int k = 0; k < 30; ++k) {
      // A body approaching the face while turning a little (b in A's range: the corners
      // can all meet it), a third of the time with a twist no load produces, now and then anything.
      Eigen::Vector4d b = J * Eigen::Vector3d(-1.0 + 0.2 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
      if (k % 3 == 1) b += 0.3 * u(rng) * null;
      if (k % 7 == 3) b = Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng));
      const std::optional<BlockVector> x = reused.solve(BlockVector(b));
      const std::optional<BlockVector> alone = SmallLcp(A).solve(BlockVector(b));
      ASSERT_TRUE(x && alone) << "face " << face << ", problem " << k;
      expectComplementary(A, b, *x, 1e-9);
      EXPECT_LT((A * (*x - *alone)).cwiseAbs().maxCoeff(), 1e-9) << "face " << face << ", problem " << k;
      if (alone->minCoeff() > 1e-9) {
        ++everyPushing;
        EXPECT_LT((*x - *alone).cwiseAbs().maxCoeff(), 1e-9) << "face " << face << ", problem " << k;
      } else {
        ++someLifting;
      }
    }
  }
  EXPECT_GT(everyPushing, 50);
  EXPECT_GT(someLifting, 50);
}

// One SmallLcp solving problem after problem, as a block's does through a solve's sweeps
// (its operators made once and kept), answers each as a fresh one does, to the bit, above
// all where several sets hold and which one is taken decides the answer's bits: problems
// built from an answer x and velocities w with points at zero impulse and zero velocity
// both, on random regular matrices and on a face's four coplanar corners (rank 3). Any
// order of tries that starts from the set the last solve took must pass it too (README,
// Benchmarks: one that did, measured and not kept).
TEST(SmallLcp, ASolverUsedAgainAnswersToTheBitAsAFreshOneWhereSeveralSetsHold) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1), positive(0.1, 1.0);
  std::bernoulli_distribution half(0.5);
  int degenerate = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + trial % (kMaxBlockSize - 1);
    BlockMatrix A(n, n);
    if (n == 4 && trial % 2) {  // a face's corners, as in RandomSingularProblemsLiftTheCornersTheyMust
      Eigen::MatrixXd J(4, 3);
      for (int i = 0; i < 4; ++i) J.row(i) << 1.0, 0.5 * (i < 2 ? 1 : -1) + 0.1 * u(rng), 0.5 * (i % 2 ? 1 : -1) + 0.1 * u(rng);
      A = J * Eigen::Vector3d(1.0, 6.0, 6.0).asDiagonal() * J.transpose();
    } else {
      Eigen::MatrixXd M(n, n);
      for (int i = 0; i < n * n; ++i) M(i) = u(rng);
      A = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    }
    const SmallLcp kept(A);
    for (int k = 0; k < 12; ++k) {
      Eigen::VectorXd x = Eigen::VectorXd::Zero(n), w = Eigen::VectorXd::Zero(n);
      bool several = false;
      for (int i = 0; i < n; ++i) {
        if (half(rng)) x(i) = positive(rng);
        else if (half(rng)) w(i) = positive(rng);
        else several = true;  // zero impulse and zero velocity: in the set or out of it
      }
      degenerate += several;
      const BlockVector b = w - A * x;
      const std::optional<BlockVector> reused = kept.solve(b);
      const std::optional<BlockVector> fresh = SmallLcp(A).solve(b);
      ASSERT_EQ(reused.has_value(), fresh.has_value()) << "trial " << trial << ", problem " << k;
      if (!fresh) continue;
      for (int i = 0; i < n; ++i)
        ASSERT_EQ((*reused)(i), (*fresh)(i)) << "trial " << trial << ", problem " << k << ", point " << i;
    }
  }
  EXPECT_GT(degenerate, 500) << "problems where several sets hold";
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
