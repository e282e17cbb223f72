#pragma once
// An object's faces placed in the world for one query, computed on first use: a query
// touches only the faces near the other object, so transforming all of them would cost
// more than the test itself on large meshes.

#include <cstdint>
#include <vector>

#include "collision/object.h"
#include "collision/polygon_tests.h"

namespace polysim::collision {

class WorldFaces {
 public:
  /// Binds to `object` at its current pose. Forgets the faces placed before (O(1)),
  /// unless the object is the same mesh at the same pose as last time: a static floor
  /// is placed once, not once per query.
  void reset(const ObjNode& object);
  /// Face f's world bounding box.
  const Eigen::AlignedBox3d& box(int f) { return entry(f).box; }
  /// Face f's world plane.
  const Plane& plane(int f) { return entry(f).plane; }
  /// Face f as a world-frame polygon. Its pointers stay valid until the next reset() as
  /// long as no face not seen before is asked for (box() of every face first, then views).
  PolygonView view(int f);

 private:
  struct Entry {
    Eigen::AlignedBox3d box;
    Plane plane;
    int first = 0;  // into vertices_ and outward_
  };
  const Entry& entry(int f);

  const ObjNode* object_ = nullptr;
  const PolygonMesh* mesh_ = nullptr;  // and pose_: what the placed faces belong to
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  std::uint32_t query_ = 0;
  std::vector<std::uint32_t> stamp_;
  std::vector<Entry> entries_;
  std::vector<Eigen::Vector3d> vertices_, outward_, sideNormals_;
  std::vector<char> flat_;
  std::vector<int> vertexIds_, edgeIds_;
};

}  // namespace polysim::collision
