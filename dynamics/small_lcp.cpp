#include "dynamics/small_lcp.h"

#include <Eigen/QR>
#include <algorithm>
#include <vector>

#include "dynamics/settings.h"

namespace polysim::dynamics {

namespace {

int pointsIn(unsigned set) {
  int count = 0;
  for (; set; set &= set - 1) ++count;
  return count;
}

// The sets of n points, largest first (in order of their bits among sets of one size).
const std::vector<unsigned>& setsLargestFirst(int n) {
  static const std::array<std::vector<unsigned>, kMaxBlockSize + 1> table = [] {
    std::array<std::vector<unsigned>, kMaxBlockSize + 1> sets;
    for (int size = 0; size <= kMaxBlockSize; ++size) {
      for (unsigned s = 0; s < (1u << size); ++s) sets[size].push_back(s);
      std::stable_sort(sets[size].begin(), sets[size].end(), [](unsigned x, unsigned y) { return pointsIn(x) > pointsIn(y); });
    }
    return sets;
  }();
  return table[n];
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

}  // namespace

SmallLcp::SmallLcp(const BlockMatrix& A) : A_(A), largestCoefficient_(A.size() ? A.cwiseAbs().maxCoeff() : 0.0) {}

const double* SmallLcp::pseudoInverse(unsigned set, int n) const {
  double* stored = pseudoInverses_[set].data();
  if (made_ & (1u << set)) return stored;
  const Members in = membersOf(set, n);
  BlockMatrix Ass(in.count, in.count);
  for (int i = 0; i < in.count; ++i)
    for (int j = 0; j < in.count; ++j) Ass(i, j) = A_(in.index[i], in.index[j]);
  // The least-norm solution's operator, as CompleteOrthogonalDecomposition::solve would
  // apply it: rank found to the decomposition's own threshold.
  Eigen::Map<BlockMatrix>(stored, in.count, in.count) = Eigen::CompleteOrthogonalDecomposition<BlockMatrix>(Ass).pseudoInverse();
  made_ |= 1u << set;
  return stored;
}

template <int N>
std::optional<BlockVector> SmallLcp::solveWithEveryPoint(const BlockVector& b, double scale) const {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  const Eigen::Map<const Matrix> pinv(pseudoInverse((1u << N) - 1, N));
  const Eigen::Map<const Matrix> A(A_.data());  // n x n, stored contiguously
  const Eigen::Map<const Vector> bN(b.data());
  const Vector x = -(pinv * bN);
  const Vector w = A * x + bN;
  for (int i = 0; i < N; ++i)
    if (x(i) < -scale || std::abs(w(i)) > scale) return std::nullopt;
  return BlockVector(x.cwiseMax(0.0));
}

std::optional<BlockVector> SmallLcp::solve(const BlockVector& b) const {
  const int n = static_cast<int>(b.size());
  // Round-off scale of the residuals: the problem's own magnitudes.
  const double scale = kLcpRoundOff * std::max({1.0, largestCoefficient_, b.cwiseAbs().maxCoeff()});
  // Every point pushing is the set tried first and the one that holds in nearly every
  // solve (a face resting on its corners): tried in fixed-size arithmetic, about three
  // times quicker than the general path below.
  std::optional<BlockVector> every;
  switch (n) {
    case 2: every = solveWithEveryPoint<2>(b, scale); break;
    case 3: every = solveWithEveryPoint<3>(b, scale); break;
    case 4: every = solveWithEveryPoint<4>(b, scale); break;
    default: break;
  }
  if (every) return every;
  const bool everyTried = n >= 2;
  for (unsigned set : setsLargestFirst(n)) {
    if (everyTried && set == (1u << n) - 1) continue;
    const Members in = membersOf(set, n);
    BlockVector x = BlockVector::Zero(n);
    if (in.count > 0) {
      using Stored = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockSize, kMaxBlockSize>>;
      const Stored pinv(pseudoInverse(set, n), in.count, in.count);
      BlockVector bs(in.count);
      for (int i = 0; i < in.count; ++i) bs(i) = b(in.index[i]);
      const BlockVector xs = -(pinv * bs);
      for (int i = 0; i < in.count; ++i) x(in.index[i]) = xs(i);
    }
    const BlockVector w = A_ * x + b;
    bool valid = true;
    for (int i = 0; i < n && valid; ++i) valid = (set & (1u << i)) ? x(i) >= -scale && std::abs(w(i)) <= scale : w(i) >= -scale;
    if (valid) return BlockVector(x.cwiseMax(0.0));
  }
  return std::nullopt;
}

std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const std::optional<BlockVector> x = SmallLcp(A).solve(b);
  if (!x) return std::nullopt;
  return Eigen::VectorXd(*x);
}

}  // namespace polysim::dynamics
