#pragma once
// The contact solver's sweeps (sequential impulses over prepared rows), shared by the
// main solve (contact_solver.cpp) and shock propagation (shock_propagation.h). Internal
// to the solver.

#include <utility>
#include <vector>

#include "dynamics/contact_row.h"
#include "dynamics/contact_solver.h"
#include "dynamics/small_lcp.h"
#include "dynamics/solve_bodies.h"

namespace polysim::dynamics::solver {

/// Their kinetic energy (J).
double kineticEnergy(const std::vector<RigidBody*>& bodies);

/// Sets the row's three axes and their effective masses from its bodies, frames and
/// arms: a body marked static (or with zero inverse mass and frame) takes no impulse.
void prepareAxes(Row& r);

/// The order of a solve's sweeps, flat: the rows copied group after group, each group's
/// blocks in the rows' order and each block's rows together, so that a sweep reads one
/// stretch of rows in order without chasing a vector per block or group.
struct SweepLayout {
  struct Block {
    int first = 0, count = 0;              // its rows: [first, first + count) of the copy
    const SmallLcp* coupling = nullptr;    // its coupling matrix, or null for one row
  };
  std::vector<Block> blocks;     // group after group
  std::vector<int> groupStart;   // group g's: blocks[groupStart[g], groupStart[g + 1])
  std::vector<int> rowOf;        // the solve's row at each place of the copy: every row once

  int groupCount() const { return static_cast<int>(groupStart.size()) - 1; }
  /// Group g's rows: [first, end) of the copy.
  std::pair<int, int> rowSpan(int g) const {
    const Block& last = blocks[static_cast<size_t>(groupStart[g + 1]) - 1];
    return {blocks[static_cast<size_t>(groupStart[g])].first, last.first + last.count};
  }
};

/// The rows of one solve, laid out for sweeping: the blocks (an area's corners or a
/// line's ends, solved together by small_lcp.h; any other point alone), each block's
/// coupling matrix, and the groups of blocks that share no moving body. Built once per
/// solve: the poses and rows' axes do not change while it sweeps.
class ContactSweeps {
 public:
  explicit ContactSweeps(const std::vector<Row>& rows);
  ContactSweeps(const ContactSweeps&) = delete;  // the layout points into couplings_
  ContactSweeps& operator=(const ContactSweeps&) = delete;

  /// Sweeps each group until no impulse changes by kSolverVelocityTolerance (m/s over the
  /// lighter body's mass) or its limit is reached: kMaxSolverIterations, or `maxSweeps`
  /// if fewer or if at that point no contact moves faster than kSettlingSpeed (a settling
  /// group, settings.h), whose sweeps also stop once they stall (kSettlingStallWindow).
  /// Each sweep solves each block's friction rows, then its normal impulses. Sweeps run in
  /// the rows' order (bottom-up: the first carries a stack's weight down in one pass),
  /// then backwards, and so on (symmetric Gauss-Seidel). `iterations` is the most sweeps any
  /// group took; `converged`, whether every group stopped on the tolerance. A solve of at
  /// least kSharedSweepRows rows sweeps its groups on two threads (work_sharing.h), with
  /// the same result. Not re-entrant on one thread: the rows are swept in a copy each
  /// thread keeps from run to run.
  SolveStats run(std::vector<Row>& rows, int maxSweeps) const;

  /// The rows of each group of blocks that share no moving body (the groups the sweeps
  /// converge one by one), each group's rows in increasing order.
  std::vector<std::vector<int>> groupRows() const;

  /// The rows' bodies, numbered: for whatever else the solve keeps per body.
  const SolveBodies& bodies() const { return bodies_; }

 private:
  SolveBodies bodies_;
  std::vector<SmallLcp> couplings_;  // one per block of several rows; the layout points into it
  SweepLayout layout_;
  std::vector<int> groupOrder_;  // the order the groups are taken in: largest first if shared()

  bool shared() const;  // whether run() sweeps on two threads (kSharedSweepRows)
};

}  // namespace polysim::dynamics::solver
