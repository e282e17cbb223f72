#pragma once
// Distance between two convex polygons in space, for the time-of-contact root finder.

#include "collision/polygon_tests.h"

namespace polysim::collision {

/// The distance (m) between polygons p and q when they do not intersect: the least of
/// each vertex's distance to the other face (when it projects inside it) and of the
/// edge-edge distances, which is exact for convex polygons. 0 when they intersect.
double polygonDistance(const PolygonView& p, const PolygonView& q, PolygonScratch& scratch);

}  // namespace polysim::collision
