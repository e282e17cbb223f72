#include "collision/area_cover.h"

#include <algorithm>
#include <cmath>

namespace polysim::collision {

void AreaCover::reset(const PolygonMesh& meshA, const PolygonMesh& meshB) {
  meshA_ = &meshA;
  meshB_ = &meshB;
  byA_.clear();
  byB_.clear();
}

void AreaCover::addArea(int fa, int fb) {
  byA_.emplace_back(fa, fb);
  byB_.emplace_back(fb, fa);
}

void AreaCover::seal() {
  std::sort(byA_.begin(), byA_.end());
  std::sort(byB_.begin(), byB_.end());
}

bool AreaCover::covers(const PolygonView& p, const double* dP, const PolygonView& q, const double* dQ,
                       double eps) const {
  if (byA_.empty()) return false;
  return covered(p, dP, q, *meshA_, byB_, eps) || covered(q, dQ, p, *meshB_, byA_, eps);
}

bool AreaCover::covered(const PolygonView& steep, const double* d, const PolygonView& other, const PolygonMesh& mesh,
                        const std::vector<std::pair<int, int>>& areasByOther, double eps) const {
  // At 45 degrees or steeper, the part of `steep` within eps of the other's plane lies
  // within eps of its vertices there.
  if (std::abs(steep.plane.normal.dot(other.plane.normal)) > std::sqrt(0.5)) return false;
  const auto first = std::lower_bound(areasByOther.begin(), areasByOther.end(), std::pair(other.faceId, -1));
  auto inAreaFace = [&](int vertex) {
    for (auto it = first; it != areasByOther.end() && it->first == other.faceId; ++it) {
      const int face = it->second;
      if (face == steep.faceId) continue;
      const int* ids = mesh.faceVertices(face);
      if (std::find(ids, ids + mesh.faceSize(face), vertex) != ids + mesh.faceSize(face)) return true;
    }
    return false;
  };
  bool near = false;
  for (int i = 0; i < steep.size; ++i) {
    if (d[i] > eps) continue;
    if (d[i] < -eps || !inAreaFace(steep.vertexIds[i])) return false;
    near = true;
  }
  return near;
}

}  // namespace polysim::collision
