#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "dynamics/disjoint_sets.h"
#include "dynamics/settings.h"
#include "dynamics/small_lcp.h"

namespace polysim::dynamics {
namespace {

// A body as the sweeps see it, taken once per solve (a solve changes velocities, never
// poses): its world inverse inertia and centre of mass. Recomputing them from the
// quaternion at every impulse was most of a resting stack's solve time.
struct BodyFrame {
  Eigen::Matrix3d inverseInertia = Eigen::Matrix3d::Zero();  // 1 / (kg m^2), world axes
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();    // m, world
};

// A contact prepared for the sweeps: lever arms, effective masses, target, impulses.
struct Row {
  ContactPoint* source;
  RigidBody* a;
  RigidBody* b;
  const BodyFrame* frameA;
  const BodyFrame* frameB;
  Eigen::Vector3d point, normal, tangent1, tangent2;
  Eigen::Vector3d armA, armB;                                 // m, from each centre of mass to the point
  double normalMass = 0, tangentMass1 = 0, tangentMass2 = 0;  // kg: 1 / (J M^-1 J^T)
  double target = 0;                                          // m/s, least normal velocity
  double separation = 0;                                      // m, as detected
  double restitution = 0;                                     // 0 unless the contact bounces
  double friction = 0;
  double normalImpulse = 0;                                   // accumulated, N s
  Eigen::Vector2d frictionImpulse = Eigen::Vector2d::Zero();  // accumulated, N s
};

// A body's velocities, or its push velocities (split impulses): the pairs the sweeps change.
using Velocity = Eigen::Vector3d RigidBody::*;
struct Velocities {
  Velocity linear, angular;
};
constexpr Velocities kMomentum{&RigidBody::velocity, &RigidBody::angularVelocity};
constexpr Velocities kPush{&RigidBody::pushVelocity, &RigidBody::pushAngularVelocity};

// The velocity of a's material point at the contact relative to b's.
Eigen::Vector3d relativeVelocity(const Row& r, Velocities v = kMomentum) {
  return (r.a->*v.linear + (r.a->*v.angular).cross(r.armA)) - (r.b->*v.linear + (r.b->*v.angular).cross(r.armB));
}

// 1 / (n . (M_a^-1 + M_b^-1) n) for a unit direction n at the contact point.
double effectiveMass(const Row& r, const Eigen::Vector3d& n) {
  double k = r.a->inverseMass + r.b->inverseMass;
  if (!r.a->isStatic) k += n.dot((r.frameA->inverseInertia * r.armA.cross(n)).cross(r.armA));
  if (!r.b->isStatic) k += n.dot((r.frameB->inverseInertia * r.armB.cross(n)).cross(r.armB));
  return k > 0 ? 1.0 / k : 0.0;
}

// How much a unit impulse along row j's normal at its point changes row i's normal
// velocity (both rows between the same two bodies): the block's coupling matrix entry.
double coupling(const Row& i, const Row& j) {
  double k = (i.a->inverseMass + i.b->inverseMass) * i.normal.dot(j.normal);
  if (!i.a->isStatic) k += i.armA.cross(i.normal).dot(i.frameA->inverseInertia * j.armA.cross(j.normal));
  if (!i.b->isStatic) k += i.armB.cross(i.normal).dot(i.frameB->inverseInertia * j.armB.cross(j.normal));
  return k;
}

// The second derivative of the row's gap (m/s^2) were both bodies to keep their velocities
// (g = n . (x_a - x_b) for the material points x_a, x_b at the contact, with n turning
// as the face it belongs to): the turn of the normal against the relative velocity, and
// the centripetal accelerations of the two material points. A gap curving closed over
// the step is what a velocity target of -gap / dt misses: a domino's edge sliding down
// its neighbour's face, which turns towards it at 2 rad/s, closes 0.4 mm more in a step
// of 1/60 s, four tolerances; each time the step backed up to it.
double gapCurvature(const Row& r) {
  auto centripetal = [](const RigidBody* body, const Eigen::Vector3d& arm) -> Eigen::Vector3d {
    if (body->isStatic) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d& w = body->angularVelocity;
    return w.cross(w.cross(arm));
  };
  const double withA = r.source->normalTurnWithA;
  const Eigen::Vector3d normalTurn = (withA * r.a->angularVelocity + (1 - withA) * r.b->angularVelocity).cross(r.normal);
  return r.normal.dot(centripetal(r.a, r.armA) - centripetal(r.b, r.armB)) + 2.0 * normalTurn.dot(relativeVelocity(r));
}

// J on a at the point and -J on b, as RigidBody::applyImpulse does it (the same
// operations, so the same round-off) with the solve's frames.
void applyPair(Row& r, const Eigen::Vector3d& J, Velocities v = kMomentum) {
  if (!r.a->isStatic) {
    r.a->*v.linear += r.a->inverseMass * J;
    r.a->*v.angular += r.frameA->inverseInertia * r.armA.cross(J);
  }
  if (!r.b->isStatic) {
    r.b->*v.linear += r.b->inverseMass * -J;
    r.b->*v.angular += r.frameB->inverseInertia * r.armB.cross(-J);
  }
}

// The bodies the rows touch, each once (static ones excluded).
std::vector<RigidBody*> movingBodies(const std::vector<Row>& rows) {
  std::vector<RigidBody*> bodies;
  std::unordered_set<const RigidBody*> seen;
  for (const Row& r : rows)
    for (RigidBody* b : {r.a, r.b})
      if (!b->isStatic && seen.insert(b).second) bodies.push_back(b);
  return bodies;
}

double kineticEnergy(const std::vector<RigidBody*>& bodies) {
  double e = 0.0;
  for (const RigidBody* b : bodies) e += b->kineticEnergy();
  return e;
}

// The rows of each contact, in the order their first rows come: an area's corners or a
// line's ends are one block; a point, or a contact larger than kMaxBlockSize, one per row.
std::vector<std::vector<int>> blocksOf(const std::vector<Row>& rows) {
  std::vector<std::vector<int>> blocks;
  std::unordered_map<int, size_t> blockOf;  // manifold id -> its block
  for (size_t k = 0; k < rows.size(); ++k) {
    const int id = rows[k].source->manifold;
    const auto [at, fresh] = blockOf.try_emplace(id, blocks.size());
    if (id < 0 || fresh) blocks.push_back({static_cast<int>(k)});
    else blocks[at->second].push_back(static_cast<int>(k));
  }
  std::vector<std::vector<int>> split;
  for (std::vector<int>& b : blocks) {
    if (static_cast<int>(b.size()) <= kMaxBlockSize) split.push_back(std::move(b));
    else for (int k : b) split.push_back({k});
  }
  return split;
}

// The blocks in groups that share no moving body, each group's blocks in their order.
// A sweep of one group changes no velocity another group reads, so each group is swept
// until it converges on its own: a pile whose one corner will not settle keeps sweeping
// that corner's group, not every contact of the solve.
std::vector<std::vector<int>> groupsOf(const std::vector<Row>& rows, const std::vector<std::vector<int>>& blocks, int bodyCount) {
  DisjointSets sets(bodyCount);
  for (const std::vector<int>& block : blocks) {
    const Row& r = rows[block.front()];  // a block's rows share their two bodies
    if (!r.a->isStatic && !r.b->isStatic) sets.join(r.source->a, r.source->b);
  }
  std::vector<std::vector<int>> groups;
  std::unordered_map<int, size_t> groupOfRoot;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const Row& r = rows[blocks[k].front()];
    const int moving = r.a->isStatic ? r.source->b : r.source->a;
    const auto [at, fresh] = groupOfRoot.try_emplace(sets.root(moving), groups.size());
    if (fresh) groups.emplace_back();
    groups[at->second].push_back(static_cast<int>(k));
  }
  return groups;
}

// One row's friction impulse, clamped to the disk of its current normal impulse (no
// work for a frictionless row). Returns the change over the lighter body's mass (m/s).
double solveFrictionRow(Row& r) {
  if (r.friction <= 0) return 0.0;
  const Eigen::Vector3d v = relativeVelocity(r);
  const Eigen::Vector2d old = r.frictionImpulse;
  Eigen::Vector2d wanted = old - Eigen::Vector2d(r.tangentMass1 * r.tangent1.dot(v), r.tangentMass2 * r.tangent2.dot(v));
  const double limit = r.friction * r.normalImpulse;
  if (wanted.norm() > limit) wanted *= limit / wanted.norm();
  r.frictionImpulse = wanted;
  const Eigen::Vector2d d = wanted - old;
  applyPair(r, d.x() * r.tangent1 + d.y() * r.tangent2);
  return d.norm() * std::max(r.a->inverseMass, r.b->inverseMass);
}

// One row's normal impulse, as sequential impulses: the change that brings its normal
// velocity to its target, clamped so that the accumulated impulse stays >= 0.
double solveNormalRow(Row& r) {
  const double vn = r.normal.dot(relativeVelocity(r));
  const double old = r.normalImpulse;
  r.normalImpulse = std::max(0.0, old - r.normalMass * (vn - r.target));
  applyPair(r, (r.normalImpulse - old) * r.normal);
  return std::abs(r.normalImpulse - old) * std::max(r.a->inverseMass, r.b->inverseMass);
}

// A block's normal impulses solved together: the accumulated impulses x >= 0 with normal
// velocities >= their targets and complementary. Falls back to row by row when the
// small problem has no solution (round-off at a degenerate manifold).
// A block's coupling matrix (constant through a solve: the poses do not move).
BlockMatrix couplingMatrix(const std::vector<Row>& rows, const std::vector<int>& block) {
  const int n = static_cast<int>(block.size());
  BlockMatrix A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = coupling(rows[block[i]], rows[block[j]]);
  return A;
}

double solveNormalBlock(std::vector<Row>& rows, const std::vector<int>& block, const SmallLcp& lcp) {
  const int n = static_cast<int>(block.size());
  if (n == 1) return solveNormalRow(rows[block[0]]);
  const BlockMatrix& A = lcp.matrix();
  BlockVector b(n), old(n);
  for (int i = 0; i < n; ++i) {
    const Row& ri = rows[block[i]];
    old(i) = ri.normalImpulse;
    b(i) = ri.normal.dot(relativeVelocity(ri)) - ri.target;
  }
  b -= A * old;
  const std::optional<BlockVector> x = lcp.solve(b);
  double change = 0.0;
  if (!x) {
    for (int k : block) change = std::max(change, solveNormalRow(rows[k]));
    return change;
  }
  for (int i = 0; i < n; ++i) {
    Row& r = rows[block[i]];
    r.normalImpulse = (*x)(i);
    applyPair(r, (r.normalImpulse - old(i)) * r.normal);
    change = std::max(change, std::abs(r.normalImpulse - old(i)) * std::max(r.a->inverseMass, r.b->inverseMass));
  }
  return change;
}

// Sweeps over one group's blocks until no impulse changes by kSolverVelocityTolerance or
// kMaxSolverIterations are made: each block's friction rows, then its normal impulses.
SolveStats sweepGroup(std::vector<Row>& rows, const std::vector<std::vector<int>>& blocks,
                      const std::vector<SmallLcp>& couplings, const std::vector<int>& group) {
  SolveStats stats;
  while (stats.iterations < kMaxSolverIterations) {
    ++stats.iterations;
    double largestChange = 0.0;  // m/s: impulse change over the lighter body's mass
    for (int k : group) {
      stats.rowSolves += static_cast<long>(blocks[k].size());
      for (int row : blocks[k]) largestChange = std::max(largestChange, solveFrictionRow(rows[row]));
      largestChange = std::max(largestChange, solveNormalBlock(rows, blocks[k], couplings[k]));
    }
    if (largestChange < kSolverVelocityTolerance) {
      stats.converged = true;
      break;
    }
  }
  return stats;
}

// Poisson restitution: each bouncing contact pushes apart again with e times the impulse
// that stopped it. With friction that rebound could end with more kinetic energy than
// the bodies had before the solve; energy is quadratic in the rebound's scale alpha, so
// alpha is cut to the largest value in [0, 1] that keeps it at most `energyBefore`.
void applyRestitution(std::vector<Row>& rows, double energyBefore) {
  if (std::none_of(rows.begin(), rows.end(), [](const Row& r) { return r.restitution > 0; })) return;
  const std::vector<RigidBody*> bodies = movingBodies(rows);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> compressed, delta;
  for (const RigidBody* b : bodies) compressed.emplace_back(b->velocity, b->angularVelocity);
  const double e0 = kineticEnergy(bodies);
  for (Row& r : rows)
    if (r.restitution > 0) applyPair(r, r.restitution * r.normalImpulse * r.normal);
  const double e1 = kineticEnergy(bodies);
  for (size_t i = 0; i < bodies.size(); ++i)
    delta.emplace_back(bodies[i]->velocity - compressed[i].first, bodies[i]->angularVelocity - compressed[i].second);
  if (e1 <= energyBefore) return;
  auto setScale = [&](double alpha) {
    for (size_t i = 0; i < bodies.size(); ++i) {
      bodies[i]->velocity = compressed[i].first + alpha * delta[i].first;
      bodies[i]->angularVelocity = compressed[i].second + alpha * delta[i].second;
    }
  };
  setScale(-1.0);
  const double eMinus = kineticEnergy(bodies);
  const double a = 0.5 * (e1 + eMinus) - e0, b = 0.5 * (e1 - eMinus);  // E(alpha) = e0 + b alpha + a alpha^2
  const double c = e0 - energyBefore;                                     // <= 0: compression dissipates
  const double alpha = a > 0 ? (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a) : 0.0;
  setScale(std::clamp(alpha, 0.0, 1.0));
}

// Split impulses (Catto's pseudo velocities, as in Box2D v2 and Bullet): sequential
// impulses on the push velocities alone, targets from the overlap beyond the allowed one.
void solvePushes(std::vector<Row>& rows, double allowedOverlap, double dt) {
  for (RigidBody* b : movingBodies(rows)) b->pushVelocity.setZero(), b->pushAngularVelocity.setZero();
  std::vector<double> target(rows.size()), impulse(rows.size(), 0.0);
  bool any = false;
  for (size_t k = 0; k < rows.size(); ++k) {
    target[k] = std::max(0.0, -rows[k].separation - allowedOverlap) / dt;
    any = any || target[k] > 0;
  }
  if (!any) return;
  for (int sweep = 0; sweep < kMaxSolverIterations; ++sweep) {
    double largestChange = 0.0;
    for (size_t k = 0; k < rows.size(); ++k) {
      Row& r = rows[k];
      const double vn = r.normal.dot(relativeVelocity(r, kPush));
      const double old = impulse[k];
      impulse[k] = std::max(0.0, old - r.normalMass * (vn - target[k]));
      applyPair(r, (impulse[k] - old) * r.normal, kPush);
      largestChange = std::max(largestChange, std::abs(impulse[k] - old) * std::max(r.a->inverseMass, r.b->inverseMass));
    }
    if (largestChange < kPushVelocityTolerance) break;
  }
}

}  // namespace

SolveStats solveContacts(std::vector<RigidBody>& bodies, std::vector<ContactPoint>& contacts, double dt,
                         double allowedOverlap) {
  std::vector<Row> rows;
  rows.reserve(contacts.size());
  std::vector<BodyFrame> frames;
  frames.reserve(2 * contacts.size());  // never reallocated: rows point into it
  std::unordered_map<int, const BodyFrame*> frameOf;
  auto frame = [&](int i) {
    const auto [at, fresh] = frameOf.try_emplace(i, nullptr);
    if (fresh) at->second = &frames.emplace_back(BodyFrame{bodies[i].inverseInertiaWorld(), bodies[i].centerOfMass()});
    return at->second;
  };
  for (ContactPoint& c : contacts) {
    Row r;
    r.source = &c;
    r.a = &bodies[c.a];
    r.b = &bodies[c.b];
    if (r.a->isStatic && r.b->isStatic) continue;  // static pairs cost nothing
    r.frameA = frame(c.a);
    r.frameB = frame(c.b);
    r.armA = c.point - r.frameA->centerOfMass;
    r.armB = c.point - r.frameB->centerOfMass;
    r.point = c.point;
    r.normal = c.normal;
    r.friction = c.friction;
    r.separation = c.separation;
    r.normalMass = effectiveMass(r, r.normal);
    const double approach = r.normal.dot(relativeVelocity(r));
    if (approach < -kBounceThreshold) r.restitution = c.restitution;
    // A contact still apart may close its gap within the step (a speculative target),
    // but a bouncing one is stopped outright: restitution returns e times the impulse
    // that stopped it, and closing the gap first would take gap / dt off the rebound
    // (0.6% of the speed per bounce at dt 1/240, measured on bounce_e09).
    r.target = r.restitution > 0 ? 0.0 : -std::max(c.separation, 0.0) / dt;
    if (r.restitution == 0) r.target -= 0.5 * std::min(0.0, gapCurvature(r)) * dt;
    r.tangent1 = r.normal.unitOrthogonal();
    r.tangent2 = r.normal.cross(r.tangent1);
    if (r.friction > 0) {
      r.tangentMass1 = effectiveMass(r, r.tangent1);
      r.tangentMass2 = effectiveMass(r, r.tangent2);
    }
    rows.push_back(r);
  }

  const double energyBefore = kineticEnergy(movingBodies(rows));
  for (Row& r : rows) {  // warm start
    r.normalImpulse = std::max(0.0, r.source->normalImpulse);
    if (r.friction > 0) {
      r.frictionImpulse = r.source->frictionImpulse;
      const double limit = r.friction * r.normalImpulse;
      if (r.frictionImpulse.norm() > limit) r.frictionImpulse *= limit / r.frictionImpulse.norm();
    }
    applyPair(r, r.normalImpulse * r.normal + r.frictionImpulse.x() * r.tangent1 + r.frictionImpulse.y() * r.tangent2);
  }
  const std::vector<std::vector<int>> blocks = blocksOf(rows);
  std::vector<SmallLcp> couplings;  // per block, its coupling matrix: constant through the sweeps
  couplings.reserve(blocks.size());
  for (const std::vector<int>& block : blocks) couplings.emplace_back(block.size() > 1 ? couplingMatrix(rows, block) : BlockMatrix());
  SolveStats stats;
  stats.converged = true;
  for (const std::vector<int>& group : groupsOf(rows, blocks, static_cast<int>(bodies.size()))) {
    const SolveStats swept = sweepGroup(rows, blocks, couplings, group);
    stats.iterations = std::max(stats.iterations, swept.iterations);
    stats.converged = stats.converged && swept.converged;
    stats.rowSolves += swept.rowSolves;
  }
  applyRestitution(rows, energyBefore);
  solvePushes(rows, allowedOverlap, dt);
  for (Row& r : rows) {
    r.source->normalImpulse = r.normalImpulse;
    r.source->frictionImpulse = r.frictionImpulse;
  }
  return stats;
}

}  // namespace polysim::dynamics
