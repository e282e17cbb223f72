#pragma once
// A rigid body's state: pose of its frame, velocities at its centre of mass, and mass.

#include <Eigen/Geometry>

#include "dynamics/mass_properties.h"

namespace polysim::dynamics {

struct RigidBody {
  /// World pose of the body's frame (the scene's position and orientation); the centre
  /// of mass is at centerOfMassLocal in that frame.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  /// Velocity of the centre of mass (m/s) and angular velocity (rad/s), both world.
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();
  /// Split-impulse velocities (m/s, rad/s, world): how fast the contact solver moves the
  /// body out of an overlap deeper than it allows, over the time to the next contact
  /// detection. They move the pose (integrator.h) but are no momentum: they carry no
  /// kinetic energy and no bounce, and the solver sets them afresh at every solve.
  Eigen::Vector3d pushVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d pushAngularVelocity = Eigen::Vector3d::Zero();
  /// Whether the body ended the last contact solve it was in at rest (slower than
  /// kRestSpeed, turning slower than kRestSpeed per metre). A group of such bodies is held
  /// by shock propagation and takes no settling sweeps (contact_sweeps.cpp).
  bool restedAfterLastSolve = false;

  Eigen::Vector3d centerOfMassLocal = Eigen::Vector3d::Zero();  // m, body frame
  double mass = 0.0;                                            // kg; 0 for static
  double inverseMass = 0.0;                                     // 1/kg; 0 for static
  Eigen::Matrix3d inertiaLocal = Eigen::Matrix3d::Zero();       // kg m^2, about the centre of mass, body axes
  Eigen::Matrix3d inverseInertiaLocal = Eigen::Matrix3d::Zero();
  bool isStatic = false;

  /// A dynamic body with the given mass properties (mesh frame = body frame).
  static RigidBody dynamic(const MassProperties& props);
  /// A static body: infinite mass, never moves.
  static RigidBody fixed();

  Eigen::Vector3d centerOfMass() const { return position + orientation * centerOfMassLocal; }
  Eigen::Matrix3d inverseInertiaWorld() const;
  /// Velocity (m/s, world) of the body's material point at world point p.
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& p) const {
    return velocity + angularVelocity.cross(p - centerOfMass());
  }
  /// Applies impulse J (N s, world) at world point p.
  void applyImpulse(const Eigen::Vector3d& J, const Eigen::Vector3d& p);
  /// The same for a push impulse: changes the push velocities only.
  void applyPushImpulse(const Eigen::Vector3d& J, const Eigen::Vector3d& p);
  Eigen::Vector3d pushVelocityAt(const Eigen::Vector3d& p) const {
    return pushVelocity + pushAngularVelocity.cross(p - centerOfMass());
  }
  /// Kinetic energy (J).
  double kineticEnergy() const;
  Eigen::Isometry3d pose() const;
};

/// True when a body of the given size (m: its farthest point from the centre of mass)
/// moves slower than kRestSpeed, counting the speed its spin gives its farthest point.
bool atRest(const Eigen::Vector3d& velocity, const Eigen::Vector3d& angularVelocity, double size);

}  // namespace polysim::dynamics
