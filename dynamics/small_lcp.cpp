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

std::optional<BlockVector> SmallLcp::solve(const BlockVector& b) const {
  const int n = static_cast<int>(b.size());
  // Round-off scale of the residuals: the problem's own magnitudes.
  const double scale = kLcpRoundOff * std::max({1.0, largestCoefficient_, b.cwiseAbs().maxCoeff()});
  for (unsigned set : setsLargestFirst(n)) {
    const Members in = membersOf(set, n);
    BlockVector x = BlockVector::Zero(n);
    if (in.count > 0) {
      using Stored = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockSize, kMaxBlockSize>>;
      Stored pinv(pseudoInverses_[set].data(), in.count, in.count);
      if (!(made_ & (1u << set))) {
        BlockMatrix Ass(in.count, in.count);
        for (int i = 0; i < in.count; ++i)
          for (int j = 0; j < in.count; ++j) Ass(i, j) = A_(in.index[i], in.index[j]);
        // The least-norm solution's operator, as CompleteOrthogonalDecomposition::solve
        // would apply it: rank found to the decomposition's own threshold.
        pinv = Eigen::CompleteOrthogonalDecomposition<BlockMatrix>(Ass).pseudoInverse();
        made_ |= 1u << set;
      }
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
