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

}  // namespace

std::optional<Eigen::VectorXd> solveSmallLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(b.size());
  // Round-off scale of the residuals: the problem's own magnitudes.
  const double scale = kLcpRoundOff * std::max({1.0, A.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()});
  std::vector<unsigned> sets;
  for (unsigned s = 0; s < (1u << n); ++s) sets.push_back(s);
  std::stable_sort(sets.begin(), sets.end(), [](unsigned x, unsigned y) { return pointsIn(x) > pointsIn(y); });
  for (unsigned set : sets) {
    std::vector<int> in;
    for (int i = 0; i < n; ++i)
      if (set & (1u << i)) in.push_back(i);
    Eigen::MatrixXd Ass(in.size(), in.size());
    Eigen::VectorXd bs(in.size());
    for (size_t i = 0; i < in.size(); ++i) {
      bs(i) = b(in[i]);
      for (size_t j = 0; j < in.size(); ++j) Ass(i, j) = A(in[i], in[j]);
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    if (!in.empty()) {
      const Eigen::VectorXd xs = Ass.completeOrthogonalDecomposition().solve(-bs);
      for (size_t i = 0; i < in.size(); ++i) x(in[i]) = xs(i);
    }
    const Eigen::VectorXd w = A * x + b;
    bool valid = true;
    for (int i = 0; i < n && valid; ++i) valid = (set & (1u << i)) ? x(i) >= -scale && std::abs(w(i)) <= scale : w(i) >= -scale;
    if (valid) return x.cwiseMax(0.0);
  }
  return std::nullopt;
}

}  // namespace polysim::dynamics
