#pragma once
// Polygon meshes drawn from a fuzzer's bytes: boxes, icospheres, closed non-convex star
// prisms (their caps fanned into triangles) and open triangle soups (any faces that
// validateMesh accepts: non-convex, open, thin, degenerate but valid).

#include <fuzzer/FuzzedDataProvider.h>

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "collision/polygon_mesh.h"
#include "collision/shapes.h"

namespace polysim::fuzz {

inline double unitRange(FuzzedDataProvider& bytes, double low, double high) {
  return bytes.ConsumeFloatingPointInRange<double>(low, high);
}

/// A star-shaped prism: k rays of lengths in [0.2, 1] m around the z axis, height h.
inline collision::MeshData starPrism(FuzzedDataProvider& bytes) {
  const int k = bytes.ConsumeIntegralInRange<int>(3, 9);
  const double h = unitRange(bytes, 0.05, 1.0);
  collision::MeshData m;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < k; ++i) {
      const double a = 2 * M_PI * i / k, r = unitRange(bytes, 0.2, 1.0);
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), side ? h / 2 : -h / 2);
    }
  const int bottomCentre = 2 * k, topCentre = 2 * k + 1;
  m.vertices.emplace_back(0, 0, -h / 2);
  m.vertices.emplace_back(0, 0, h / 2);
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    m.faces.push_back({i, j, k + j, k + i});        // side, counter-clockwise seen from outside
    m.faces.push_back({bottomCentre, j, i});         // bottom fan, facing -z
    m.faces.push_back({topCentre, k + i, k + j});    // top fan, facing +z
  }
  return m;
}

/// Triangles over a few vertices, kept only if validateMesh accepts them as an open mesh.
inline std::optional<collision::MeshData> triangleSoup(FuzzedDataProvider& bytes) {
  collision::MeshData m;
  const int n = bytes.ConsumeIntegralInRange<int>(3, 10);
  for (int i = 0; i < n; ++i)
    m.vertices.emplace_back(unitRange(bytes, -1, 1), unitRange(bytes, -1, 1), unitRange(bytes, -1, 1));
  const int faces = bytes.ConsumeIntegralInRange<int>(1, 8);
  for (int f = 0; f < faces; ++f)
    m.faces.push_back({bytes.ConsumeIntegralInRange<int>(0, n - 1), bytes.ConsumeIntegralInRange<int>(0, n - 1),
                       bytes.ConsumeIntegralInRange<int>(0, n - 1)});
  if (!collision::validateMesh(m, false).empty()) return std::nullopt;
  return m;
}

/// One mesh of the four kinds; nullopt when the bytes make no valid one.
inline std::optional<collision::MeshData> anyMesh(FuzzedDataProvider& bytes) {
  switch (bytes.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      return collision::makeBox({unitRange(bytes, 0.01, 2), unitRange(bytes, 0.01, 2), unitRange(bytes, 0.01, 2)});
    case 1: return collision::makeIcosphere(unitRange(bytes, 0.05, 1), bytes.ConsumeIntegralInRange<int>(0, 1));
    case 2: return starPrism(bytes);
    default: return triangleSoup(bytes);
  }
}

/// A pose within 2 m of the origin, any orientation.
inline Eigen::Isometry3d anyPose(FuzzedDataProvider& bytes) {
  Eigen::Quaterniond q(unitRange(bytes, -1, 1), unitRange(bytes, -1, 1), unitRange(bytes, -1, 1), unitRange(bytes, -1, 1));
  if (q.norm() < 1e-6) q = Eigen::Quaterniond::Identity();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(unitRange(bytes, -2, 2), unitRange(bytes, -2, 2), unitRange(bytes, -2, 2));
  return X;
}

}  // namespace polysim::fuzz
