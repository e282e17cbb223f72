#pragma once
// The broad steps of Garcia-Alonso et al. 1994 for one pair of objects: their containers'
// world boxes and the overlap region, then the voxels of each object inside that region,
// then the pairs of polygons from voxels that meet.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "collision/object.h"
#include "collision/world_faces.h"

namespace polysim::collision {

/// The world box of an object's container at its current pose.
Eigen::AlignedBox3d worldContainer(const ObjNode& object);

/// The region where two objects could be within eps (m) of each other: the intersection
/// of their world container boxes, each grown by eps. Empty optional when they cannot.
std::optional<Eigen::AlignedBox3d> overlapRegion(const ObjNode& a, const ObjNode& b, double eps);

/// The pairs of objects (i < j, not both static) whose boxes (one per object of the
/// database, in any frame they share) meet, by sweep and prune along x: about N log N
/// plus the pairs. Sorted by i, then j.
void overlappingBoxPairs(const ObjectDatabase& db, const std::vector<Eigen::AlignedBox3d>& boxes,
                         std::vector<std::pair<int, int>>& pairs);

/// The pairs of objects (i < j, not both static) whose world containers, each grown by
/// eps (m), meet: those overlapRegion() may find a region for, and no others. Sweep and
/// prune along x, so N objects cost about N log N plus the pairs, not N^2 / 2 box tests.
/// In database order (by i, then j), `boxes` is scratch.
void candidateObjectPairs(const ObjectDatabase& db, std::vector<Eigen::AlignedBox3d>& boxes,
                          std::vector<std::pair<int, int>>& pairs);

/// The same pairs, found among `among` alone (i < j each, sorted) instead of by sweep and
/// prune: for a caller that knows no other pair can be within eps (collisionDetect()'s
/// pairs that can meet in its interval). Costs the pairs given, not the objects.
void candidateObjectPairsAmong(const ObjectDatabase& db, const std::vector<std::pair<int, int>>& among,
                               std::vector<Eigen::AlignedBox3d>& boxes, std::vector<std::pair<int, int>>& pairs);

/// A candidate polygon pair: face `a` of the first object, face `b` of the second.
struct FacePair {
  int a, b;
};

/// The descent's working memory, kept between queries so that they do not allocate.
struct DescentScratch {
  std::vector<std::pair<VoxelCell, VoxelCell>> stack;
  std::vector<int> nearA, nearB;
  std::vector<Eigen::AlignedBox3d> boxesB;  // of nearB's faces
};

/// Calls visit(fa, fb) for every pair of faces whose world boxes, grown by eps, overlap
/// inside `region`, found by descending both voxel grids together (see voxel_grid.h).
/// A pair may be visited more than once (a face lies in several voxels). The descent
/// stops early when visit returns false. `facesA` and `facesB` must be reset() to a, b.
template <class Visit>
void forEachCandidatePair(const ObjNode& a, WorldFaces& facesA, const ObjNode& b, WorldFaces& facesB,
                          const Eigen::AlignedBox3d& region, double eps, DescentScratch& scratch, Visit&& visit);

/// Every candidate pair once, sorted by face of a, then face of b.
void candidatePolygonPairs(const ObjNode& a, WorldFaces& facesA, const ObjNode& b, WorldFaces& facesB,
                           const Eigen::AlignedBox3d& region, double eps, DescentScratch& scratch,
                           std::vector<FacePair>& pairs);

}  // namespace polysim::collision

#include "collision/broadphase_descent.h"
