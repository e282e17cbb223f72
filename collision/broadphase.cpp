#include "collision/broadphase.h"

#include <algorithm>
#include <utility>

#include "collision/aabb.h"

namespace polysim::collision {

Eigen::AlignedBox3d worldContainer(const ObjNode& object) {
  return transformBox(object.X_WO, object.grid->container());
}

namespace {

// One box as the sweep reads it: the sweep walks these in order of min x, so the boxes
// sit side by side in memory instead of being reached through an index.
struct SweptBox {
  Eigen::AlignedBox3d box;
  int object;
  bool isStatic;
};

}  // namespace

void overlappingBoxPairs(const ObjectDatabase& db, const std::vector<Eigen::AlignedBox3d>& boxes,
                         std::vector<std::pair<int, int>>& pairs) {
  std::vector<SweptBox> sweep(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) sweep[i] = {boxes[i], static_cast<int>(i), db.objects[i].isStatic};
  std::sort(sweep.begin(), sweep.end(),
            [](const SweptBox& p, const SweptBox& q) { return p.box.min().x() < q.box.min().x(); });
  pairs.clear();
  for (size_t k = 0; k < sweep.size(); ++k) {
    const SweptBox& a = sweep[k];
    for (size_t m = k + 1; m < sweep.size() && sweep[m].box.min().x() <= a.box.max().x(); ++m) {
      const SweptBox& b = sweep[m];
      if ((a.isStatic && b.isStatic) || !a.box.intersects(b.box)) continue;
      pairs.emplace_back(std::min(a.object, b.object), std::max(a.object, b.object));
    }
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
