#pragma once
// ObjNode, the seed's object record, and the object database the module works on.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "collision/polygon_mesh.h"
#include "collision/voxel_grid.h"

namespace polysim::collision {

/// The seed's update function: sets X_WO, the object's pose in the world, for the time
/// t in [0, 1] of the interval being tested; `info` is the object's ObjNode::info.
using TransformUpdate = void (*)(double t, const void* info, Eigen::Isometry3d& X_WO);

/// One object of the database.
struct ObjNode {
  std::string name;
  std::shared_ptr<const PolygonMesh> mesh;
  std::shared_ptr<const VoxelGrid> grid;  // in the object's frame, built with the mesh
  /// The global transform: object frame to world (X_WO * p_O = p_W).
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  /// Sets X_WO for a time of the interval; null when the transform does not change.
  TransformUpdate ctrans = nullptr;
  const void* info = nullptr;
  /// A static object never moves in any interval; two static objects are never tested.
  bool isStatic = false;
  /// Upper bound (m) on how far any point of the object moves during the interval; used
  /// by collisionDetect() to catch objects passing through each other. Infinity: unknown.
  double motionBound = 0.0;
  /// Upper bound (m per unit of the interval's time t) on how fast any point of the
  /// object moves anywhere in the interval: between t1 and t2 no point moves more than
  /// motionRate |t2 - t1|. Lets collisionDetect()'s bisection stop watching pairs that
  /// cannot interpenetrate within its shrinking bracket. Infinity: unknown (every pair
  /// stays watched); ignored for an object without ctrans, which does not move.
  double motionRate = std::numeric_limits<double>::infinity();
  /// The object's least thickness (m; see thickness.h), computed when it is added.
  double thickness = 0.0;
  /// Its index in the database it was added to; copies into other databases (an
  /// island's) keep it, so that contact reuse (contact_reuse.h) knows the object again.
  /// -1 for an object not added with ObjectDatabase::add: never reused.
  int id = -1;
};

/// The object database: the objects and the contact tolerance they are judged with.
struct ObjectDatabase {
  std::vector<ObjNode> objects;
  /// Contact tolerance epsilon (m): see SPEC.md's contact conventions.
  double tolerance = 1e-4;

  /// Adds an object with its voxel grid (M halvings; -1 chooses M from the mesh).
  /// Returns its index.
  int add(std::string name, std::shared_ptr<const PolygonMesh> mesh, const Eigen::Isometry3d& X_WO,
          bool isStatic, int halvings = -1);

  /// Sets every moving object (non-null ctrans) to time t of the interval.
  void setTime(double t);
};

}  // namespace polysim::collision
