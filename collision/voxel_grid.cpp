#include "collision/voxel_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "collision/tolerances.h"

namespace polysim::collision {

VoxelGrid::VoxelGrid(const PolygonMesh& mesh, int halvings, double padding) {
  if (halvings < 0 || halvings > kMostHalvings)
    throw std::invalid_argument("voxel halvings must lie in [0, " + std::to_string(kMostHalvings) + "]");
  container_ = Eigen::AlignedBox3d(mesh.bounds().min().array() - padding, mesh.bounds().max().array() + padding);
  const Eigen::Array3d extent = container_.sizes().array();

  // The halving sequence: each step doubles the axis whose cells are currently longest.
  Eigen::Array3i n = Eigen::Array3i::Ones();
  dims_.push_back(n);
  for (int m = 0; m < halvings; ++m) {
    int axis = 0;
    (extent / n.cast<double>()).maxCoeff(&axis);
    splitAxis_.push_back(axis);
    n[axis] *= 2;
    dims_.push_back(n);
  }

  // Leaf lists in two passes (count, then fill) into one CSR array.
  const Eigen::Array3d cell = extent / n.cast<double>();
  const int leafCount = n.prod();
  auto range = [&](const Eigen::AlignedBox3d& box, Eigen::Array3i& lo, Eigen::Array3i& hi) {
    const Eigen::Array3d a = (box.min() - container_.min()).array() / cell;
    const Eigen::Array3d b = (box.max() - container_.min()).array() / cell;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::clamp(static_cast<int>(std::floor(a[k])), 0, n[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor(b[k])), 0, n[k] - 1);
    }
  };
  start_.assign(leafCount + 1, 0);
  Eigen::Array3i lo, hi;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> cursor;
    if (pass == 1) {
      for (int i = 0; i < leafCount; ++i) start_[i + 1] += start_[i];
      faces_.resize(start_[leafCount]);
      cursor.assign(start_.begin(), start_.end() - 1);
    }
    for (int f = 0; f < mesh.faceCount(); ++f) {
      range(mesh.faceBounds(f), lo, hi);
      for (int z = lo.z(); z <= hi.z(); ++z)
        for (int y = lo.y(); y <= hi.y(); ++y)
          for (int x = lo.x(); x <= hi.x(); ++x) {
            const int id = x + n.x() * (y + n.y() * z);
            if (pass == 0) ++start_[id + 1];
            else faces_[cursor[id]++] = f;
          }
    }
  }

  // Content boxes, from the leaves up: a leaf holds its faces' boxes clipped to it, a
  // parent the union of its halves.
  content_.resize(halvings + 1);
  content_[halvings].assign(leafCount, Eigen::AlignedBox3d());
  for (int z = 0; z < n.z(); ++z)
    for (int y = 0; y < n.y(); ++y)
      for (int x = 0; x < n.x(); ++x) {
        const VoxelCell leaf{halvings, Eigen::Array3i(x, y, z)};
        const int id = linear(leaf);
        if (start_[id] == start_[id + 1]) continue;
        const Eigen::AlignedBox3d cellBounds = cellBox(leaf);
        Eigen::AlignedBox3d& box = content_[halvings][id];
        for (int k = start_[id]; k < start_[id + 1]; ++k) box.extend(mesh.faceBounds(faces_[k]).intersection(cellBounds));
      }
  for (int m = halvings - 1; m >= 0; --m) {
    const Eigen::Array3i& child = dims_[m + 1];
    content_[m].assign(dims_[m].prod(), Eigen::AlignedBox3d());
    const int axis = splitAxis_[m];
    for (int z = 0; z < child.z(); ++z)
      for (int y = 0; y < child.y(); ++y)
        for (int x = 0; x < child.x(); ++x) {
          const Eigen::AlignedBox3d& box = content_[m + 1][x + child.x() * (y + child.y() * z)];
          if (box.isEmpty()) continue;
          Eigen::Array3i parent(x, y, z);
          parent[axis] /= 2;
          content_[m][linear({m, parent})].extend(box);
        }
  }
}

int VoxelGrid::chooseHalvings(const PolygonMesh& mesh) {
  // Aim for leaf voxels that a surface crosses with about kFacesPerVoxel faces: a side
  // sqrt(kFacesPerVoxel) typical faces long. The number of halvings along an axis is
  // log2(extent / voxel side), summed over the axes with room to halve.
  double area = 0.0;
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Eigen::Vector3d d = mesh.faceBounds(f).sizes();
    area += std::max({d.x() * d.y(), d.y() * d.z(), d.x() * d.z()});
  }
  const double side = std::sqrt(area / mesh.faceCount() * kFacesPerVoxel);
  const Eigen::Vector3d extent = mesh.bounds().sizes();
  double m = 0.0;
  for (int k = 0; k < 3; ++k)
    if (extent[k] > side) m += std::log2(extent[k] / side);
  return std::clamp(static_cast<int>(std::lround(m)), kMinVoxelHalvings, kMaxVoxelHalvings);
}

Eigen::AlignedBox3d VoxelGrid::cellBox(const VoxelCell& c) const {
  const Eigen::Array3d cell = container_.sizes().array() / dims_[c.level].cast<double>();
  const Eigen::Vector3d lo = container_.min().array() + c.index.cast<double>() * cell;
  return Eigen::AlignedBox3d(lo, lo + cell.matrix());
}

void VoxelGrid::children(const VoxelCell& c, VoxelCell& first, VoxelCell& second) const {
  const int axis = splitAxis_[c.level];
  first = {c.level + 1, c.index};
  first.index[axis] *= 2;
  second = first;
  second.index[axis] += 1;
}

}  // namespace polysim::collision
