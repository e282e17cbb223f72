#pragma once
// Contacts as the solver sees them: each pair's contacts turned into the dynamics' plain
// contact points, one manifold per plane of contact.

#include <functional>
#include <vector>

#include "collision/contact.h"
#include "dynamics/contact_solver.h"

namespace polysim::sim {

/// Material of a pair of bodies: the larger restitution, the geometric mean of frictions.
struct PairMaterial {
  double restitution = 0.0;
  double friction = 0.0;
};

/// The unit direction (world) of edge `edgeId` of the pair's body a (`ofA`) or b.
using EdgeDirection = std::function<Eigen::Vector3d(bool ofA, int edgeId)>;

/// Contacts of one pair whose normals lie within this angle (rad) of each other are one
/// manifold for the solver. A box resting on another, or a cup on a cup's rim, touches in
/// one plane, which the detector reports as several contacts: the face of each body, each
/// convex piece of a rim, edges sharing a corner. Solved apart, they repeat points (a
/// corner shared by two edges, by two pieces of a rim) with targets that differ by round-
/// off, and the sweeps shift load between the copies forever: in a pile of 125 tilted
/// boxes most solves ran to the sweep limit. Faces touching within the contact tolerance
/// (1e-4 m over a 1 m box) lie within 2e-4 rad of each other; different faces of a box,
/// or a cup's wall and rim, lie far outside 1e-3.
inline constexpr double kCoplanarContactAngle = 1e-3;

/// Points of one manifold closer than this (m) in its plane are one point; three whose
/// triangle is thinner than this are on a line. Far below the contact tolerance, far
/// above round-off on metre-sized bodies.
inline constexpr double kSameContactPoint = 1e-9;

/// The contact points of one pair of bodies (a, b: body indices). The pair's contacts
/// are grouped by normal (kCoplanarContactAngle); each group is one manifold: the corners
/// of the convex hull of its points in its plane (every vertex of an area, both ends of a
/// line, a point), each with its own gap. The hull's corners bound every normal force and
/// torque the group's points could give, so nothing a contact can hold is lost; points
/// inside it, and copies of one point, are dropped. A group takes the normal of its
/// deepest contact. A contact alone in its plane goes as the detector gave it (its
/// polygon's corners in order): the sweeps follow the points' order, and a pyramid of
/// 820 boxes at the sweep limit moved 16 mm in 10 s with its corners re-ordered, 4.1 mm
/// without.
/// A point where an edge of a crosses an edge of b (a point contact between two edges, on
/// its own in its plane) also gets the two edges' directions, from `edgeDirection` when
/// given (dynamics::ContactPoint::edgeA).
void appendContactPoints(int a, int b, const std::vector<collision::Contact>& contacts, const PairMaterial& material,
                         std::vector<dynamics::ContactPoint>& out, const EdgeDirection& edgeDirection = {});

}  // namespace polysim::sim
