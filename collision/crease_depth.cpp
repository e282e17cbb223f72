#include "collision/crease_depth.h"

#include <algorithm>
#include <limits>

#include "collision/clip.h"
#include "collision/segment_distance.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Whether x lies behind both faces of q's crease k.
bool insideCrease(const PolygonView& q, int k, const Eigen::Vector3d& x) {
  const Eigen::Vector3d n = neighbourNormal(q, k);
  return q.plane.signedDistance(x) <= 0.0 && n.dot(x - q.vertices[k]) <= 0.0;
}

// Whether a point `along` m from the start of side k of q (`length` m long) lies within
// `reach` of an end of that side where q's adjacent side is a convex crease.
bool nearCappedEnd(const PolygonView& q, int k, double along, double length, double reach) {
  const int before = (k + q.size - 1) % q.size, after = (k + 1) % q.size;
  return (along <= reach && convexCrease(q, before)) || (length - along <= reach && convexCrease(q, after));
}

}  // namespace

Eigen::Vector3d neighbourNormal(const PolygonView& q, int k) {
  const Eigen::Vector3d& o = q.edgeOutward[k];
  return 2.0 * q.plane.normal.dot(o) * o - q.plane.normal;
}

bool convexCrease(const PolygonView& q, int k) {
  return !q.edgeFlat[k] && q.sideNormal[k].dot(neighbourNormal(q, k)) > kFlatEdgeAngle;
}

double deepestCrossing(const PolygonView& p, const PolygonView& q, double eps) {
  double deepest = 0.0;
  for (int i = 0; i < p.size; ++i) {
    if (!convexCrease(p, i)) continue;
    const Eigen::Vector3d& p0 = p.vertices[i];
    const Eigen::Vector3d u = p.vertices[(i + 1) % p.size] - p0;
    for (int j = 0; j < q.size; ++j) {
      if (!convexCrease(q, j)) continue;
      const Eigen::Vector3d& q0 = q.vertices[j];
      const Eigen::Vector3d v = q.vertices[(j + 1) % q.size] - q0;
      if (u.cross(v).norm() <= kParallelSine * u.norm() * v.norm()) continue;
      const SegmentClosestPoints cp = closestPointsOnSegments(p0, u, q0, v);
      if (cp.distance <= deepest || cp.distance > kCrossingReach * eps) continue;
      // A crease is a wedge only away from an end where a third face caps it (the
      // polygon's next side there is a convex crease too): within their distance of such
      // an end, the closest points say nothing about depth. A cup's bottom corner on
      // another cup's rim, 1.6 mm outside the rim's inner edge, has its corner edge's line
      // pass that edge 1.6 mm away 37 um above the corner, where the bottom face bounds
      // it. Where the next side is a reflex crease or flat (a cup's inner rim edge ends in
      // the inner corner of two walls), the object goes on past the end.
      const double uLength = u.norm(), vLength = v.norm();
      const double s = u.dot(cp.onFirst - p0) / uLength, t = v.dot(cp.onSecond - q0) / vLength;  // m along each
      if (s <= 0.0 || s >= uLength || t <= 0.0 || t >= vLength) continue;  // an end: its vertex's to report
      if (nearCappedEnd(p, i, s, uLength, cp.distance) || nearCappedEnd(q, j, t, vLength, cp.distance)) continue;
      if (insideCrease(q, j, cp.onFirst) && insideCrease(p, i, cp.onSecond)) deepest = cp.distance;
    }
  }
  return deepest;
}

// Measured behind q alone, a cup's inner rim corner sunk into the outer corner of another
// cup would read as deep as it lies behind one wall, though it is held by the contact on
// the other wall, which is shallower; a step would then never leave that state.
double deepestInWedge(const PolygonView& q, const std::vector<Eigen::Vector3d>& polygon, double enough, PolygonScratch& s) {
  s.wedge.clear();  // planes (outward normal, offset): a point's depth behind each is offset - normal . x
  s.wedge.push_back({q.plane.normal, q.plane.offset});
  for (int k = 0; k < q.size; ++k) {
    if (!convexCrease(q, k)) continue;
    const Eigen::Vector3d neighbour = neighbourNormal(q, k);
    s.wedge.push_back({neighbour, neighbour.dot(q.vertices[k])});
  }
  auto depthAt = [&s](const Eigen::Vector3d& x) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [normal, offset] : s.wedge) d = std::min(d, offset - normal.dot(x));
    return d;
  };
  // The depth is concave over the polygon: at least its largest at a corner, at most the
  // largest depth behind q (at a corner too, being linear).
  double lo = 0.0, hi = 0.0;
  for (const Eigen::Vector3d& x : polygon) {
    lo = std::max(lo, depthAt(x));
    hi = std::max(hi, -q.plane.signedDistance(x));
  }
  // Whether some point of the polygon lies at least `depth` inside every plane.
  auto reaches = [&s, &polygon](double depth) {
    s.deepA = polygon;
    for (const auto& [normal, offset] : s.wedge) {
      clipBelow(s.deepA, normal, offset - depth, s.deepB);
      s.deepA.swap(s.deepB);
      if (s.deepA.empty()) return false;
    }
    return true;
  };
  if (enough >= 0.0 && lo <= enough) {
    if (!reaches(enough)) return lo;
    lo = enough;
  }
  while (hi - lo > kDepthResolution) {
    const double mid = 0.5 * (lo + hi);
    (reaches(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace polysim::collision
