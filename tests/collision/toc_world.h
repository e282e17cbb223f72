#pragma once
// A database of objects for collisionDetect() tests: static ones, and moving ones on
// kinematic paths (constant velocity and angular velocity over the interval [0, 1]) or
// on a test's own path, with their motion bounds filled in.

#include <memory>
#include <string>
#include <vector>

#include "collision/time_of_contact.h"
#include "collision/tolerances.h"
#include "sim/kinematic_motion.h"

namespace polysim::test {

class TocWorld {
 public:
  explicit TocWorld(double eps = collision::kDefaultContactTolerance) { db.tolerance = eps; }
  int addStatic(const collision::MeshData& mesh, const Eigen::Isometry3d& X) {
    return db.add("static" + std::to_string(db.objects.size()), std::make_shared<collision::PolygonMesh>(mesh), X,
                  true);
  }
  /// A moving object at pose X at t = 0, moving at v (m per interval) and turning at w
  /// (rad per interval) about its origin.
  int addMoving(const collision::MeshData& mesh, const Eigen::Isometry3d& X, const Eigen::Vector3d& v,
                const Eigen::Vector3d& w = Eigen::Vector3d::Zero()) {
    motions_.push_back(std::make_unique<sim::KinematicMotion>(sim::KinematicMotion{X, v, w, 1.0}));
    const int id = addOnPath(mesh, X, sim::kinematicPose, motions_.back().get(), 0.0);
    db.objects[id].motionBound = sim::kinematicMotionBound(*motions_.back(), *db.objects[id].mesh);
    db.objects[id].motionRate = db.objects[id].motionBound;  // constant speeds
    return id;
  }
  /// A moving object on its own path: `ctrans` sets its pose at t from `info`; it moves
  /// at most `motionBound` (m) over [0, 1].
  int addOnPath(const collision::MeshData& mesh, const Eigen::Isometry3d& X, collision::TransformUpdate ctrans,
                const void* info, double motionBound) {
    const int id =
        db.add("moving" + std::to_string(db.objects.size()), std::make_shared<collision::PolygonMesh>(mesh), X, false);
    collision::ObjNode& node = db.objects[id];
    node.ctrans = ctrans;
    node.info = info;
    node.motionBound = motionBound;
    return id;
  }
  /// collisionDetect() over [0, 1] from the objects' t = 1 poses.
  collision::TocResult detect(collision::TocMethod method) {
    collision::TocOptions options;
    options.method = method;
    return detect(options);
  }
  collision::TocResult detect(const collision::TocOptions& options) {
    db.setTime(1.0);
    return collision::collisionDetect(db, options);
  }
  collision::ObjectDatabase db;

 private:
  std::vector<std::unique_ptr<sim::KinematicMotion>> motions_;
};

}  // namespace polysim::test
