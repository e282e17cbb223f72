#pragma once
// Contact response by impulses: sequential impulses with accumulated, clamped normal and
// friction impulses (Catto, "Iterative Dynamics with Temporal Coherence", 2005), solved
// for all contacts together, the normal impulses of one contact's points (an area's
// corners) as one block (small_lcp.h).

#include <Eigen/Core>
#include <vector>

#include "dynamics/rigid_body.h"
#include "dynamics/settings.h"

namespace polysim::dynamics {

/// One contact point between bodies a and b, as plain data.
struct ContactPoint {
  int a = -1, b = -1;                                  // indices into the body array
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     // m, world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit, world, from b towards a
  double separation = 0.0;                             // m: gap (> 0) or overlap (< 0)
  double restitution = 0.0;                            // the pair's coefficient
  double friction = 0.0;                               // the pair's Coulomb coefficient
  /// Points of one contact (an area's corners, a line's ends) share an id, and their
  /// normal impulses are solved together as one block (small_lcp.h); -1: on its own.
  int manifold = -1;
  /// How the normal turns as the bodies do: with a's angular velocity times this plus b's
  /// times (1 - this). 1: the normal is a face's of a (a point of b on it); 0: a face's of
  /// b; 0.5: between two edges, or two faces together.
  double normalTurnWithA = 0.5;
  /// A point where an edge of a crosses an edge of b: the two edges' unit directions
  /// (world), whose cross product is the normal; zero for any other point. The normal then
  /// turns with both edges, not with one body, and the points closest on the two edges
  /// slide along them (contact_row.h, gapCurvature).
  Eigen::Vector3d edgeA = Eigen::Vector3d::Zero(), edgeB = Eigen::Vector3d::Zero();
  /// In: the impulses to start from (warm start, e.g. last step's for the same point);
  /// out: the accumulated impulses solved (N s). Friction is a world vector in the
  /// contact plane (a given one is projected onto it), not coordinates in the solver's
  /// tangent axes: those axes may swing by any angle between steps when the normal tilts
  /// slightly off a world axis, and a warm start in them would push the wrong way.
  double normalImpulse = 0.0;
  Eigen::Vector3d frictionImpulse = Eigen::Vector3d::Zero();
};

struct SolveStats {
  int iterations = 0;        // sweeps made (by the group of contacts that took the most)
  bool converged = false;    // every group stopped on kSolverVelocityTolerance, not the sweep limit
  long rowSolves = 0;        // contact points solved, summed over all sweeps: the sweeps' work
  int shockSweeps = 0;       // shock propagation's sweeps, summed over its levels (0 if converged)
  long shockRowSolves = 0;   // and its work, as rowSolves
};

/// Changes the bodies' velocities so that no contact approaches: every contact ends with
/// relative normal velocity >= its target (0 at rest; -gap/dt for a contact with a gap,
/// which may close within the step; raised by the gap's closing curvature times dt / 2
/// where the bodies' turning closes the gap faster than their velocities say: a point
/// sliding along a face that turns towards it), normal impulses >= 0, friction impulses within the
/// Coulomb disk mu * normal impulse (sticking while inside it, sliding on its rim).
/// Restitution follows Poisson's hypothesis: after that compression solve, each contact
/// that approached faster than kBounceThreshold gets e times its compression impulse
/// more (frictionless, that cannot add energy for e <= 1: dE = (e^2 - 1)/2 P'AP); with
/// friction the rebound is scaled down where needed so that kinetic energy never rises.
/// `dt` (s) is the time to the next contact detection. Static bodies are never changed;
/// contacts with zero friction skip all friction work.
/// Starting from each contact's given impulses (warm start) lets a resting stack carry
/// its weight from the first sweep; they are clamped to the same limits first.
/// Sweeps go through the contacts in their given order and back again in turn (the
/// step loop gives them bottom-up). Contacts that share no moving body (two piles on one
/// floor) are swept apart, each group until it converges or reaches its limit on its own:
/// `maxSweeps` (the scene's `solver_sweeps`) bounds every group, and one still moving
/// faster than kSettlingSpeed, or whose bodies all rested after their last solve, stops
/// at kMaxSolverIterations (settings.h). Each body's `restedAfterLastSolve` is set here.
/// The compression solve is kept from adding kinetic energy: where the sweeps end with
/// more than the bodies had (a warm start larger than the step needs, not taken back
/// within `maxSweeps`), the solve starts again from zero impulses with no target above
/// zero, which frictionless cannot gain (with friction, whose two axes are solved as if
/// uncoupled, a solve stopped within a few sweeps may still gain a little).
/// Where the sweeps stop at `maxSweeps`, shock propagation (shock_propagation.h) solves
/// again from the ground up (`up`: the unit vector against gravity, zero for none), each
/// level against the ones below held fixed; its result is kept only if it raised no
/// kinetic energy.
/// Then the push velocities of the bodies touched are set afresh (split impulses,
/// rigid_body.h): every contact overlapping deeper than `allowedOverlap` (m) separates at
/// (depth - allowedOverlap) / dt or more, no contact's push approaches, and push impulses
/// are >= 0 and frictionless.
SolveStats solveContacts(std::vector<RigidBody>& bodies, std::vector<ContactPoint>& contacts, double dt,
                         double allowedOverlap = 0.0, int maxSweeps = kSettlingSolverSweeps,
                         const Eigen::Vector3d& up = Eigen::Vector3d::Zero());

}  // namespace polysim::dynamics
