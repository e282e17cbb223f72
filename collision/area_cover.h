#pragma once
// Which polygon pairs need not gather contacts because an area contact already holds
// them. A box on a triangulated floor meets each triangle along its bottom face (an
// area) and along the bottom edges of its four sides (lines and points on that area's
// boundary, which the reduction would drop). Finding the areas first lets the side
// pairs skip gathering what would be thrown away.

#include <utility>
#include <vector>

#include "collision/polygon_mesh.h"
#include "collision/polygon_tests.h"

namespace polysim::collision {

class AreaCover {
 public:
  /// Forgets the areas of the previous object pair; faces of a come from meshA, of b
  /// from meshB.
  void reset(const PolygonMesh& meshA, const PolygonMesh& meshB);
  /// Records that face fa of a and face fb of b are in area contact.
  void addArea(int fa, int fb);
  /// Ready for covers() once every area is added.
  void seal();

  /// True when every contact p (of a) and q (of b) could have lies on an area contact
  /// recorded for a face next to one of them: one of the two (say p) stands steeply on
  /// the other's plane (at least 45 degrees), has at least one vertex within eps (m) of
  /// that plane, and every such vertex belongs to another face of its object that is in
  /// area contact with q; its other vertices are more than eps outside q's plane. Then
  /// what p has within eps of q is within eps of that area. dP and dQ are the signed
  /// distances of p's vertices to q's plane and of q's to p's.
  bool covers(const PolygonView& p, const double* dP, const PolygonView& q, const double* dQ, double eps) const;

 private:
  // One side of covers(): `steep` (face of `mesh`) against `other` (face of the other object).
  bool covered(const PolygonView& steep, const double* d, const PolygonView& other, const PolygonMesh& mesh,
               const std::vector<std::pair<int, int>>& areasByOther, double eps) const;

  const PolygonMesh* meshA_ = nullptr;
  const PolygonMesh* meshB_ = nullptr;
  std::vector<std::pair<int, int>> byB_;  // (fb, fa), sorted
  std::vector<std::pair<int, int>> byA_;  // (fa, fb), sorted
};

}  // namespace polysim::collision
