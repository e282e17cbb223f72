#include "collision/broadphase.h"

#include <algorithm>

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
                           const Eigen::AlignedBox3d& region, double eps, std::vector<FacePair>& pairs) {
  std::vector<std::uint64_t> found;
  forEachCandidatePair(a, facesA, b, facesB, region, eps, [&found](int fa, int fb) {
    found.push_back(static_cast<std::uint64_t>(fa) << 32 | static_cast<std::uint32_t>(fb));
    return true;
  });
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  pairs.clear();
  pairs.reserve(found.size());
  for (std::uint64_t key : found) pairs.push_back({static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)});
}

}  // namespace polysim::collision
