#include "collision/thickness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "collision/clip.h"

namespace polysim::collision {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Ray o + s d, s in (0, limit): does it cross the box? (slab test)
bool rayMeetsBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double limit, const Eigen::AlignedBox3d& box) {
  double lo = 0.0, hi = limit;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < box.min()[k] || o[k] > box.max()[k]) return false;
      continue;
    }
    double s0 = (box.min()[k] - o[k]) / d[k], s1 = (box.max()[k] - o[k]) / d[k];
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0);
    hi = std::min(hi, s1);
    if (lo > hi) return false;
  }
  return true;
}

// Distance along the ray to face f, or infinity when it misses.
double rayHitsFace(const PolygonMesh& mesh, int f, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const Plane& plane = mesh.facePlane(f);
  const double along = plane.normal.dot(d);
  if (along == 0.0) return kInfinity;
  const double s = -plane.signedDistance(o) / along;
  if (!(s > 0.0)) return kInfinity;
  const Eigen::Vector3d x = o + s * d;
  const PlaneFrame frame(x, plane.normal);
  Polygon2 poly;
  for (int i = 0; i < mesh.faceSize(f); ++i) poly.push_back(frame.to2d(mesh.vertices()[mesh.faceVertices(f)[i]]));
  return distanceToConvex(poly, Eigen::Vector2d::Zero()) == 0.0 ? s : kInfinity;
}

}  // namespace

double minimumThickness(const PolygonMesh& mesh, const VoxelGrid& grid) {
  double thinnest = kInfinity;
  std::vector<VoxelCell> stack;
  for (int f = 0; f < mesh.faceCount(); ++f) {
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
    for (int i = 0; i < mesh.faceSize(f); ++i) o += mesh.vertices()[mesh.faceVertices(f)[i]];
    o /= mesh.faceSize(f);
    const Eigen::Vector3d d = -mesh.facePlane(f).normal;
    double nearest = kInfinity;
    stack.assign(1, VoxelCell{});
    while (!stack.empty()) {
      const VoxelCell cell = stack.back();
      stack.pop_back();
      const double limit = std::min(nearest, thinnest);  // nothing farther can matter
      if (!grid.occupied(cell) || !rayMeetsBox(o, d, limit, grid.contentBox(cell))) continue;
      if (!grid.isLeaf(cell)) {
        VoxelCell a, b;
        grid.children(cell, a, b);
        stack.push_back(a);
        stack.push_back(b);
        continue;
      }
      for (const int* g = grid.facesBegin(cell); g != grid.facesEnd(cell); ++g)
        if (*g != f) nearest = std::min(nearest, rayHitsFace(mesh, *g, o, d));
    }
    thinnest = std::min(thinnest, nearest);
  }
  return thinnest;
}

}  // namespace polysim::collision
