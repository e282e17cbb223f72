#include "collision/broadphase.h"

#include <algorithm>
#include <utility>

#include "collision/aabb.h"

namespace polysim::collision {

Eigen::AlignedBox3d worldContainer(const ObjNode& object) {
  return transformBox(object.X_WO, object.grid->container());
}

void overlappingBoxPairs(const ObjectDatabase& db, const std::vector<Eigen::AlignedBox3d>& boxes,
                         std::vector<std::pair<int, int>>& pairs) {
  std::vector<int> order(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int i, int j) { return boxes[i].min().x() < boxes[j].min().x(); });
  pairs.clear();
  for (size_t k = 0; k < order.size(); ++k)
    for (size_t m = k + 1; m < order.size() && boxes[order[m]].min().x() <= boxes[order[k]].max().x(); ++m) {
      const int i = std::min(order[k], order[m]), j = std::max(order[k], order[m]);
      if ((db.objects[i].isStatic && db.objects[j].isStatic) || !boxes[i].intersects(boxes[j])) continue;
      pairs.emplace_back(i, j);
    }
  std::sort(pairs.begin(), pairs.end());
}

void candidateObjectPairs(const ObjectDatabase& db, std::vector<Eigen::AlignedBox3d>& boxes,
                          std::vector<std::pair<int, int>>& pairs) {
  boxes.resize(db.objects.size());
  for (size_t i = 0; i < db.objects.size(); ++i)
    boxes[i] = grow(worldContainer(db.objects[i]), db.tolerance);  // as overlapRegion grows them
  overlappingBoxPairs(db, boxes, pairs);
}

void candidateObjectPairsAmong(const ObjectDatabase& db, const std::vector<std::pair<int, int>>& among,
                               std::vector<Eigen::AlignedBox3d>& boxes, std::vector<std::pair<int, int>>& pairs) {
  boxes.assign(db.objects.size(), Eigen::AlignedBox3d());  // empty: not yet taken
  const auto box = [&](int i) -> const Eigen::AlignedBox3d& {
    if (boxes[i].isEmpty()) boxes[i] = grow(worldContainer(db.objects[i]), db.tolerance);
    return boxes[i];
  };
  pairs.clear();
  for (const auto& [i, j] : among)
    if (box(i).intersects(box(j))) pairs.emplace_back(i, j);
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
