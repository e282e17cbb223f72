#pragma once
// The signed separation of two convex objects by the separating axis test: a cheap,
// continuous measure whose zero is the moment they touch, for collisionDetect()'s
// root finder.

#include <optional>

#include "collision/object.h"

namespace polysim::collision {

/// True when the mesh lists its separating directions (convex, and few of them), so
/// that convexSeparation() can measure it.
inline bool hasSeparatingAxes(const PolygonMesh& mesh) { return !mesh.faceDirections().empty(); }

/// Signed separation (m) of convex objects a and b at their current poses, over the
/// axes of the separating axis test (each one's face normals, and cross products of an
/// edge direction of each). Apart: the widest gap along those axes, a lower bound on
/// their distance (equal to it when the nearest features are a face and a vertex or
/// two crossing edges). Overlapping: minus the least translation that parts them (the
/// penetration depth). Zero exactly when they touch. Empty when either mesh has no
/// separating directions listed (not convex, or too many; see PolygonMesh).
std::optional<double> convexSeparation(const ObjNode& a, const ObjNode& b);

}  // namespace polysim::collision
