#include "collision/crease_depth.h"

#include <algorithm>
#include <limits>

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

bool convexCrease(const PolygonView& q, int k) { return q.convexSide[k] != 0; }

double deepestCrossing(const PolygonView& p, const PolygonView& q, double eps) {
  double deepest = 0.0;
  if (!p.anyConvexSide || !q.anyConvexSide) return deepest;
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
      // An end is told by the clamped parameters themselves: recomputed from the point, a
      // rim edge's end came out 1 ulp short of the edge's length, and a cup's bottom edge
      // passing 1.9 mm beyond it read as a crossing 1.6 mm deep.
      if (cp.s <= 0.0 || cp.s >= 1.0 || cp.t <= 0.0 || cp.t >= 1.0) continue;  // an end: its vertex's to report
      const double uLength = u.norm(), vLength = v.norm();
      const double s = cp.s * uLength, t = cp.t * vLength;  // m along each
      if (nearCappedEnd(p, i, s, uLength, cp.distance) || nearCappedEnd(q, j, t, vLength, cp.distance)) continue;
      if (insideCrease(q, j, cp.onFirst) && insideCrease(p, i, cp.onSecond)) deepest = cp.distance;
    }
  }
  return deepest;
}

// Measured behind q alone, a cup's inner rim corner sunk into the outer corner of another
// cup would read as deep as it lies behind one wall, though it is held by the contact on
// the other wall, which is shallower; a step would then never leave that state.
double deepestInWedge(const PolygonView& q, const std::vector<Eigen::Vector3d>& polygon, PolygonScratch& s) {
  s.wedge.clear();  // planes (outward normal, offset): a point's depth behind each is offset - normal . x
  s.wedge.push_back({q.plane.normal, q.plane.offset});
  for (int k = 0; k < q.size; ++k) {
    if (!convexCrease(q, k)) continue;
    const Eigen::Vector3d neighbour = neighbourNormal(q, k);
    s.wedge.push_back({neighbour, neighbour.dot(q.vertices[k])});
  }
  const int planes = static_cast<int>(s.wedge.size()), corners = static_cast<int>(polygon.size());
  auto depthAt = [&s](const Eigen::Vector3d& x) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [normal, offset] : s.wedge) d = std::min(d, offset - normal.dot(x));
    return d;
  };
  // The depth is the least of linear functions, concave over the polygon: it is largest
  // at a corner of the polygon's division into the regions where one plane is the
  // nearest. Such a corner is a corner of the polygon, a point of its side where two
  // planes are equally near, or a point inside where three are. Every candidate lies in
  // the polygon, so none can read deeper than the deepest point.
  double deepest = 0.0;
  for (const Eigen::Vector3d& x : polygon) deepest = std::max(deepest, depthAt(x));
  if (planes == 1) return deepest;  // behind q alone the depth is linear
  for (int c = 0; c < corners; ++c) {
    const Eigen::Vector3d& a = polygon[c];
    const Eigen::Vector3d side = polygon[(c + 1) % corners] - a;
    for (int i = 0; i < planes; ++i)
      for (int j = i + 1; j < planes; ++j) {
        // f_i - f_j along a + t side, t in (0, 1): zero where the two are equally near.
        const Eigen::Vector3d dn = s.wedge[j].first - s.wedge[i].first;
        const double at0 = s.wedge[i].second - s.wedge[j].second + dn.dot(a), slope = dn.dot(side);
        if (slope == 0.0) continue;
        const double t = -at0 / slope;
        if (t > 0.0 && t < 1.0) deepest = std::max(deepest, depthAt(a + t * side));
      }
  }
  Eigen::Vector3d areaNormal = Eigen::Vector3d::Zero();  // Newell's: twice the area along the normal
  for (int c = 0; c < corners; ++c) areaNormal += polygon[c].cross(polygon[(c + 1) % corners]);
  if (corners < 3 || areaNormal.squaredNorm() == 0.0) return deepest;
  const Eigen::Vector3d normal = areaNormal.normalized();
  auto inside = [&](const Eigen::Vector3d& x) {
    for (int c = 0; c < corners; ++c)
      if ((polygon[(c + 1) % corners] - polygon[c]).cross(x - polygon[c]).dot(normal) < 0.0) return false;
    return true;
  };
  for (int i = 0; i < planes; ++i)
    for (int j = i + 1; j < planes; ++j)
      for (int k = j + 1; k < planes; ++k) {
        // x in the polygon's plane where f_i = f_j = f_k, by Cramer's rule.
        const Eigen::Vector3d r0 = s.wedge[j].first - s.wedge[i].first, r1 = s.wedge[k].first - s.wedge[i].first;
        const Eigen::Vector3d r1xn = r1.cross(normal), nxr0 = normal.cross(r0), r0xr1 = r0.cross(r1);
        const double det = r0.dot(r1xn);
        if (det == 0.0) continue;  // the points where all three agree form a line or none: see the sides
        const double b0 = s.wedge[j].second - s.wedge[i].second, b1 = s.wedge[k].second - s.wedge[i].second;
        const Eigen::Vector3d x = (b0 * r1xn + b1 * nxr0 + normal.dot(polygon[0]) * r0xr1) / det;
        if (inside(x)) deepest = std::max(deepest, depthAt(x));
      }
  return deepest;
}

}  // namespace polysim::collision
