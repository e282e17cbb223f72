#pragma once
// Convex polygons in a plane: clipping, hulls, areas. The plane's 2D coordinates come
// from a PlaneFrame; every polygon here is counter-clockwise in those coordinates.

#include <Eigen/Geometry>
#include <vector>

namespace polysim::collision {

using Polygon2 = std::vector<Eigen::Vector2d>;

/// An orthonormal frame on a plane: u x v = normal. Points are shifted to `origin` before
/// projecting, so that 2D coordinates stay small and round-off stays small (Box2D habit).
struct PlaneFrame {
  Eigen::Vector3d origin, u, v, normal;
  PlaneFrame(const Eigen::Vector3d& origin, const Eigen::Vector3d& unitNormal);
  Eigen::Vector2d to2d(const Eigen::Vector3d& p) const { return {u.dot(p - origin), v.dot(p - origin)}; }
  Eigen::Vector3d to3d(const Eigen::Vector2d& q) const { return origin + q.x() * u + q.y() * v; }
};

/// 2D cross product (z of the 3D one): positive when b is counter-clockwise from a.
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double signedArea(const Polygon2& poly);
double perimeter(const Polygon2& poly);

/// subject ∩ clipper for two convex counter-clockwise polygons (Sutherland-Hodgman: clip
/// the subject by the half-plane left of each clipper edge in turn). Empty, or a polygon
/// that may be degenerate (zero area) when they only touch.
Polygon2 clipConvex(const Polygon2& subject, const Polygon2& clipper);
/// The same into `out`, with `work` as scratch: no allocation once both have grown.
void clipConvex(const Polygon2& subject, const Polygon2& clipper, Polygon2& out, Polygon2& work);

/// Keeps the part of segment [a, b] inside `convex` grown outwards by `grow` (m):
/// every edge's half-plane moved out by `grow`. Returns false when nothing is left. An
/// end inside is left exactly as it was.
bool clipSegment(const Polygon2& convex, double grow, Eigen::Vector2d& a, Eigen::Vector2d& b);

/// The part of polygon `in` (3D, planar) where normal . x <= offset, into `out` (one
/// Sutherland-Hodgman step in space). Empty when nothing is left.
void clipBelow(const std::vector<Eigen::Vector3d>& in, const Eigen::Vector3d& normal, double offset,
               std::vector<Eigen::Vector3d>& out);

/// Distance from p to a convex counter-clockwise polygon: 0 inside, else to the boundary.
double distanceToConvex(const Polygon2& convex, const Eigen::Vector2d& p);

/// The point of segment [a, b] nearest to a convex counter-clockwise polygon (exact when
/// the segment does not cross it: the nearest pair then has an end of the segment or a
/// corner of the polygon in it).
Eigen::Vector2d nearestPointToConvex(const Polygon2& convex, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
Polygon2 convexHull(std::vector<Eigen::Vector2d> points);

}  // namespace polysim::collision
