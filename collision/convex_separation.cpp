#include "collision/convex_separation.h"

#include <algorithm>

#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Every candidate axis of two meshes at their limit, one per row, held without
// allocating; rows so that each coordinate of all axes is contiguous (vectorizes).
constexpr int kMaxAxes = 2 * kMaxSeparatingDirections + kMaxSeparatingDirections * kMaxSeparatingDirections;
using Axes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, kMaxAxes, 3>;
using Levels = Eigen::Array<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxAxes, 1>;

// The least and greatest level of the mesh's vertices along each axis (rows).
void extents(const PolygonMesh& mesh, const Axes& axes, Levels& lo, Levels& hi) {
  const auto& vertices = mesh.vertices();
  if (vertices.size() > PolygonMesh::kScanUpTo) {  // climb, axis by axis
    lo.resize(axes.rows());
    hi.resize(axes.rows());
    for (int k = 0; k < axes.rows(); ++k) std::tie(lo[k], hi[k]) = mesh.extentAlong(axes.row(k).transpose());
    return;
  }
  auto levelsOf = [&axes](const Eigen::Vector3d& v) {
    return axes.col(0).array() * v.x() + axes.col(1).array() * v.y() + axes.col(2).array() * v.z();
  };
  lo = levelsOf(vertices.front());
  hi = lo;
  for (const Eigen::Vector3d& v : vertices) {
    const Levels level = levelsOf(v);
    lo = lo.min(level);
    hi = hi.max(level);
  }
}

}  // namespace

std::optional<double> convexSeparation(const ObjNode& a, const ObjNode& b) {
  const PolygonMesh& meshA = *a.mesh;
  const PolygonMesh& meshB = *b.mesh;
  if (!hasSeparatingAxes(meshA) || !hasSeparatingAxes(meshB)) return std::nullopt;
  // The axes in a's frame: a's face normals, b's, and the cross products of an edge
  // direction of each (skipping parallel pairs).
  const Eigen::Matrix3d R_AB = a.X_WO.linear().transpose() * b.X_WO.linear();
  const Eigen::Vector3d p_AB = a.X_WO.linear().transpose() * (b.X_WO.translation() - a.X_WO.translation());
  const int most = static_cast<int>(meshA.faceDirections().size() + meshB.faceDirections().size() +
                                    meshA.edgeDirections().size() * meshB.edgeDirections().size());
  Axes axes(most, 3);
  int count = 0;
  for (const Eigen::Vector3d& n : meshA.faceDirections()) axes.row(count++) = n.transpose();
  for (const Eigen::Vector3d& n : meshB.faceDirections()) axes.row(count++) = (R_AB * n).transpose();
  for (const Eigen::Vector3d& u : meshA.edgeDirections())
    for (const Eigen::Vector3d& v : meshB.edgeDirections()) {
      const Eigen::Vector3d axis = u.cross(R_AB * v);
      if (axis.norm() > kParallelSine) axes.row(count++) = axis.normalized().transpose();
    }
  axes.conservativeResize(count, Eigen::NoChange);
  // Along each axis the wider gap of the two orders (b beyond a, or a beyond b); b's
  // levels are measured in b's frame and shifted by where its origin lies.
  Levels loA, hiA, loB, hiB;
  extents(meshA, axes, loA, hiA);
  const Axes axesInB = axes * R_AB;  // row k: (R_AB^T n_k)^T
  extents(meshB, axesInB, loB, hiB);
  const Levels shift = (axes * p_AB).array();
  return (loB + shift - hiA).max(loA - hiB - shift).maxCoeff();
}

}  // namespace polysim::collision
