#pragma once
// What the intersection test reports: per pair of objects a status and the contacts,
// each a point, a line (segment) or an area (convex polygon) with a normal.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace polysim::collision {

/// Ordered from best to worst: a database's status is the worst of its pairs.
enum class Status { Separate = 0, Contact = 1, Interpenetrating = 2 };

enum class ContactType { Point, Line, Area };

/// Which feature of a mesh a contact came from, so that a contact can be matched from one
/// query to the next (Box2D's feature ids). `id` indexes the mesh's vertices, edges or faces.
struct Feature {
  enum class Kind { Vertex, Edge, Face };
  Kind kind = Kind::Face;
  int id = -1;
};

/// One contact between objects a and b, all in the world frame (m).
struct Contact {
  ContactType type = ContactType::Point;
  /// Unit vector from b towards a: moving a along it separates the pair (ODE's convention).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Point: one point. Line: the segment's two end points. Area: the overlap polygon's
  /// vertices, counter-clockwise seen from the tip of `normal` (3 or more).
  std::vector<Eigen::Vector3d> points;
  /// Per point of `points`: the distance (m) between the touching features there, along
  /// the normal; positive for a gap, negative for an overlap. A face tilted within the
  /// band is deeper at some corners than at others, and the solver needs each corner's own.
  std::vector<double> gaps;
  /// The smallest of `gaps` (m): the deepest the features come; within [-tolerance,
  /// tolerance].
  double separation = 0.0;
  Feature featureA, featureB;

  /// Appends a point x with its gap; keeps `separation` the smallest gap.
  void addPoint(const Eigen::Vector3d& x, double gap);
  /// The gap at point i: gaps[i], or `separation` for a contact built without gaps.
  double gapAt(size_t i) const { return i < gaps.size() ? gaps[i] : separation; }
};

/// The outcome for one pair of objects (indices into the database, a < b).
struct PairResult {
  int a = -1, b = -1;
  Status status = Status::Separate;
  /// The contacts, each reported once; empty when the pair interpenetrates (contact
  /// geometry is not meaningful then) or is separate.
  std::vector<Contact> contacts;
  /// For an interpenetrating pair, the deepest interpenetration found (m; a lower bound
  /// when the test was asked for no contacts); for two convex objects, their penetration
  /// depth (the least translation that parts them). 0 otherwise.
  double depth = 0.0;
};

std::string toString(Status status);
std::string toString(ContactType type);

}  // namespace polysim::collision
