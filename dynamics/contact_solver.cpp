#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "dynamics/contact_row.h"
#include "dynamics/contact_sweeps.h"
#include "dynamics/settings.h"
#include "dynamics/shock_propagation.h"

namespace polysim::dynamics {
namespace {

using namespace solver;

// The moving bodies' velocities, to go back to.
class SavedVelocities {
 public:
  explicit SavedVelocities(std::vector<RigidBody*> bodies) : bodies_(std::move(bodies)) {
    for (const RigidBody* b : bodies_) saved_.emplace_back(b->velocity, b->angularVelocity);
  }
  void restore() const {
    for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i]->velocity = saved_[i].first, bodies_[i]->angularVelocity = saved_[i].second;
  }

 private:
  std::vector<RigidBody*> bodies_;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> saved_;
};

// Poisson restitution: each bouncing contact pushes apart again with e times the impulse
// that stopped it. With friction that rebound could end with more kinetic energy than
// the bodies had before the solve; energy is quadratic in the rebound's scale alpha, so
// alpha is cut to the largest value in [0, 1] that keeps it at most `energyBefore`.
void applyRestitution(std::vector<Row>& rows, const std::vector<RigidBody*>& bodies, double energyBefore) {
  if (std::none_of(rows.begin(), rows.end(), [](const Row& r) { return r.restitution > 0; })) return;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> compressed, delta;
  for (const RigidBody* b : bodies) compressed.emplace_back(b->velocity, b->angularVelocity);
  const double e0 = kineticEnergy(bodies);
  for (Row& r : rows)
    if (r.restitution > 0) applyAlong(r, r.normalAxis, r.restitution * r.normalImpulse);
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

// The rows a push can reach: those of the sweeps' groups (linked through moving bodies)
// that hold a row with a target above zero, in increasing order. Every other row's push
// impulse stays zero (no push velocity, no target), so the push sweeps skip them: the
// same result, without sweeping a whole pile for the one corner of it that overlaps too
// deep.
std::vector<int> rowsReachedByPushes(const ContactSweeps& sweeps, const std::vector<double>& target) {
  std::vector<int> reached;
  for (const std::vector<int>& group : sweeps.groupRows())
    if (std::any_of(group.begin(), group.end(), [&target](int k) { return target[k] > 0; }))
      reached.insert(reached.end(), group.begin(), group.end());
  std::sort(reached.begin(), reached.end());
  return reached;
}

// A row as the push sweeps see it: its accumulated push impulse (N s) and its target
// (m/s, the overlap beyond the allowed one over the time to the next detection).
struct PushRow {
  Row* row;
  double* impulse;
  double target;
};

// Sequential impulses on the push velocities alone, in the given order, until no sweep
// changes a push velocity by kPushVelocityTolerance or kMaxSolverIterations sweeps; true
// when converged. Most rows swept push nothing (their group is swept for an overlap too
// deep elsewhere in it), and a row whose push impulse does not change applies nothing:
// 17% of the push sweeps' instructions (callgrind, solver_bench's 343/1/150 replay), the
// same velocities.
bool sweepPushes(const std::vector<PushRow>& pushRows) {
  for (int sweep = 0; sweep < kMaxSolverIterations; ++sweep) {
    double largestChange = 0.0;
    for (const PushRow& p : pushRows) {
      Row& r = *p.row;
      const double vn = velocityAlong(r, r.normalAxis, kPush);
      const double old = *p.impulse;
      *p.impulse = std::max(0.0, old - r.normalMass * (vn - p.target));
      const double change = *p.impulse - old;
      if (change != 0.0) applyAlong(r, r.normalAxis, change, kPush);
      largestChange = std::max(largestChange, std::abs(change) * std::max(r.a->inverseMass, r.b->inverseMass));
    }
    if (largestChange < kPushVelocityTolerance) return true;
  }
  return false;
}

// Split impulses (Catto's pseudo velocities, as in Box2D v2 and Bullet): sequential
// impulses on the push velocities alone, targets from the overlap beyond the allowed one.
// Sweeps that stop unconverged leave a column's pushes half carried: an overlap high in
// a column of ten pushes each box below down a little more each sweep, and at the limit
// the bottom box was pushed 0.02 m/s into the ground while 1e-4 m deep in it (its
// every event of the step then stalled at once: pile of 1000, seed 6). So they end, as
// the velocities do, with a pass from the ground up (shock_propagation.h), each level's
// pushes solved against the levels below held where their pushes take them.
void solvePushes(std::vector<Row>& rows, const ContactSweeps& sweeps, double allowedOverlap, double dt,
                 const Eigen::Vector3d& up) {
  for (RigidBody* b : sweeps.bodies().moving(rows)) b->pushVelocity.setZero(), b->pushAngularVelocity.setZero();
  std::vector<double> target(rows.size()), impulse(rows.size(), 0.0);
  bool any = false;
  for (size_t k = 0; k < rows.size(); ++k) {
    target[k] = std::max(0.0, -rows[k].separation - allowedOverlap) / dt;
    any = any || target[k] > 0;
  }
  if (!any) return;
  std::vector<PushRow> reached;
  for (int k : rowsReachedByPushes(sweeps, target)) reached.push_back({&rows[k], &impulse[k], target[k]});
  if (sweepPushes(reached)) return;
  forEachLevel(rows, sweeps.bodies(), up, [&](std::vector<Row>& sub, const std::vector<int>& picked) {
    std::vector<PushRow> level;
    for (size_t i = 0; i < sub.size(); ++i) level.push_back({&sub[i], &impulse[picked[i]], target[picked[i]]});
    sweepPushes(level);
  });
}

// Prepare: a row per contact of a moving body, its frames, axes, effective masses and
// target taken once. `frames` holds the bodies' frames the rows point into.
std::vector<Row> prepareRows(std::vector<RigidBody>& bodies, std::vector<ContactPoint>& contacts, double dt,
                             std::vector<BodyFrame>& frames) {
  std::vector<Row> rows;
  rows.reserve(contacts.size());
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
    r.normal = c.normal;
    r.friction = c.friction;
    r.separation = c.separation;
    r.tangent1 = r.normal.unitOrthogonal();
    r.tangent2 = r.normal.cross(r.tangent1);
    prepareAxes(r);
    const double approach = r.normal.dot(relativeVelocity(r));
    if (approach < -kBounceThreshold) r.restitution = c.restitution;
    // A contact still apart may close its gap within the step (a speculative target),
    // but a bouncing one is stopped outright: restitution returns e times the impulse
    // that stopped it, and closing the gap first would take gap / dt off the rebound
    // (0.6% of the speed per bounce at dt 1/240, measured on bounce_e09).
    r.target = r.restitution > 0 ? 0.0 : -std::max(c.separation, 0.0) / dt;
    if (r.restitution == 0) r.target -= 0.5 * std::min(0.0, gapCurvature(r)) * dt;
    rows.push_back(r);
  }
  return rows;
}

// The rows' accumulated impulses applied to the bodies.
void applyImpulses(std::vector<Row>& rows) {
  for (Row& r : rows) {
    applyAlong(r, r.normalAxis, r.normalImpulse);
    applyAlong(r, r.tangentAxis1, r.frictionImpulse.x());
    applyAlong(r, r.tangentAxis2, r.frictionImpulse.y());
  }
}

// Warm start: each row's given impulses, clamped to their limits, applied to the bodies.
// The given friction is a world vector (contact_solver.h), projected on the row's axes.
void warmStart(std::vector<Row>& rows) {
  for (Row& r : rows) {
    r.normalImpulse = std::max(0.0, r.source->normalImpulse);
    if (r.friction > 0) {
      const Eigen::Vector3d& given = r.source->frictionImpulse;
      r.frictionImpulse = Eigen::Vector2d(r.tangent1.dot(given), r.tangent2.dot(given));
      const double limit = r.friction * r.normalImpulse;
      if (r.frictionImpulse.norm() > limit) r.frictionImpulse *= limit / r.frictionImpulse.norm();
    }
  }
  applyImpulses(rows);
}

// The rows' accumulated impulses, to go back to.
std::vector<std::pair<double, Eigen::Vector2d>> impulsesOf(const std::vector<Row>& rows) {
  std::vector<std::pair<double, Eigen::Vector2d>> impulses;
  impulses.reserve(rows.size());
  for (const Row& r : rows) impulses.emplace_back(r.normalImpulse, r.frictionImpulse);
  return impulses;
}

}  // namespace

SolveStats solveContacts(std::vector<RigidBody>& bodies, std::vector<ContactPoint>& contacts, double dt,
                         double allowedOverlap, int maxSweeps, const Eigen::Vector3d& up) {
  std::vector<BodyFrame> frames;
  std::vector<Row> rows = prepareRows(bodies, contacts, dt, frames);
  const ContactSweeps sweeps(rows);
  const std::vector<RigidBody*> moving = sweeps.bodies().moving(rows);
  const double energyBefore = kineticEnergy(moving);
  const auto gainedEnergy = [&](double before) { return kineticEnergy(moving) > before * (1 + kEnergyRoundOff); };
  const SavedVelocities start(moving);
  warmStart(rows);

  SolveStats stats;
  const auto sweep = [&] {
    const SolveStats swept = sweeps.run(rows, maxSweeps);
    stats.iterations = std::max(stats.iterations, swept.iterations);
    stats.converged = swept.converged;
    stats.rowSolves += swept.rowSolves;
  };
  sweep();
  // A solve that ends with more kinetic energy than it began with starts again from zero
  // impulses and with no target above zero, where sequential impulses take energy away
  // (frictionless, each update lowers a convex energy; friction's two axes are solved as
  // if uncoupled, so with friction nearly). It gains two ways. A target above zero (a gap curving closed faster than the
  // bodies approach) asks for separation the turning bodies' own motion must pay for: a
  // cup wedged on a spinning neighbour was asked for 21 m/s of separation a step, spun
  // faster, and was asked for more (5e14 J in 20 s). And a warm start may push harder
  // than this step needs (a contact that came apart) and not be taken back before the
  // sweeps' limit: at 100 sweeps a frictionless column of cups gained 2,500 J in 4 s.
  if (gainedEnergy(energyBefore)) {
    start.restore();
    for (Row& r : rows) r.target = std::min(r.target, 0.0), r.normalImpulse = 0.0, r.frictionImpulse.setZero();
    sweep();
  }
  if (!stats.converged) {
    const SavedVelocities swept(moving);
    const double energySwept = kineticEnergy(moving);
    const std::vector<std::pair<double, Eigen::Vector2d>> impulses = impulsesOf(rows);
    const SolveStats shock = propagateShock(rows, sweeps.bodies(), std::min(maxSweeps, kMaxSolverIterations), up);
    stats.shockSweeps = shock.iterations;
    stats.shockRowSolves = shock.rowSolves;
    // A pass that gains energy (a level pushed by a body below it moving up) is not
    // thrown away: its impulses, found with the levels below held fixed, are still a far
    // better guess than where the sweeps stopped. The sweeps start again from them, every
    // body free (momentum conserved again), and that is kept unless it ends above the
    // sweeps' own energy. Thrown away, it left a quarter of a settling pile's solves with
    // a contact approaching over 1 mm/s faster than its target, each a back-up to come.
    if (gainedEnergy(energySwept)) {  // the pass gained energy
      start.restore();
      applyImpulses(rows);
      sweep();
      if (gainedEnergy(energySwept)) {  // and so did the sweeps from it
        swept.restore();
        for (size_t k = 0; k < rows.size(); ++k) std::tie(rows[k].normalImpulse, rows[k].frictionImpulse) = impulses[k];
      }
    }
  }
  applyRestitution(rows, moving, energyBefore);
  solvePushes(rows, sweeps, allowedOverlap, dt, up);
  // The test of rest per metre of size (a body's own size is the scene's, not the solver's).
  for (RigidBody* b : moving) b->restedAfterLastSolve = atRest(b->velocity, b->angularVelocity, 1.0);
  for (Row& r : rows) {  // store, for the next step's warm start
    r.source->normalImpulse = r.normalImpulse;
    r.source->frictionImpulse = r.tangent1 * r.frictionImpulse.x() + r.tangent2 * r.frictionImpulse.y();
  }
  return stats;
}

}  // namespace polysim::dynamics
