#include "collision/broadphase.h"

#include <algorithm>
#include <utility>

#include "collision/aabb.h"

namespace polysim::collision {

Eigen::AlignedBox3d worldContainer(const ObjNode& object) {
  return transformBox(object.X_WO, object.grid->container());
}

namespace {

// One box as the sweep reads it: the sweep walks these in order of min x, so the
// boxes sit side by side in memory instead of being reached through an index.
struct SweptBox {
  double minX, maxX, minY, maxY, minZ, maxZ;
  int object;
  bool isStatic;
};

}  // namespace

void overlappingBoxPairs(const ObjectDatabase& db, const std::vector<Eigen::AlignedBox3d>& boxes,
                         std::vector<std::pair<int, int>>& pairs) {
  thread_local std::vector<SweptBox> sweep;  // reused: this runs once per detection
  sweep.resize(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Eigen::AlignedBox3d& b = boxes[i];
    sweep[i] = {b.min().x(), b.max().x(), b.min().y(), b.max().y(), b.min().z(), b.max().z(),
                static_cast<int>(i), db.objects[i].isStatic};
  }
  std::sort(sweep.begin(), sweep.end(), [](const SweptBox& p, const SweptBox& q) { return p.minX < q.minX; });
  pairs.clear();
  for (size_t k = 0; k < sweep.size(); ++k) {
    const SweptBox& a = sweep[k];
    for (size_t m = k + 1; m < sweep.size() && sweep[m].minX <= a.maxX; ++m) {
      const SweptBox& b = sweep[m];
      // Eigen's AlignedBox::intersects(), axis by axis: an empty box (min > max) meets nothing.
      const auto meet = [](double minA, double maxA, double minB, double maxB) {
        return std::max(minA, minB) <= std::min(maxA, maxB);
      };
      if ((a.isStatic && b.isStatic) || !meet(a.minX, a.maxX, b.minX, b.maxX) ||
          !meet(a.minY, a.maxY, b.minY, b.maxY) || !meet(a.minZ, a.maxZ, b.minZ, b.maxZ))
        continue;
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
