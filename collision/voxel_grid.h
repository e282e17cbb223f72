#pragma once
// Garcia-Alonso et al. 1994's per-object voxel grid: the object's container (its box in
// its own frame) is halved along its longest side M times, giving 2^M voxels, and each
// voxel lists the faces whose bounding box meets it. Because the grid is made by
// successive halvings, level m of that sequence (m = 0..M) is itself a grid whose cells
// each split in two at level m+1: the levels form an implicit binary tree, which the
// broad phase descends two objects at a time. Each cell keeps the tight box of what it
// holds (its faces' boxes clipped to the cell), so empty space prunes early.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// A cell of level `level`, by its integer coordinates in that level's grid.
struct VoxelCell {
  int level = 0;
  Eigen::Array3i index = Eigen::Array3i::Zero();
};

class VoxelGrid {
 public:
  /// Most halvings a grid may be asked for (2^31 cells would overflow its indices; far
  /// beyond what memory allows anyway).
  static constexpr int kMostHalvings = 30;

  /// Builds the grid of `mesh` with M = `halvings` in [0, kMostHalvings] (else throws
  /// std::invalid_argument). The container is the mesh's bounds grown by `padding` (m)
  /// so that flat objects still have a thickness to divide.
  VoxelGrid(const PolygonMesh& mesh, int halvings, double padding);

  /// M for a mesh: voxels holding about kFacesPerVoxel faces of its surface, clamped to
  /// [kMinVoxelHalvings, kMaxVoxelHalvings].
  static int chooseHalvings(const PolygonMesh& mesh);

  int halvings() const { return static_cast<int>(splitAxis_.size()); }
  const Eigen::AlignedBox3d& container() const { return container_; }
  /// The cell's box in the object's frame.
  Eigen::AlignedBox3d cellBox(const VoxelCell& cell) const;
  /// The box (object frame) of the faces listed in the cell or below it, clipped to the
  /// cell; empty when no face reaches the cell.
  const Eigen::AlignedBox3d& contentBox(const VoxelCell& cell) const { return content_[cell.level][linear(cell)]; }
  bool occupied(const VoxelCell& cell) const { return !contentBox(cell).isEmpty(); }
  bool isLeaf(const VoxelCell& cell) const { return cell.level == halvings(); }
  /// The two halves of a non-leaf cell.
  void children(const VoxelCell& cell, VoxelCell& first, VoxelCell& second) const;
  /// The faces listed in a leaf voxel: [begin, end) into faceIndices().
  const int* facesBegin(const VoxelCell& leaf) const { return faces_.data() + start_[linear(leaf)]; }
  const int* facesEnd(const VoxelCell& leaf) const { return faces_.data() + start_[linear(leaf) + 1]; }
  /// Total number of (voxel, face) entries: the grid's memory in ints.
  size_t entryCount() const { return faces_.size(); }

 private:
  int linear(const VoxelCell& c) const {
    const Eigen::Array3i& n = dims_[c.level];
    return c.index.x() + n.x() * (c.index.y() + n.y() * c.index.z());
  }

  Eigen::AlignedBox3d container_;
  std::vector<int> splitAxis_;                      // axis doubled going from level m to m+1
  std::vector<Eigen::Array3i> dims_;                // cells per axis at each level
  std::vector<std::vector<Eigen::AlignedBox3d>> content_;  // per level, per cell
  std::vector<int> start_;                          // CSR offsets per leaf voxel
  std::vector<int> faces_;
};

}  // namespace polysim::collision
