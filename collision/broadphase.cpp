#include "collision/broadphase.h"

#include <algorithm>
#include <utility>

#include "collision/aabb.h"

namespace polysim::collision {

Eigen::AlignedBox3d worldContainer(const ObjNode& object) {
  return transformBox(object.X_WO, object.grid->container());
}

std::optional<Eigen::AlignedBox3d> overlapRegion(const ObjNode& a, const ObjNode& b, double eps) {
  const Eigen::AlignedBox3d region = grow(worldContainer(a), eps).intersection(grow(worldContainer(b), eps));
  if (region.isEmpty()) return std::nullopt;
  return region;
}

void candidatePolygonPairs(const ObjNode& a, WorldFaces& facesA, const ObjNode& b, WorldFaces& facesB,
                           const Eigen::AlignedBox3d& region, double eps, DescentScratch& scratch,
                           std::vector<FacePair>& pairs) {
  pairs.clear();
  forEachCandidatePair(a, facesA, b, facesB, region, eps, scratch, [&pairs](int fa, int fb) {
    pairs.push_back({fa, fb});
    return true;
  });
  auto key = [](const FacePair& p) { return std::pair(p.a, p.b); };
  std::sort(pairs.begin(), pairs.end(), [&](const FacePair& x, const FacePair& y) { return key(x) < key(y); });
  pairs.erase(std::unique(pairs.begin(), pairs.end(), [&](const FacePair& x, const FacePair& y) { return key(x) == key(y); }),
              pairs.end());
}

}  // namespace polysim::collision
