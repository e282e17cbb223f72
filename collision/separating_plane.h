#pragma once
// A quick proof that two objects are apart: a plane between them. Garcia-Alonso's broad
// steps prune by boxes, which fit curved surfaces loosely: two spheres a little apart
// keep thousands of voxel pairs whose boxes come close. A plane across the line between
// the objects' containers settles such a pair by looking only at the cells of each
// object that reach towards the plane.

#include "collision/object.h"

namespace polysim::collision {

/// A vertex level close to the top of the object along d: the returned value is d . x of
/// a vertex x, and no vertex lies higher than it by more than `slack` (d and x in the
/// object's frame, m). Branch and bound over the voxel grid: a cell whose content box
/// cannot beat the best vertex so far by more than the slack is skipped, so a large
/// slack looks at few cells. `known` is a level some vertex is known to reach (-inf if
/// none), which prunes from the start.
double topLevelAlong(const ObjNode& object, const Eigen::Vector3d& d, double slack, double known);

/// True when a and b are more than eps (m) apart along the unit world direction from a's
/// container centre to b's: every point of b lies farther along it than every point of
/// a, by more than eps, so no two points come within eps. False says nothing (the
/// objects may still be apart, for example non-convex ones nested in each other).
bool separatedAlongCentreLine(const ObjNode& a, const ObjNode& b, double eps);

}  // namespace polysim::collision
