#pragma once
// Distance between two convex polygons in space, for the time-of-contact root finder.

#include <limits>

#include "collision/polygon_tests.h"

namespace polysim::collision {

/// The distance (m) between polygons p and q when they do not intersect: the least of
/// each vertex's distance to the other face (when it projects inside it) and of the
/// edge-edge distances, which is exact for convex polygons. 0 when they intersect.
/// A caller keeping the least distance of many pairs passes it as `least`: when one
/// polygon lies wholly beyond the other's plane by at least that much, the distance
/// cannot beat it and that gap (a lower bound, >= least) is returned at once.
double polygonDistance(const PolygonView& p, const PolygonView& q, PolygonScratch& scratch,
                       double least = std::numeric_limits<double>::infinity());

}  // namespace polysim::collision
