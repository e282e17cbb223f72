#include "collision/polygon_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/segment_distance.h"

namespace polysim::collision {
namespace {

// The least signed distance of p's vertices from the plane: how far p lies wholly in
// front of it (negative when p reaches behind).
double lowestAbove(const PolygonView& p, const Plane& plane) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < p.size; ++i) lowest = std::min(lowest, plane.signedDistance(p.vertices[i]));
  return lowest;
}

// Distance from the vertices of p to face q, for the vertices that project inside q.
double verticesToFace(const PolygonView& p, const PolygonView& q, PolygonScratch& s) {
  const PlaneFrame frame(q.vertices[0], q.plane.normal);
  s.q2.resize(q.size);
  for (int k = 0; k < q.size; ++k) s.q2[k] = frame.to2d(q.vertices[k]);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < p.size; ++i)
    if (distanceToConvex(s.q2, frame.to2d(p.vertices[i])) == 0.0)
      best = std::min(best, std::abs(q.plane.signedDistance(p.vertices[i])));
  return best;
}

// True when an edge of p passes through q (its ends on opposite sides of q's plane and
// the crossing inside q).
bool edgePierces(const PolygonView& p, const PolygonView& q, PolygonScratch& s) {
  const PlaneFrame frame(q.vertices[0], q.plane.normal);
  s.q2.resize(q.size);
  for (int k = 0; k < q.size; ++k) s.q2[k] = frame.to2d(q.vertices[k]);
  for (int i = 0; i < p.size; ++i) {
    const Eigen::Vector3d& a = p.vertices[i];
    const Eigen::Vector3d& b = p.vertices[(i + 1) % p.size];
    const double da = q.plane.signedDistance(a), db = q.plane.signedDistance(b);
    if ((da < 0) == (db < 0)) continue;
    const Eigen::Vector3d x = a + (da / (da - db)) * (b - a);
    if (distanceToConvex(s.q2, frame.to2d(x)) == 0.0) return true;
  }
  return false;
}

}  // namespace

double polygonDistance(const PolygonView& p, const PolygonView& q, PolygonScratch& s, double least) {
  const double gap = std::max(lowestAbove(p, q.plane), lowestAbove(q, p.plane));
  if (gap >= least) return gap;
  if (edgePierces(p, q, s) || edgePierces(q, p, s)) return 0.0;
  double best = std::min(verticesToFace(p, q, s), verticesToFace(q, p, s));
  for (int i = 0; i < p.size; ++i)
    for (int j = 0; j < q.size; ++j)
      best = std::min(best, closestPointsOnSegments(p.vertices[i], p.vertices[(i + 1) % p.size] - p.vertices[i],
                                                    q.vertices[j], q.vertices[(j + 1) % q.size] - q.vertices[j])
                                .distance);
  return best;
}

}  // namespace polysim::collision
