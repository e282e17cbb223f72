#include "collision/containment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/aabb.h"
#include "collision/broadphase.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Directions tried in turn: none parallel to a box's faces or edges, nor to each other's.
const Eigen::Vector3d kRayDirections[] = {Eigen::Vector3d(1.0, std::sqrt(2.0), std::sqrt(3.0)).normalized(),
                                          Eigen::Vector3d(-std::sqrt(5.0), 1.0, std::sqrt(7.0)).normalized(),
                                          Eigen::Vector3d(std::sqrt(11.0), -std::sqrt(3.0), -1.0).normalized()};

enum class Crossing { Miss, Hit, Grazing };

// Does the ray p + t d, t > 0, cross face f (a planar convex polygon)?
Crossing crosses(const PolygonMesh& mesh, int f, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  const Plane& plane = mesh.facePlane(f);
  const double along = plane.normal.dot(d);
  if (along == 0.0) return Crossing::Miss;  // parallel: the neighbouring faces decide
  const double t = -plane.signedDistance(p) / along;
  if (t <= 0.0) return Crossing::Miss;
  const Eigen::Vector3d hit = p + t * d;
  const double size = mesh.faceBounds(f).diagonal().norm();
  const int* v = mesh.faceVertices(f);
  bool grazing = false;
  for (int i = 0, n = mesh.faceSize(f); i < n; ++i) {
    const Eigen::Vector3d& a = mesh.vertices()[v[i]];
    const Eigen::Vector3d edge = mesh.vertices()[v[(i + 1) % n]] - a;
    const double side = edge.cross(hit - a).dot(plane.normal) / std::max(edge.norm(), std::numeric_limits<double>::min());
    if (side < -kGrazingFraction * size) return Crossing::Miss;
    grazing = grazing || side <= kGrazingFraction * size;
  }
  return grazing ? Crossing::Grazing : Crossing::Hit;
}

// Distance from p to the convex polygon f of the mesh (m).
double distanceToFace(const PolygonMesh& mesh, int f, const Eigen::Vector3d& p) {
  const Plane& plane = mesh.facePlane(f);
  const Eigen::Vector3d onPlane = p - plane.signedDistance(p) * plane.normal;
  const int* v = mesh.faceVertices(f);
  double rim = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (int i = 0, n = mesh.faceSize(f); i < n; ++i) {
    const Eigen::Vector3d& a = mesh.vertices()[v[i]];
    const Eigen::Vector3d edge = mesh.vertices()[v[(i + 1) % n]] - a;
    inside = inside && edge.cross(onPlane - a).dot(plane.normal) >= 0.0;
    const double s = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    rim = std::min(rim, (a + s * edge - p).norm());
  }
  return inside ? std::abs(plane.signedDistance(p)) : rim;
}

}  // namespace

bool insideClosedMesh(const PolygonMesh& mesh, const Eigen::Vector3d& p) {
  for (const Eigen::Vector3d& d : kRayDirections) {
    int hits = 0;
    bool grazed = false;
    for (int f = 0; f < mesh.faceCount() && !grazed; ++f) {
      const Crossing c = crosses(mesh, f, p, d);
      grazed = c == Crossing::Grazing;
      hits += c == Crossing::Hit;
    }
    if (!grazed) return hits % 2 == 1;
  }
  return false;  // every direction grazed a rim: p lies on a face's edge, so not inside
}

std::optional<double> containmentDepth(const ObjNode& inner, const ObjNode& outer) {
  if (!outer.mesh->closed() || inner.mesh->vertices().empty()) return std::nullopt;
  if (!worldContainer(outer).contains(worldContainer(inner))) return std::nullopt;
  const Eigen::Isometry3d X_OI = outer.X_WO.inverse() * inner.X_WO;  // inner's frame to outer's
  if (!insideClosedMesh(*outer.mesh, X_OI * inner.mesh->vertices().front())) return std::nullopt;
  double deepest = 0.0;  // every vertex is inside: the deepest one's distance to the surface
  for (const Eigen::Vector3d& v : inner.mesh->vertices()) {
    const Eigen::Vector3d p = X_OI * v;
    double depth = std::numeric_limits<double>::infinity();
    for (int f = 0; f < outer.mesh->faceCount(); ++f) depth = std::min(depth, distanceToFace(*outer.mesh, f, p));
    deepest = std::max(deepest, depth);
  }
  return deepest;
}

}  // namespace polysim::collision
