#include "dynamics/small_lcp.h"

#include <Eigen/Dense>
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

std::vector<int> members(unsigned set, int n) {
  std::vector<int> in;
  for (int i = 0; i < n; ++i)
    if (set & (1u << i)) in.push_back(i);
  return in;
}

}  // namespace

SmallLcp::SmallLcp(const Eigen::MatrixXd& A) : A_(A), largestCoefficient_(A.size() ? A.cwiseAbs().maxCoeff() : 0.0) {}

std::optional<Eigen::VectorXd> SmallLcp::solve(const Eigen::VectorXd& b) const {
  const int n = static_cast<int>(b.size());
  // Round-off scale of the residuals: the problem's own magnitudes.
  const double scale = kLcpRoundOff * std::max({1.0, largestCoefficient_, b.cwiseAbs().maxCoeff()});
  for (unsigned set : setsLargestFirst(n)) {
    const std::vector<int> in = members(set, n);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    if (!in.empty()) {
      std::optional<Decomposition>& solver = decompositions_[set];
      if (!solver) {
        Eigen::MatrixXd Ass(in.size(), in.size());
        for (size_t i = 0; i < in.size(); ++i)
          for (size_t j = 0; j < in.size(); ++j) Ass(i, j) = A_(in[i], in[j]);
        solver.emplace(Ass);
      }
      Eigen::VectorXd bs(in.size());
      for (size_t i = 0; i < in.size(); ++i) bs(i) = b(in[i]);
      const Eigen::VectorXd xs = solver->solve(-bs);
      for (size_t i = 0; i < in.size(); ++i) x(in[i]) = xs(i);
    }
    const Eigen::VectorXd w = A_ * x + b;
    bool valid = true;
    for (int i = 0; i < n && valid; ++i) valid = (set & (1u << i)) ? x(i) >= -scale && std::abs(w(i)) <= scale : w(i) >= -scale;
    if (valid) return x.cwiseMax(0.0);
  }
  return std::nullopt;
}

std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return SmallLcp(A).solve(b);
}

}  // namespace polysim::dynamics
