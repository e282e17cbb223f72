#pragma once
// The simultaneous descent of two voxel grids (template body of forEachCandidatePair,
// declared in broadphase.h).

#include <utility>
#include <vector>

#include "collision/aabb.h"

namespace polysim::collision {
namespace detail {

// True when box `a` (frame A, grown by eps) and box `b` (frame B) may overlap, tested on
// the axes of both frames: b placed in A's frame against a, then a placed in B's frame
// against b (six of the fifteen separating axes of two boxes).
inline bool mayOverlap(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b, const Eigen::Isometry3d& X_AB,
                       const Eigen::Matrix3d& absR_AB, const Eigen::Isometry3d& X_BA, double eps) {
  const Eigen::Vector3d ha = 0.5 * a.sizes(), hb = 0.5 * b.sizes();
  const Eigen::Vector3d bInA = X_AB * b.center(), hbInA = absR_AB * hb;
  if (((bInA - a.center()).cwiseAbs() - ha - hbInA).maxCoeff() > eps) return false;
  const Eigen::Vector3d aInB = X_BA * a.center(), haInB = absR_AB.transpose() * ha;
  return ((aInB - b.center()).cwiseAbs() - hb - haInB).maxCoeff() <= eps;
}

}  // namespace detail

template <class Visit>
void forEachCandidatePair(const ObjNode& a, WorldFaces& facesA, const ObjNode& b, WorldFaces& facesB,
                          const Eigen::AlignedBox3d& region, double eps, DescentScratch& scratch, Visit&& visit) {
  const VoxelGrid& gridA = *a.grid;
  const VoxelGrid& gridB = *b.grid;
  const Eigen::Isometry3d X_AB = a.X_WO.inverse() * b.X_WO;
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  const Eigen::Matrix3d absR_AB = X_AB.linear().cwiseAbs();
  // The overlap region seen from each object's own frame, so cells are tested untransformed.
  const Eigen::AlignedBox3d regionA = transformBox(a.X_WO.inverse(), region);
  const Eigen::AlignedBox3d regionB = transformBox(b.X_WO.inverse(), region);
  auto inRegion = [](const VoxelGrid& grid, const VoxelCell& cell, const Eigen::AlignedBox3d& r) {
    const Eigen::AlignedBox3d& box = grid.contentBox(cell);
    return !box.isEmpty() && box.intersects(r);
  };

  auto& [stack, nearA, nearB, boxesB] = scratch;
  stack.clear();
  if (inRegion(gridA, {}, regionA) && inRegion(gridB, {}, regionB)) stack.push_back({VoxelCell{}, VoxelCell{}});
  // A pair of cells is kept while both hold faces inside the overlap region and their
  // content boxes come within eps of each other. A point of A within eps of a point of B
  // lies in the region and in a cell of each that passes these tests, so nothing is lost.
  while (!stack.empty()) {
    const auto [cellA, cellB] = stack.back();
    stack.pop_back();
    const Eigen::AlignedBox3d& boxA = gridA.contentBox(cellA);
    const Eigen::AlignedBox3d& boxB = gridB.contentBox(cellB);
    if (!detail::mayOverlap(boxA, boxB, X_AB, absR_AB, X_BA, eps)) continue;
    const bool leafA = gridA.isLeaf(cellA), leafB = gridB.isLeaf(cellB);
    if (leafA && leafB) {
      // Each leaf's faces that reach the other leaf's content (world boxes, within the
      // region), then every pair of those: coarse leaves hold many faces, and most of
      // them lie away from the other leaf.
      const Eigen::AlignedBox3d reachA = grow(transformBox(a.X_WO, boxA), eps).intersection(region);
      const Eigen::AlignedBox3d reachB = grow(transformBox(b.X_WO, boxB), eps).intersection(region);
      // The boxes are copied side by side: the pair loop then reads them in order.
      nearA.clear();
      nearB.clear();
      boxesB.clear();
      for (const int* fa = gridA.facesBegin(cellA); fa != gridA.facesEnd(cellA); ++fa)
        if (grow(facesA.box(*fa), eps).intersects(reachB)) nearA.push_back(*fa);
      for (const int* fb = gridB.facesBegin(cellB); fb != gridB.facesEnd(cellB); ++fb)
        if (const Eigen::AlignedBox3d& box = facesB.box(*fb); box.intersects(reachA)) {
          nearB.push_back(*fb);
          boxesB.push_back(box);
        }
      for (const int fa : nearA) {
        const Eigen::AlignedBox3d boxFa = grow(facesA.box(fa), eps);
        for (size_t k = 0; k < nearB.size(); ++k)
          if (boxFa.intersects(boxesB[k]) && !visit(fa, nearB[k])) return;
      }
      continue;
    }
    // Split the larger of the two cells (or the one that still can be split).
    const bool splitA = leafB || (!leafA && boxA.sizes().maxCoeff() >= boxB.sizes().maxCoeff());
    VoxelCell halves[2];
    if (splitA) {
      gridA.children(cellA, halves[0], halves[1]);
      for (const VoxelCell& h : halves)
        if (inRegion(gridA, h, regionA)) stack.push_back({h, cellB});
    } else {
      gridB.children(cellB, halves[0], halves[1]);
      for (const VoxelCell& h : halves)
        if (inRegion(gridB, h, regionB)) stack.push_back({cellA, h});
    }
  }
}

}  // namespace polysim::collision
