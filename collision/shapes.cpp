#include "collision/shapes.h"

#include <cmath>
#include <map>
#include <utility>

namespace polysim::collision {

MeshData makeBox(const Eigen::Vector3d& size) {
  const Eigen::Vector3d h = 0.5 * size;
  MeshData m;
  for (int i = 0; i < 8; ++i)  // bit 0: +x, bit 1: +y, bit 2: +z
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  m.faces = {{0, 2, 3, 1},   // -z
             {4, 5, 7, 6},   // +z
             {0, 1, 5, 4},   // -y
             {2, 6, 7, 3},   // +y
             {0, 4, 6, 2},   // -x
             {1, 3, 7, 5}};  // +x
  return m;
}

MeshData makeIcosphere(double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  MeshData m;
  m.vertices = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (auto& v : m.vertices) v.normalize();
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      auto [it, inserted] = midpoint.try_emplace(std::minmax(a, b), static_cast<int>(m.vertices.size()));
      if (inserted) m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return it->second;
    };
    std::vector<std::vector<int>> faces;
    faces.reserve(4 * m.faces.size());
    for (const auto& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({f[1], bc, ab});
      faces.push_back({f[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    m.faces = std::move(faces);
  }
  for (auto& v : m.vertices) v *= radius;
  return m;
}

MeshData makeTriangulatedFloor(double sx, double sy, int k) {
  MeshData m;
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i <= k; ++i)
      m.vertices.emplace_back(sx * (static_cast<double>(i) / k - 0.5), sy * (static_cast<double>(j) / k - 0.5), 0.0);
  auto id = [k](int i, int j) { return j * (k + 1) + i; };
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace polysim::collision
