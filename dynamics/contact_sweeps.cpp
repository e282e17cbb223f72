#include "dynamics/contact_sweeps.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>

#include "dynamics/buckets.h"
#include "dynamics/disjoint_sets.h"
#include "dynamics/settings.h"
#include "dynamics/settling_progress.h"
#include "dynamics/solve_bodies.h"
#include "dynamics/work_sharing.h"

namespace polysim::dynamics::solver {

double kineticEnergy(const std::vector<RigidBody*>& bodies) {
  double e = 0.0;
  for (const RigidBody* b : bodies) e += b->kineticEnergy();
  return e;
}

void prepareAxes(Row& r) {
  r.normalAxis = axisOf(r, r.normal);
  r.tangentAxis1 = axisOf(r, r.tangent1);
  r.tangentAxis2 = axisOf(r, r.tangent2);
  r.normalMass = effectiveMass(r, r.normalAxis);
  if (r.friction > 0) {
    r.tangentMass1 = effectiveMass(r, r.tangentAxis1);
    r.tangentMass2 = effectiveMass(r, r.tangentAxis2);
  }
}

namespace {

// Lays out the blocks, in the order their first rows come: the rows of each contact
// (sharing a manifold id, in the rows' order) are a block, an area's corners or a line's
// ends; a point, or a contact larger than kMaxBlockSize, is a block of one row. A
// contact's rows need not be consecutive: the rows come in the order the sweeps take
// them (bottom-up), corners of different contacts interleaved.
void layBlocks(const std::vector<Row>& rows, SweepLayout& layout) {
  const int n = static_cast<int>(rows.size());
  std::vector<std::pair<int, int>> byId;  // (manifold id, row) of the rows in a manifold
  for (int k = 0; k < n; ++k)
    if (const int id = rows[k].source->manifold; id >= 0) byId.emplace_back(id, k);
  std::sort(byId.begin(), byId.end());
  // Each manifold's run of rows in byId, [first, end), found at the manifold's first row.
  std::vector<std::pair<int, int>> runs;
  std::vector<int> runAt(static_cast<size_t>(n), -1);
  for (size_t i = 0, end = 0; i < byId.size(); i = end) {
    for (end = i + 1; end < byId.size() && byId[end].first == byId[i].first;) ++end;
    runAt[byId[i].second] = static_cast<int>(runs.size());
    runs.emplace_back(static_cast<int>(i), static_cast<int>(end));
  }
  layout.blockRows.reserve(static_cast<size_t>(n));
  const auto addBlock = [&](int count) {
    layout.blocks.push_back({static_cast<int>(layout.blockRows.size()) - count, count, nullptr});
  };
  for (int k = 0; k < n; ++k) {
    if (rows[k].source->manifold < 0) {
      layout.blockRows.push_back(k), addBlock(1);
      continue;
    }
    if (runAt[k] < 0) continue;  // a later row of a manifold: laid out with its first
    const auto [first, end] = runs[static_cast<size_t>(runAt[k])];
    const int count = end - first;
    for (int i = first; i < end; ++i) {
      layout.blockRows.push_back(byId[static_cast<size_t>(i)].second);
      if (count > kMaxBlockSize) addBlock(1);
    }
    if (count <= kMaxBlockSize) addBlock(count);
  }
}

// Lays the blocks out in groups that share no moving body, each group's blocks in their
// order, the groups in the order of their first blocks. A sweep of one group changes no
// velocity another group reads, so each group is swept until it converges on its own: a
// pile whose one corner will not settle keeps sweeping that corner's group, not every
// contact of the solve.
void layGroups(const std::vector<Row>& rows, const SolveBodies& bodies, SweepLayout& layout) {
  const int blockCount = static_cast<int>(layout.blocks.size());
  const auto firstRow = [&](int block) { return layout.blockRows[layout.blocks[block].first]; };
  DisjointSets sets(bodies.count());
  for (int k = 0; k < blockCount; ++k) {
    const Row& r = rows[firstRow(k)];  // a block's rows share their two bodies
    if (!r.a->isStatic && !r.b->isStatic) sets.join(bodies.a(firstRow(k)), bodies.b(firstRow(k)));
  }
  std::vector<int> groupOfRoot(static_cast<size_t>(bodies.count()), -1), groupOf(static_cast<size_t>(blockCount));
  int groupCount = 0;
  for (int k = 0; k < blockCount; ++k) {
    const int first = firstRow(k);
    const int moving = rows[first].a->isStatic ? bodies.b(first) : bodies.a(first);
    int& group = groupOfRoot[static_cast<size_t>(sets.root(moving))];
    if (group < 0) group = groupCount++;
    groupOf[k] = group;
  }
  Buckets groups(groupCount, groupOf);
  layout.groupStart = std::move(groups.start);
  layout.groupBlocks = std::move(groups.items);
}

// One row's friction impulse, clamped to the disk of its current normal impulse (no
// work for a frictionless row). Returns the change over the lighter body's mass (m/s).
// A row holding neither a normal nor a friction impulse has a disk of radius zero and
// stays as it is, whatever the velocities, so they are not read: a speculative contact
// still apart, an area's corner its block leaves unloaded. A fifth of a settling pile's
// friction rows are such (pile of 343, seed 1: 11.7 M of 59 M), and skipping them takes
// 8% of the instructions off the sweeps (callgrind, solver_bench's 343/1/150 replay).
double solveFrictionRow(Row& r, PairVelocities& v) {
  if (r.friction <= 0 || (r.normalImpulse == 0.0 && r.frictionImpulse.isZero(0.0))) return 0.0;
  const Eigen::Vector2d old = r.frictionImpulse;
  Eigen::Vector2d wanted = old - Eigen::Vector2d(r.tangentMass1 * velocityAlong(v, r.tangentAxis1), r.tangentMass2 * velocityAlong(v, r.tangentAxis2));
  const double limit = r.friction * r.normalImpulse;
  if (const double size2 = wanted.squaredNorm(); size2 > limit * limit) wanted *= limit / std::sqrt(size2);
  r.frictionImpulse = wanted;
  const Eigen::Vector2d d = wanted - old;
  applyAlong(v, r.tangentAxis1, d.x());
  applyAlong(v, r.tangentAxis2, d.y());
  return d.norm() * std::max(v.inverseMassA, v.inverseMassB);
}

// One row's normal impulse, as sequential impulses: the change that brings its normal
// velocity to its target, clamped so that the accumulated impulse stays >= 0.
double solveNormalRow(Row& r, PairVelocities& v) {
  const double vn = velocityAlong(v, r.normalAxis);
  const double old = r.normalImpulse;
  r.normalImpulse = std::max(0.0, old - r.normalMass * (vn - r.target));
  applyAlong(v, r.normalAxis, r.normalImpulse - old);
  return std::abs(r.normalImpulse - old) * std::max(v.inverseMassA, v.inverseMassB);
}

// A block's coupling matrix (constant through a solve: the poses do not move).
BlockMatrix couplingMatrix(const std::vector<Row>& rows, const int* block, int n) {
  BlockMatrix A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = coupling(rows[block[i]], rows[block[j]]);
  return A;
}

// A block's normal impulses solved together: the accumulated impulses x >= 0 with normal
// velocities >= their targets and complementary. Falls back to row by row when the
// small problem has no solution (round-off at a degenerate manifold).
double solveNormalBlock(std::vector<Row>& rows, const int* block, int n, const SmallLcp* lcp, PairVelocities& v) {
  if (n == 1) return solveNormalRow(rows[block[0]], v);
  const BlockMatrix& A = lcp->matrix();
  BlockVector b(n), old(n);
  for (int i = 0; i < n; ++i) {
    const Row& ri = rows[block[i]];
    old(i) = ri.normalImpulse;
    b(i) = velocityAlong(v, ri.normalAxis) - ri.target;
  }
  b -= A * old;
  const std::optional<BlockVector> x = lcp->solve(b);
  double change = 0.0;
  if (!x) {
    for (int i = 0; i < n; ++i) change = std::max(change, solveNormalRow(rows[block[i]], v));
    return change;
  }
  for (int i = 0; i < n; ++i) {
    Row& r = rows[block[i]];
    r.normalImpulse = (*x)(i);
    applyAlong(v, r.normalAxis, r.normalImpulse - old(i));
    change = std::max(change, std::abs(r.normalImpulse - old(i)) * std::max(v.inverseMassA, v.inverseMassB));
  }
  return change;
}

// Whether `holds` is true of every row of group g's blocks.
template <typename RowTest>
bool everyRowOf(const SweepLayout& layout, int g, RowTest holds) {
  for (int k = layout.groupStart[g]; k < layout.groupStart[g + 1]; ++k) {
    const SweepLayout::Block& block = layout.blocks[layout.groupBlocks[k]];
    for (int i = block.first; i < block.first + block.count; ++i)
      if (!holds(layout.blockRows[i])) return false;
  }
  return true;
}

// No contact of group g moves faster than kSettlingSpeed at its point.
bool settling(const std::vector<Row>& rows, const SweepLayout& layout, int g) {
  return everyRowOf(layout, g, [&](int row) { return relativeVelocity(rows[row]).squaredNorm() < kSettlingSpeed * kSettlingSpeed; });
}

// Every moving body of group g ended its last solve at rest, and every contact has
// friction. Such a group's sweeps stop at kMaxSolverIterations like a moving one's: what
// they leave, shock propagation settles, as it did the step before. Frictionless contacts
// are left out: columns of frictionless cups, nesting, reached the event bound in 122
// steps against 12 (seed 2) and 71 against 1 (seed 4) without their settling sweeps.
bool rested(const std::vector<Row>& rows, const SweepLayout& layout, int g) {
  const auto restedBody = [](const RigidBody* b) { return b->isStatic || b->restedAfterLastSolve; };
  return everyRowOf(layout, g, [&](int row) { return rows[row].friction > 0 && restedBody(rows[row].a) && restedBody(rows[row].b); });
}

// Sweeps over group g's blocks until no impulse changes by kSolverVelocityTolerance or
// its limit is reached: kMaxSolverIterations, or maxSweeps if fewer or if the group is
// settling there and did not rest after its last solve (settings.h); a settling group's
// sweeps also stop once they stall (SettlingProgress). Each sweep solves
// each block's friction rows, then its normal impulses. Sweeps run in the given order
// (bottom-up: the first carries a stack's weight down in one pass), then backwards, and so
// on (symmetric Gauss-Seidel): a load that must shift across a tall structure travels both
// ways. Every sweep bottom-up, 600 sweeps a step left the 40-high pyramid leaning out of
// its plane by 5 cm in 3 s; alternating, 2.4 mm.
SolveStats sweepGroup(std::vector<Row>& rows, const SweepLayout& layout, int g, int maxSweeps) {
  SolveStats stats;
  SettlingProgress progress;
  const int* groupBlocks = layout.groupBlocks.data() + layout.groupStart[g];
  const int blockCount = layout.groupStart[g + 1] - layout.groupStart[g];
  for (int limit = std::min(maxSweeps, kMaxSolverIterations);;) {
    if (stats.iterations == limit && limit < maxSweeps && settling(rows, layout, g) && !rested(rows, layout, g))
      limit = maxSweeps;
    if (stats.iterations >= limit) break;
    if (limit > kMaxSolverIterations && progress.stalled(stats.iterations)) break;
    ++stats.iterations;
    double largestChange = 0.0;  // m/s: impulse change over the lighter body's mass
    const bool backwards = stats.iterations % 2 == 0;  // the first sweep is forwards
    for (int n = 0; n < blockCount; ++n) {
      const SweepLayout::Block& block = layout.blocks[groupBlocks[backwards ? blockCount - 1 - n : n]];
      const int* blockRows = layout.blockRows.data() + block.first;
      stats.rowSolves += block.count;
      PairVelocities v = velocitiesOf(rows[blockRows[0]]);
      for (int i = 0; i < block.count; ++i) largestChange = std::max(largestChange, solveFrictionRow(rows[blockRows[i]], v));
      largestChange = std::max(largestChange, solveNormalBlock(rows, blockRows, block.count, block.coupling, v));
      storeVelocities(v, rows[blockRows[0]]);
    }
    if (largestChange < kSolverVelocityTolerance) {
      stats.converged = true;
      break;
    }
    progress.note(largestChange);
  }
  return stats;
}
}  // namespace

ContactSweeps::ContactSweeps(const std::vector<Row>& rows) : bodies_(rows) {
  layBlocks(rows, layout_);
  const auto coupled = [](const SweepLayout::Block& b) { return b.count > 1; };
  const auto several = std::count_if(layout_.blocks.begin(), layout_.blocks.end(), coupled);
  couplings_.reserve(static_cast<size_t>(several));  // never reallocated: the layout points into it
  for (SweepLayout::Block& block : layout_.blocks)
    if (coupled(block))
      block.coupling = &couplings_.emplace_back(couplingMatrix(rows, &layout_.blockRows[block.first], block.count));
  layGroups(rows, bodies_, layout_);
  groupOrder_.resize(layout_.groupCount());
  std::iota(groupOrder_.begin(), groupOrder_.end(), 0);
  if (shared()) {  // largest first, so that the two threads finish together
    std::vector<int> rowCount(groupOrder_.size(), 0);  // each group's
    for (int g = 0; g < layout_.groupCount(); ++g)
      for (int k = layout_.groupStart[g]; k < layout_.groupStart[g + 1]; ++k)
        rowCount[g] += layout_.blocks[layout_.groupBlocks[k]].count;
    std::stable_sort(groupOrder_.begin(), groupOrder_.end(), [&](int g, int h) { return rowCount[g] > rowCount[h]; });
  }
}

bool ContactSweeps::shared() const { return static_cast<int>(layout_.blockRows.size()) >= kSharedSweepRows; }

SolveStats ContactSweeps::run(std::vector<Row>& rows, int maxSweeps) const {
  // Groups share no moving body and no row, so each sweeps on its own data: on two
  // threads the impulses are the same, to the bit, as on one.
  std::vector<SolveStats> swept(layout_.groupCount());
  forEachPiece(layout_.groupCount(), shared(), [&](int k) {
    const int g = groupOrder_[k];
    swept[g] = sweepGroup(rows, layout_, g, maxSweeps);
  });
  SolveStats stats;
  stats.converged = true;
  for (const SolveStats& group : swept) {
    stats.iterations = std::max(stats.iterations, group.iterations);
    stats.converged = stats.converged && group.converged;
    stats.rowSolves += group.rowSolves;
  }
  return stats;
}

std::vector<std::vector<int>> ContactSweeps::groupRows() const {
  std::vector<std::vector<int>> rows;
  for (int g = 0; g < layout_.groupCount(); ++g) {
    std::vector<int>& mine = rows.emplace_back();
    everyRowOf(layout_, g, [&](int row) {
      mine.push_back(row);
      return true;
    });
    std::sort(mine.begin(), mine.end());
  }
  return rows;
}

}  // namespace polysim::dynamics::solver
