#include "dynamics/small_lcp.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>

#include "dynamics/settings.h"

namespace polysim::dynamics {

namespace {

constexpr int pointsIn(unsigned set) {
  int count = 0;
  for (; set; set &= set - 1) ++count;
  return count;
}

// The sets of N points, largest first (in order of their bits among sets of one size).
// Made at compile time: a sweep asks for them once per block it solves.
template <int N>
constexpr std::array<unsigned, (1u << N)> setsLargestFirst() {
  std::array<unsigned, (1u << N)> sets{};
  size_t next = 0;
  for (int size = N; size >= 0; --size)
    for (unsigned s = 0; s < (1u << N); ++s)
      if (pointsIn(s) == size) sets[next++] = s;
  return sets;
}

// The points of a set, in order, and how many there are.
struct Members {
  std::array<int, kMaxBlockSize> index{};
  int count = 0;
};

Members membersOf(unsigned set, int n) {
  Members m;
  for (int i = 0; i < n; ++i)
    if (set & (1u << i)) m.index[m.count++] = i;
  return m;
}

// Ass's inverse in closed form (fixed size) when it is far from singular: the determinant
// of a symmetric positive definite matrix is at most the product of its diagonal
// (Hadamard), and one above kLcpRoundOff times it cannot come from round-off. Else the
// least-norm solution's operator, as CompleteOrthogonalDecomposition::solve would apply
// it, rank found to the decomposition's own threshold: four coplanar corners of one face
// carry a load in infinitely many ways, and the least-norm one spreads it evenly. A
// landing pile makes 7.9 operators per block and solve (its tilted boxes rest on two
// corners or three: pile of 343, first 1.5 s); made in closed form where they can be,
// the run took 17% fewer instructions.
template <int N>
bool invertIfRegular(const BlockMatrix& Ass, BlockMatrix& inverse) {
  const Eigen::Matrix<double, N, N> M = Ass;
  const double diagonal = M.diagonal().prod();
  if (!(diagonal > 0.0)) return false;
  Eigen::Matrix<double, N, N> inv;
  double determinant = 0.0;
  bool invertible = false;
  M.computeInverseAndDetWithCheck(inv, determinant, invertible, kLcpRoundOff * diagonal);
  if (!invertible || determinant <= 0.0) return false;
  inverse = inv;
  return true;
}

BlockMatrix leastNormOperator(const BlockMatrix& Ass) {
  BlockMatrix inverse;
  switch (Ass.rows()) {
    case 1: if (invertIfRegular<1>(Ass, inverse)) return inverse; break;
    case 2: if (invertIfRegular<2>(Ass, inverse)) return inverse; break;
    case 3: if (invertIfRegular<3>(Ass, inverse)) return inverse; break;
    case 4: if (invertIfRegular<4>(Ass, inverse)) return inverse; break;
    default: break;
  }
  return Eigen::CompleteOrthogonalDecomposition<BlockMatrix>(Ass).pseudoInverse();
}

}  // namespace

SmallLcp::SmallLcp(const BlockMatrix& A) : A_(A), largestCoefficient_(A.size() ? A.cwiseAbs().maxCoeff() : 0.0) {}

const double* SmallLcp::expandedPseudoInverse(unsigned set, int n) const {
  double* stored = pseudoInverses_[set].data();
  if (made_ & (1u << set)) return stored;
  const Members in = membersOf(set, n);
  Eigen::Map<BlockMatrix> expanded(stored, n, n);
  expanded.setZero();
  if (in.count > 0) {
    BlockMatrix Ass(in.count, in.count);
    for (int i = 0; i < in.count; ++i)
      for (int j = 0; j < in.count; ++j) Ass(i, j) = A_(in.index[i], in.index[j]);
    const BlockMatrix pinv = leastNormOperator(Ass);
    for (int i = 0; i < in.count; ++i)
      for (int j = 0; j < in.count; ++j) expanded(in.index[i], in.index[j]) = pinv(i, j);
  }
  made_ |= 1u << set;
  return stored;
}

template <int N>
std::optional<BlockVector> SmallLcp::solveWithSet(unsigned set, const BlockVector& b, double scale) const {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  const Eigen::Map<const Matrix> pinv(expandedPseudoInverse(set, N));
  const Eigen::Map<const Matrix> A(A_.data());  // n x n, stored contiguously
  const Eigen::Map<const Vector> bN(b.data());
  const Vector x = -(pinv * bN);  // zero outside the set
  // A member that would pull rules the set out before its velocities are worth forming:
  // four sets in five fail (a landing pile of 1000, first second: 26 M sets tried for
  // 4.9 M solves), as a box on two corners of its face lifts the other two.
  for (int i = 0; i < N; ++i)
    if ((set & (1u << i)) && x(i) < -scale) return std::nullopt;
  const Vector w = A * x + bN;
  for (int i = 0; i < N; ++i)
    if ((set & (1u << i)) ? std::abs(w(i)) > scale : w(i) < -scale) return std::nullopt;
  return BlockVector(x.cwiseMax(0.0));
}

template <int N>
std::optional<BlockVector> SmallLcp::solveSized(const BlockVector& b, double scale) const {
  static constexpr std::array<unsigned, (1u << N)> kSets = setsLargestFirst<N>();
  for (unsigned set : kSets)
    if (std::optional<BlockVector> x = solveWithSet<N>(set, b, scale)) return x;
  return std::nullopt;
}

std::optional<BlockVector> SmallLcp::solve(const BlockVector& b) const {
  // Round-off scale of the residuals: the problem's own magnitudes.
  const double scale = kLcpRoundOff * std::max({1.0, largestCoefficient_, b.cwiseAbs().maxCoeff()});
  // In fixed-size arithmetic per size: each set's operator kept expanded to n x n (zero
  // outside the set), a try is two products of 4 x 4 at most, with no gathering.
  switch (b.size()) {
    case 1: return solveSized<1>(b, scale);
    case 2: return solveSized<2>(b, scale);
    case 3: return solveSized<3>(b, scale);
    case 4: return solveSized<4>(b, scale);
    default: return std::nullopt;
  }
}

std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const std::optional<BlockVector> x = SmallLcp(A).solve(b);
  if (!x) return std::nullopt;
  return Eigen::VectorXd(*x);
}

}  // namespace polysim::dynamics
