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

// A solve's blocks as first laid out: each block's rows (the solve's row numbers), in the
// order the blocks' first rows come.
struct Blocks {
  std::vector<int> rows;                   // block after block
  std::vector<std::pair<int, int>> spans;  // each block's (first, count) in `rows`
  int count() const { return static_cast<int>(spans.size()); }
  int firstRow(int block) const { return rows[static_cast<size_t>(spans[static_cast<size_t>(block)].first)]; }
};

// The rows of each contact (sharing a manifold id, in the rows' order) are a block, an
// area's corners or a line's ends; a point, or a contact larger than kMaxBlockSize, is a
// block of one row. A contact's rows need not be consecutive: the rows come in the order
// the sweeps take them (bottom-up), corners of different contacts interleaved.
Blocks layBlocks(const std::vector<Row>& rows) {
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
  Blocks blocks;
  blocks.rows.reserve(static_cast<size_t>(n));
  const auto addBlock = [&](int count) { blocks.spans.emplace_back(static_cast<int>(blocks.rows.size()) - count, count); };
  for (int k = 0; k < n; ++k) {
    if (rows[k].source->manifold < 0) {
      blocks.rows.push_back(k), addBlock(1);
      continue;
    }
    if (runAt[k] < 0) continue;  // a later row of a manifold: laid out with its first
    const auto [first, end] = runs[static_cast<size_t>(runAt[k])];
    const int count = end - first;
    for (int i = first; i < end; ++i) {
      blocks.rows.push_back(byId[static_cast<size_t>(i)].second);
      if (count > kMaxBlockSize) addBlock(1);
    }
    if (count <= kMaxBlockSize) addBlock(count);
  }
  return blocks;
}

// The blocks in groups that share no moving body, each group's blocks in their order,
// the groups in the order of their first blocks. A sweep of one group changes no
// velocity another group reads, so each group is swept until it converges on its own: a
// pile whose one corner will not settle keeps sweeping that corner's group, not every
// contact of the solve.
Buckets groupBlocks(const std::vector<Row>& rows, const SolveBodies& bodies, const Blocks& blocks) {
  DisjointSets sets(bodies.count());
  for (int k = 0; k < blocks.count(); ++k) {
    const int first = blocks.firstRow(k);
    const Row& r = rows[first];  // a block's rows share their two bodies
    if (!r.a->isStatic && !r.b->isStatic) sets.join(bodies.a(first), bodies.b(first));
  }
  std::vector<int> groupOfRoot(static_cast<size_t>(bodies.count()), -1), groupOf(static_cast<size_t>(blocks.count()));
  int groupCount = 0;
  for (int k = 0; k < blocks.count(); ++k) {
    const int first = blocks.firstRow(k);
    const int moving = rows[first].a->isStatic ? bodies.b(first) : bodies.a(first);
    int& group = groupOfRoot[static_cast<size_t>(sets.root(moving))];
    if (group < 0) group = groupCount++;
    groupOf[k] = group;
  }
  return Buckets(groupCount, groupOf);
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
double solveNormalBlock(Row* block, int n, const SmallLcp* lcp, PairVelocities& v) {
  if (n == 1) return solveNormalRow(block[0], v);
  const BlockMatrix& A = lcp->matrix();
  BlockVector b(n), old(n);
  for (int i = 0; i < n; ++i) {
    old(i) = block[i].normalImpulse;
    b(i) = velocityAlong(v, block[i].normalAxis) - block[i].target;
  }
  b -= A * old;
  const std::optional<BlockVector> x = lcp->solve(b);
  double change = 0.0;
  if (!x) {
    for (int i = 0; i < n; ++i) change = std::max(change, solveNormalRow(block[i], v));
    return change;
  }
  for (int i = 0; i < n; ++i) {
    Row& r = block[i];
    r.normalImpulse = (*x)(i);
    applyAlong(v, r.normalAxis, r.normalImpulse - old(i));
    change = std::max(change, std::abs(r.normalImpulse - old(i)) * std::max(v.inverseMassA, v.inverseMassB));
  }
  return change;
}

// No contact of a group (its rows [first, last)) moves faster than kSettlingSpeed at its point.
bool settling(const Row* first, const Row* last) {
  return std::all_of(first, last, [](const Row& r) { return relativeVelocity(r).squaredNorm() < kSettlingSpeed * kSettlingSpeed; });
}

// Every moving body of a group (its rows [first, last)) ended its last solve at rest, and
// every contact has friction. Such a group's sweeps stop at kMaxSolverIterations like a
// moving one's: what they leave, shock propagation settles, as it did the step before.
// Frictionless contacts are left out: columns of frictionless cups, nesting, reached the
// event bound in 122 steps against 12 (seed 2) and 71 against 1 (seed 4) without their
// settling sweeps.
bool rested(const Row* first, const Row* last) {
  const auto restedBody = [](const RigidBody* b) { return b->isStatic || b->restedAfterLastSolve; };
  return std::all_of(first, last, [&](const Row& r) { return r.friction > 0 && restedBody(r.a) && restedBody(r.b); });
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
SolveStats sweepGroup(std::vector<Row>& swept, const SweepLayout& layout, int g, int maxSweeps) {
  SolveStats stats;
  SettlingProgress progress;
  const SweepLayout::Block* blocks = layout.blocks.data() + layout.groupStart[g];
  const int blockCount = layout.groupStart[g + 1] - layout.groupStart[g];
  const auto [firstRow, endRow] = layout.rowSpan(g);
  Row* const first = swept.data() + firstRow;
  Row* const last = swept.data() + endRow;
  for (int limit = std::min(maxSweeps, kMaxSolverIterations);;) {
    if (stats.iterations == limit && limit < maxSweeps && settling(first, last) && !rested(first, last))
      limit = maxSweeps;
    if (stats.iterations >= limit) break;
    if (limit > kMaxSolverIterations && progress.stalled(stats.iterations)) break;
    ++stats.iterations;
    double largestChange = 0.0;  // m/s: impulse change over the lighter body's mass
    const bool backwards = stats.iterations % 2 == 0;  // the first sweep is forwards
    for (int n = 0; n < blockCount; ++n) {
      const SweepLayout::Block& block = blocks[backwards ? blockCount - 1 - n : n];
      Row* const rows = swept.data() + block.first;
      stats.rowSolves += block.count;
      PairVelocities v = velocitiesOf(rows[0]);
      for (int i = 0; i < block.count; ++i) largestChange = std::max(largestChange, solveFrictionRow(rows[i], v));
      largestChange = std::max(largestChange, solveNormalBlock(rows, block.count, block.coupling, v));
      storeVelocities(v, rows[0]);
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
  const Blocks blocks = layBlocks(rows);
  const Buckets groups = groupBlocks(rows, bodies_, blocks);
  const auto coupled = [](const std::pair<int, int>& span) { return span.second > 1; };  // (first, count)
  couplings_.reserve(static_cast<size_t>(std::count_if(blocks.spans.begin(), blocks.spans.end(), coupled)));
  // Group after group, block after block, row after row: each group's rows are one
  // stretch of the sweeps' copy. Never reallocated: the layout points into couplings_.
  layout_.rowOf.reserve(rows.size());
  layout_.blocks.reserve(static_cast<size_t>(blocks.count()));
  for (int g = 0; g < groups.bucketCount(); ++g) {
    layout_.groupStart.push_back(static_cast<int>(layout_.blocks.size()));
    for (const int* k = groups.begin(g); k != groups.end(g); ++k) {
      const auto [first, count] = blocks.spans[static_cast<size_t>(*k)];
      const int* blockRows = blocks.rows.data() + first;
      SweepLayout::Block& block = layout_.blocks.emplace_back();
      block.first = static_cast<int>(layout_.rowOf.size());
      block.count = count;
      if (count > 1) block.coupling = &couplings_.emplace_back(couplingMatrix(rows, blockRows, count));
      layout_.rowOf.insert(layout_.rowOf.end(), blockRows, blockRows + count);
    }
  }
  layout_.groupStart.push_back(static_cast<int>(layout_.blocks.size()));
  groupOrder_.resize(layout_.groupCount());
  std::iota(groupOrder_.begin(), groupOrder_.end(), 0);
  if (shared()) {  // largest first, so that the two threads finish together
    const auto rowCount = [this](int g) { return layout_.rowSpan(g).second - layout_.rowSpan(g).first; };
    std::stable_sort(groupOrder_.begin(), groupOrder_.end(), [&](int g, int h) { return rowCount(g) > rowCount(h); });
  }
}

bool ContactSweeps::shared() const { return static_cast<int>(layout_.rowOf.size()) >= kSharedSweepRows; }

SolveStats ContactSweeps::run(std::vector<Row>& rows, int maxSweeps) const {
  // The rows copied in the layout's order, so that a sweep reads its group's rows one
  // after another, not scattered through the solve's: solver_bench's replays, four rounds
  // alternated, took 2 to 19% less CPU (343 / 1 / 150) and 0 to 12% (1000 / 1 / 90), the
  // same impulses to the bit. Groups share no moving body and no row, so each sweeps on
  // its own stretch: on two threads the impulses are the same, to the bit, as on one.
  // The copy is kept from run to run on each thread: made afresh, a pile's megabytes were
  // mapped and faulted in at every solve, which doubled the run's system time. (A
  // thread_local is named afresh on each thread: the helper is handed this one's.)
  thread_local std::vector<Row> kept;
  std::vector<Row>& swept = kept;
  swept.clear();
  for (int k : layout_.rowOf) swept.push_back(rows[static_cast<size_t>(k)]);
  std::vector<SolveStats> stats(layout_.groupCount());
  forEachPiece(layout_.groupCount(), shared(), [&](int k) {
    const int g = groupOrder_[k];
    stats[g] = sweepGroup(swept, layout_, g, maxSweeps);
  });
  for (size_t i = 0; i < swept.size(); ++i) {
    Row& r = rows[static_cast<size_t>(layout_.rowOf[i])];
    r.normalImpulse = swept[i].normalImpulse;
    r.frictionImpulse = swept[i].frictionImpulse;
  }
  SolveStats all;
  all.converged = true;
  for (const SolveStats& group : stats) {
    all.iterations = std::max(all.iterations, group.iterations);
    all.converged = all.converged && group.converged;
    all.rowSolves += group.rowSolves;
  }
  return all;
}

std::vector<std::vector<int>> ContactSweeps::groupRows() const {
  std::vector<std::vector<int>> rows;
  for (int g = 0; g < layout_.groupCount(); ++g) {
    const auto [first, end] = layout_.rowSpan(g);
    std::vector<int>& mine = rows.emplace_back(layout_.rowOf.begin() + first, layout_.rowOf.begin() + end);
    std::sort(mine.begin(), mine.end());
  }
  return rows;
}

}  // namespace polysim::dynamics::solver
