#include "collision/convex_separation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Candidate axes, held without allocating, one array per coordinate: every step below
// is a loop over the axes that the compiler vectorizes. Axes need not be unit length;
// the gaps are divided by their lengths at the end.
constexpr int kMaxAxes = 2 * kMaxSeparatingDirections + kMaxSeparatingDirections * kMaxSeparatingDirections;
struct Axes {
  int count = 0;
  double x[kMaxAxes], y[kMaxAxes], z[kMaxAxes];
  void add(const Eigen::Vector3d& n) { x[count] = n.x(), y[count] = n.y(), z[count] = n.z(), ++count; }
  Eigen::Vector3d operator[](int k) const { return {x[k], y[k], z[k]}; }
  // The same axes expressed in a frame rotated by R from this one: R^T axis.
  void rotatedInto(const Eigen::Matrix3d& R, Axes& out) const {
    out.count = count;
    for (int k = 0; k < count; ++k) {
      out.x[k] = R(0, 0) * x[k] + R(1, 0) * y[k] + R(2, 0) * z[k];
      out.y[k] = R(0, 1) * x[k] + R(1, 1) * y[k] + R(2, 1) * z[k];
      out.z[k] = R(0, 2) * x[k] + R(1, 2) * y[k] + R(2, 2) * z[k];
    }
  }
};

// The least and greatest level of the mesh's vertices along each axis.
void extents(const PolygonMesh& mesh, const Axes& axes, double* lo, double* hi) {
  const auto& vertices = mesh.vertices();
  const int n = axes.count;
  if (vertices.size() > PolygonMesh::kScanUpTo) {  // climb, axis by axis
    for (int k = 0; k < n; ++k) std::tie(lo[k], hi[k]) = mesh.extentAlong(axes[k]);
    return;
  }
  std::fill(lo, lo + n, kInfinity);
  std::fill(hi, hi + n, -kInfinity);
  const bool mirrored = !mesh.mirroredHalf().empty();
  for (const Eigen::Vector3d& v : mirrored ? mesh.mirroredHalf() : vertices)
    for (int k = 0; k < n; ++k) {
      const double level = axes.x[k] * v.x() + axes.y[k] * v.y() + axes.z[k] * v.z();
      lo[k] = std::min(lo[k], level);
      hi[k] = std::max(hi[k], level);
    }
  if (!mirrored) return;
  // The mirror of a vertex at level l lies at 2 c - l, c the centre's level.
  const Eigen::Vector3d& c = mesh.centre();
  for (int k = 0; k < n; ++k) {
    const double twice = 2.0 * (axes.x[k] * c.x() + axes.y[k] * c.y() + axes.z[k] * c.z());
    const double mirroredLo = twice - hi[k], mirroredHi = twice - lo[k];
    lo[k] = std::min(lo[k], mirroredLo);
    hi[k] = std::max(hi[k], mirroredHi);
  }
}

}  // namespace

std::optional<double> convexSeparation(const ObjNode& a, const ObjNode& b) {
  const PolygonMesh& meshA = *a.mesh;
  const PolygonMesh& meshB = *b.mesh;
  if (!hasSeparatingAxes(meshA) || !hasSeparatingAxes(meshB)) return std::nullopt;
  // The axes in a's frame: a's face normals, b's, and the cross products of an edge
  // direction of each.
  const Eigen::Matrix3d R_AB = a.X_WO.linear().transpose() * b.X_WO.linear();
  const Eigen::Vector3d p_AB = a.X_WO.linear().transpose() * (b.X_WO.translation() - a.X_WO.translation());
  Axes axes;
  for (const Eigen::Vector3d& n : meshA.faceDirections()) axes.add(n);
  for (const Eigen::Vector3d& n : meshB.faceDirections()) axes.add(R_AB * n);
  Eigen::Vector3d edgesB[kMaxSeparatingDirections];
  const int countB = static_cast<int>(meshB.edgeDirections().size());
  for (int j = 0; j < countB; ++j) edgesB[j] = R_AB * meshB.edgeDirections()[j];
  for (const Eigen::Vector3d& u : meshA.edgeDirections())
    for (int j = 0; j < countB; ++j) axes.add(u.cross(edgesB[j]));
  Axes axesInB;
  axes.rotatedInto(R_AB, axesInB);

  double loA[kMaxAxes], hiA[kMaxAxes], loB[kMaxAxes], hiB[kMaxAxes];
  extents(meshA, axes, loA, hiA);
  extents(meshB, axesInB, loB, hiB);
  // Along each axis the wider gap of the two orders (b beyond a, or a beyond b); b's
  // levels are shifted by where its origin lies. The cross product of parallel edge
  // directions (unit vectors, so its length is the sine between them) is no axis.
  double widest = -kInfinity;
  for (int k = 0; k < axes.count; ++k) {
    const double length = std::sqrt(axes.x[k] * axes.x[k] + axes.y[k] * axes.y[k] + axes.z[k] * axes.z[k]);
    const double shift = axes.x[k] * p_AB.x() + axes.y[k] * p_AB.y() + axes.z[k] * p_AB.z();
    const double gap = std::max(loB[k] + shift - hiA[k], loA[k] - hiB[k] - shift) / length;
    widest = std::max(widest, length > kParallelSine ? gap : -kInfinity);
  }
  return widest;
}

}  // namespace polysim::collision
