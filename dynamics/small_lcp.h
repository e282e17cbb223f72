#pragma once
// An exact solver for the small linear complementarity problems of one contact manifold:
// the normal impulses of an area's corners solved together (block solving, as Box2D's
// two-point solver does), instead of one corner after another.

#include <Eigen/Core>
#include <array>
#include <optional>

namespace polysim::dynamics {

/// Most points solved as one block: 2^n active sets are tried, 16 at four corners (a box
/// face). Larger manifolds are solved point by point.
inline constexpr int kMaxBlockSize = 4;

/// A block's vector and matrix: at most kMaxBlockSize entries a side, stored in place, so
/// that the sweeps, which solve every block once each, never allocate.
using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockSize, 1>;
using BlockMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockSize, kMaxBlockSize>;

/// The problems x >= 0, w = A x + b >= 0, x . w = 0 for one symmetric positive
/// semidefinite A (n <= kMaxBlockSize) and any b: a contact's block through the sweeps of
/// one solve, where A stays and b changes. Each set of points that push is tried, largest
/// sets first; where A is singular (four coplanar corners of one rigid face carry a load
/// in infinitely many ways), a set's system is solved in the least-norm sense, so the
/// load spreads evenly, as on a real face, not onto whichever corner came first. Each
/// set's pseudo-inverse (its inverse in closed form where it is regular beyond round-off)
/// is made once, when first needed, and kept expanded to n x n (zero outside the set); a
/// try is then two fixed-size products of at most 4 x 4.
class SmallLcp {
 public:
  explicit SmallLcp(const BlockMatrix& A);
  const BlockMatrix& matrix() const { return A_; }
  /// The solution for `b`, or empty when no set satisfies the conditions within
  /// kLcpRoundOff of the problem's scale.
  std::optional<BlockVector> solve(const BlockVector& b) const;

 private:
  // Set `set`'s pseudo-inverse expanded to n x n (zero outside the set), made on first use.
  const double* expandedPseudoInverse(unsigned set, int n) const;
  // One set tried for a problem of size N; empty when it does not hold.
  template <int N>
  std::optional<BlockVector> solveWithSet(unsigned set, const BlockVector& b, double scale) const;
  // Every set, largest first, for a problem of size N.
  template <int N>
  std::optional<BlockVector> solveSized(const BlockVector& b, double scale) const;

  BlockMatrix A_;
  double largestCoefficient_;
  // Each set's pseudo-inverse, expanded to n x n, column-major, once made (bit `set` of
  // made_). Raw storage, so that making a SmallLcp touches only A_ and made_: a pile's
  // solve makes thousands, most of which try one set.
  mutable unsigned made_ = 0;
  mutable std::array<std::array<double, kMaxBlockSize * kMaxBlockSize>, 1u << kMaxBlockSize> pseudoInverses_;
};

/// SmallLcp(A).solve(b): one problem on its own.
std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace polysim::dynamics
