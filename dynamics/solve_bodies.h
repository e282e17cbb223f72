#pragma once
// The bodies one contact solve touches, numbered from zero. Internal to the solver.

#include <cstddef>
#include <vector>

#include "dynamics/contact_row.h"

namespace polysim::dynamics::solver {

/// The bodies a solve's rows name (their sources' indices into the world's body array,
/// static ones included), numbered 0 to count() - 1 in the order the rows first name
/// them. What a solve keeps per body (the union-find of its groups, shock propagation's
/// levels) is then as large as the solve, not the world: a landing pile of 1000 boxes
/// sets up about 1,900 sweeps a step, most over a few bodies (an event's groups, one
/// level of shock propagation), and clearing arrays over all 1,006 bodies for each took
/// 0.7% of its instructions (callgrind, its first 1.2 s).
class SolveBodies {
 public:
  explicit SolveBodies(const std::vector<Row>& rows);
  int count() const { return count_; }
  /// The numbers of row k's bodies a and b.
  int a(std::size_t k) const { return numbers_[2 * k]; }
  int b(std::size_t k) const { return numbers_[2 * k + 1]; }
  /// The moving bodies the rows name (static ones left out), each once, in the order the
  /// rows first name them. `rows` are the rows numbered.
  std::vector<RigidBody*> moving(const std::vector<Row>& rows) const;

 private:
  int count_ = 0;
  std::vector<int> numbers_;  // each row's a and b, row after row
};

}  // namespace polysim::dynamics::solver
