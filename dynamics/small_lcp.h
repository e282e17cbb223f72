#pragma once
// An exact solver for the small linear complementarity problems of one contact manifold:
// the normal impulses of an area's corners solved together (block solving, as Box2D's
// two-point solver does), instead of one corner after another.

#include <Eigen/Core>
#include <optional>

namespace polysim::dynamics {

/// Most points solved as one block: 2^n active sets are tried, 16 at four corners (a box
/// face). Larger manifolds are solved point by point.
inline constexpr int kMaxBlockSize = 4;

/// Finds x >= 0 with w = A x + b >= 0 and x . w = 0, for symmetric positive semidefinite
/// A (n <= kMaxBlockSize), by trying every set of points that push (largest sets first).
/// Where A is singular (four coplanar corners of one rigid face carry a load in
/// infinitely many ways), each set's system is solved in the least-norm sense: the load
/// spreads evenly, as it does on a real face, not onto whichever corner came first.
/// Empty when no set satisfies the conditions within kLcpRoundOff of the problem's scale.
std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace polysim::dynamics
