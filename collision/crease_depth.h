#pragma once
// How deep one polygon lies inside an object that is not convex (no separating axis test
// can say; see testPolygonPair), near the object's creases. Near a convex crease (an
// edge where the object's two faces fold outward: a box's edges, a cup's rim) the
// object is the wedge between the two faces, and a point inside it leaves through the
// nearer of the two planes. Reflex creases (a cup's inner corners), flat edges (inside a
// triangulated plane) and open boundaries bound nothing: the object goes on behind.

#include <vector>

#include <Eigen/Core>

#include "collision/polygon_tests.h"

namespace polysim::collision {

/// The unit normal (world) of the face across side k of q, from the side's outward
/// direction, which bisects the two faces' normals.
Eigen::Vector3d neighbourNormal(const PolygonView& q, int k);

/// True when side k of q is a convex crease: the face across it turns away from q's
/// side by more than kFlatEdgeAngle (classified once, with the mesh).
bool convexCrease(const PolygonView& q, int k);

/// How deep (m) the deepest point of `polygon` (planar, convex, behind q's plane and over
/// q) lies inside q's object: the largest over the polygon of the least of a point's
/// depths behind q and behind the face across each convex crease of q; 0 when no point
/// is behind them all. Exact up to rounding (no search).
double deepestInWedge(const PolygonView& q, const std::vector<Eigen::Vector3d>& polygon, PolygonScratch& scratch);

/// The deepest crossing (m) of a convex crease of p with a convex crease of q: two such
/// edges whose closest points lie inside both segments, each point inside the other
/// edge's wedge, at a distance (the gap an edge-edge contact measures, along their
/// common normal) up to kCrossingReach * eps. 0 when there is none. Closest points at
/// an end, or nearer than their distance to an end where a third face caps the wedge
/// (the polygon's side there is a convex crease), are left to the vertex there;
/// parallel edges to line contacts.
double deepestCrossing(const PolygonView& p, const PolygonView& q, double eps);

}  // namespace polysim::collision
