#include "sim/contact_points.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace polysim::sim {
namespace {

using Kind = collision::Feature::Kind;

// A point of a group in its plane's coordinates, with its gap.
struct PlanePoint {
  double u, v;
  Eigen::Vector3d x;
  double gap;
};

// Twice the signed area of (o, p, q): > 0 when q lies left of o -> p.
double turn(const PlanePoint& o, const PlanePoint& p, const PlanePoint& q) {
  return (p.u - o.u) * (q.v - o.v) - (p.v - o.v) * (q.u - o.u);
}

// The corners of the convex hull of `points` (Andrew's monotone chain), counter-clockwise;
// of coincident points, the one with the smallest gap. Collinear points give their two
// ends; a single point, itself.
std::vector<PlanePoint> hullCorners(std::vector<PlanePoint> points) {
  std::sort(points.begin(), points.end(), [](const PlanePoint& p, const PlanePoint& q) {
    return p.u != q.u ? p.u < q.u : p.v < q.v;
  });
  std::vector<PlanePoint> unique;
  for (const PlanePoint& p : points) {
    if (!unique.empty() && std::hypot(p.u - unique.back().u, p.v - unique.back().v) <= kSameContactPoint) {
      if (p.gap < unique.back().gap) unique.back() = p;
      continue;
    }
    unique.push_back(p);
  }
  if (unique.size() < 3) return unique;
  std::vector<PlanePoint> hull(2 * unique.size());
  size_t k = 0;
  auto keepsTurningLeft = [&](const PlanePoint& q, size_t floor) {
    while (k >= floor) {
      const double base = std::hypot(hull[k - 1].u - hull[k - 2].u, hull[k - 1].v - hull[k - 2].v);
      if (turn(hull[k - 2], hull[k - 1], q) > kSameContactPoint * base) break;
      --k;
    }
  };
  for (const PlanePoint& p : unique) {  // lower chain
    keepsTurningLeft(p, 2);
    hull[k++] = p;
  }
  for (size_t i = unique.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    keepsTurningLeft(unique[i], lower);
    hull[k++] = unique[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

}  // namespace

void appendContactPoints(int a, int b, const std::vector<collision::Contact>& contacts, const PairMaterial& material,
                         std::vector<dynamics::ContactPoint>& out, const EdgeDirection& edgeDirection) {
  const double sameDirection = std::cos(kCoplanarContactAngle);
  std::vector<char> taken(contacts.size(), 0);
  std::vector<const collision::Contact*> group;  // one plane's contacts; reused, as is `points`
  std::vector<PlanePoint> points;
  for (size_t first = 0; first < contacts.size(); ++first) {
    if (taken[first]) continue;
    group.assign(1, &contacts[first]);
    for (size_t k = first + 1; k < contacts.size(); ++k)
      if (!taken[k] && contacts[k].normal.dot(contacts[first].normal) >= sameDirection) {
        taken[k] = 1;
        group.push_back(&contacts[k]);
      }
    const collision::Contact& deepest =
        **std::min_element(group.begin(), group.end(), [](auto* p, auto* q) { return p->separation < q->separation; });
    // How the normal turns with the bodies (ContactPoint::normalTurnWithA): with a's face,
    // b's, or between; a group of contacts that disagree turns between.
    auto turnOf = [](const collision::Contact& c) {
      const bool faceOfA = c.featureA.kind == Kind::Face, faceOfB = c.featureB.kind == Kind::Face;
      return faceOfA == faceOfB ? 0.5 : faceOfA ? 1.0 : 0.0;
    };
    double turnWithA = turnOf(*group.front());
    for (const collision::Contact* c : group)
      if (turnOf(*c) != turnWithA) turnWithA = 0.5;
    const Eigen::Vector3d n = deepest.normal, t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    points.clear();
    for (const collision::Contact* c : group)
      for (size_t i = 0; i < c->points.size(); ++i) points.push_back({t1.dot(c->points[i]), t2.dot(c->points[i]), c->points[i], c->gapAt(i)});
    // A contact on its own is already its polygon's corners (or a segment, or a point), in
    // the detector's order, which the sweeps' order follows: it goes as it is.
    if (group.size() > 1) points = hullCorners(std::move(points));
    const int manifold = static_cast<int>(out.size());  // unique: the index of its first point
    const collision::Contact& only = *group.front();
    const bool crossingEdges = edgeDirection && group.size() == 1 && only.type == collision::ContactType::Point &&
                               only.featureA.kind == Kind::Edge && only.featureB.kind == Kind::Edge;
    for (const PlanePoint& p : points) {
      out.push_back({a, b, p.x, n, p.gap, material.restitution, material.friction, manifold, turnWithA});
      if (crossingEdges) out.back().edgeA = edgeDirection(true, only.featureA.id), out.back().edgeB = edgeDirection(false, only.featureB.id);
    }
  }
}

}  // namespace polysim::sim
