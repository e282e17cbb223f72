#pragma once
// A contact point as the contact solver's sweeps see it (contact_solver.cpp): its bodies'
// frames taken once per solve, and each of its three directions (normal, two tangents)
// prepared once, so that a sweep reads a relative velocity with four dot products and
// applies an impulse with four scaled additions. Internal to the solver.

#include <Eigen/Core>

#include "dynamics/contact_solver.h"
#include "dynamics/rigid_body.h"
#include "dynamics/settings.h"

namespace polysim::dynamics::solver {

// A body as the sweeps see it, taken once per solve (a solve changes velocities, never
// poses): its world inverse inertia and centre of mass. Recomputing them from the
// quaternion at every impulse was most of a resting stack's solve time.
struct BodyFrame {
  Eigen::Matrix3d inverseInertia = Eigen::Matrix3d::Zero();  // 1 / (kg m^2), world axes
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();    // m, world
};

// One direction d of a row, prepared once: the velocity along it is d . (v_a - v_b) +
// angularA . w_a - angularB . w_b, and an impulse p along it adds p * turnA to a's angular
// velocity and takes p * turnB from b's (each zero for a static body).
struct Axis {
  Eigen::Vector3d direction, angularA, angularB, turnA, turnB;
};

// A contact prepared for the sweeps: lever arms, effective masses, target, impulses.
struct Row {
  ContactPoint* source;
  RigidBody* a;
  RigidBody* b;
  const BodyFrame* frameA;
  const BodyFrame* frameB;
  Eigen::Vector3d normal, tangent1, tangent2;
  Eigen::Vector3d armA, armB;                                 // m, from each centre of mass to the point
  Axis normalAxis, tangentAxis1, tangentAxis2;
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
inline constexpr Velocities kMomentum{&RigidBody::velocity, &RigidBody::angularVelocity};
inline constexpr Velocities kPush{&RigidBody::pushVelocity, &RigidBody::pushAngularVelocity};

// The velocity of a's material point at the contact relative to b's.
inline Eigen::Vector3d relativeVelocity(const Row& r, Velocities v = kMomentum) {
  return (r.a->*v.linear + (r.a->*v.angular).cross(r.armA)) - (r.b->*v.linear + (r.b->*v.angular).cross(r.armB));
}

// The axis of a unit direction d at the row's point (its arms and frames set).
inline Axis axisOf(const Row& r, const Eigen::Vector3d& d) {
  Axis x;
  x.direction = d;
  x.angularA = r.armA.cross(d);
  x.angularB = r.armB.cross(d);
  x.turnA = r.a->isStatic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(r.frameA->inverseInertia * x.angularA);
  x.turnB = r.b->isStatic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(r.frameB->inverseInertia * x.angularB);
  return x;
}

// The relative velocity along an axis (m/s).
inline double velocityAlong(const Row& r, const Axis& x, Velocities v = kMomentum) {
  return x.direction.dot(r.a->*v.linear - r.b->*v.linear) + x.angularA.dot(r.a->*v.angular) - x.angularB.dot(r.b->*v.angular);
}

// Impulse p (N s) along an axis on a, -p on b.
inline void applyAlong(Row& r, const Axis& x, double p, Velocities v = kMomentum) {
  if (!r.a->isStatic) {
    r.a->*v.linear += (r.a->inverseMass * p) * x.direction;
    r.a->*v.angular += p * x.turnA;
  }
  if (!r.b->isStatic) {
    r.b->*v.linear -= (r.b->inverseMass * p) * x.direction;
    r.b->*v.angular -= p * x.turnB;
  }
}

// A block's two bodies' velocities (a block's rows share their bodies), held while the
// sweeps solve its rows and stored once after: a sweep then reads and writes each body
// once a block, not once per impulse. The same arithmetic as velocityAlong() and
// applyAlong(), so the same impulses to the bit. A static body (or one shock propagation
// holds fixed) has zero inverse mass and turns, so an impulse adds nothing to it, and
// its velocities are never stored back.
struct PairVelocities {
  Eigen::Vector3d linearA, angularA, linearB, angularB;
  double inverseMassA, inverseMassB;  // 1/kg, 0 for a static body
};

inline PairVelocities velocitiesOf(const Row& r) {
  return {r.a->velocity, r.a->angularVelocity, r.b->velocity, r.b->angularVelocity, r.a->inverseMass, r.b->inverseMass};
}

inline void storeVelocities(const PairVelocities& v, const Row& r) {
  if (!r.a->isStatic) r.a->velocity = v.linearA, r.a->angularVelocity = v.angularA;
  if (!r.b->isStatic) r.b->velocity = v.linearB, r.b->angularVelocity = v.angularB;
}

// The relative velocity along an axis (m/s), as velocityAlong().
inline double velocityAlong(const PairVelocities& v, const Axis& x) {
  return x.direction.dot(v.linearA - v.linearB) + x.angularA.dot(v.angularA) - x.angularB.dot(v.angularB);
}

// Impulse p (N s) along an axis on a, -p on b, as applyAlong().
inline void applyAlong(PairVelocities& v, const Axis& x, double p) {
  v.linearA += (v.inverseMassA * p) * x.direction;
  v.angularA += p * x.turnA;
  v.linearB -= (v.inverseMassB * p) * x.direction;
  v.angularB -= p * x.turnB;
}

// 1 / (d . (M_a^-1 + M_b^-1) d) for the unit direction of an axis: the impulse along it
// that changes the relative velocity along it by 1 m/s (0 between two static bodies).
inline double effectiveMass(const Row& r, const Axis& x) {
  const double k = r.a->inverseMass + r.b->inverseMass + x.angularA.dot(x.turnA) + x.angularB.dot(x.turnB);
  return k > 0 ? 1.0 / k : 0.0;
}

// How much a unit impulse along row j's normal at its point changes row i's normal
// velocity (both rows between the same two bodies): the block's coupling matrix entry.
inline double coupling(const Row& i, const Row& j) {
  return (i.a->inverseMass + i.b->inverseMass) * i.normal.dot(j.normal) + i.normalAxis.angularA.dot(j.normalAxis.turnA) +
         i.normalAxis.angularB.dot(j.normalAxis.turnB);
}

// The second derivative of the row's gap (m/s^2) were both bodies to keep their velocities
// (g = n . (x_a - x_b) for the material points x_a, x_b at the contact, with n turning
// as the face it belongs to): the turn of the normal against the relative velocity, and
// the centripetal accelerations of the two material points. A gap curving closed over
// the step is what a velocity target of -gap / dt misses: a domino's edge sliding down
// its neighbour's face, which turns towards it at 2 rad/s, closes 0.4 mm more in a step
// of 1/60 s, four tolerances; each time the step backed up to it.
//
// Two edges crossing (ContactPoint::edgeA and edgeB set): the normal is their cross
// product and turns with both, and the points closest on the two edges slide along them
// so that the relative velocity's part in the contact plane, u_t, is taken up: slides sA,
// sB (m/s) with sA eA - sB eB = -u_t. The gap's second derivative is then exact for two
// lines: the centripetal accelerations along the normal plus 2 sA n . (w_a x eA) -
// 2 sB n . (w_b x eB), the Coriolis turn of each sliding point. A box landing spinning at
// 6 rad/s on another's edge closed such a gap at 50 m/s^2 that a normal turning with the
// mean spin did not see; each event then moved on a few microseconds, to the event bound.
inline double gapCurvature(const Row& r) {
  auto centripetal = [](const RigidBody* body, const Eigen::Vector3d& arm) -> Eigen::Vector3d {
    if (body->isStatic) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d& w = body->angularVelocity;
    return w.cross(w.cross(arm));
  };
  const Eigen::Vector3d& edgeA = r.source->edgeA;
  const Eigen::Vector3d& edgeB = r.source->edgeB;
  const double cosine = edgeA.dot(edgeB), sine2 = 1.0 - cosine * cosine;
  if (!edgeA.isZero(0.0) && !edgeB.isZero(0.0) && sine2 > kCrossingEdgeSine * kCrossingEdgeSine) {
    const Eigen::Vector3d u = relativeVelocity(r);
    const Eigen::Vector3d inPlane = u - r.normal.dot(u) * r.normal;
    const double slideB = (edgeB.dot(inPlane) - cosine * edgeA.dot(inPlane)) / sine2;
    const double slideA = cosine * slideB - edgeA.dot(inPlane);
    const Eigen::Vector3d spinA = r.a->isStatic ? Eigen::Vector3d::Zero() : r.a->angularVelocity;
    const Eigen::Vector3d spinB = r.b->isStatic ? Eigen::Vector3d::Zero() : r.b->angularVelocity;
    return r.normal.dot(centripetal(r.a, r.armA) - centripetal(r.b, r.armB)) + 2.0 * slideA * r.normal.dot(spinA.cross(edgeA)) -
           2.0 * slideB * r.normal.dot(spinB.cross(edgeB));
  }
  const double withA = r.source->normalTurnWithA;
  const Eigen::Vector3d normalTurn = (withA * r.a->angularVelocity + (1 - withA) * r.b->angularVelocity).cross(r.normal);
  return r.normal.dot(centripetal(r.a, r.armA) - centripetal(r.b, r.armB)) + 2.0 * normalTurn.dot(relativeVelocity(r));
}

}  // namespace polysim::dynamics::solver
