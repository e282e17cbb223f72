#pragma once
// A scene as SPEC.md describes it: settings and bodies, loaded from JSON and validated
// before anything runs.

#include <Eigen/Geometry>
#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "collision/object.h"
#include "collision/polygon_mesh.h"
#include "collision/tolerances.h"
#include "dynamics/mass_properties.h"
#include "dynamics/settings.h"
#include "dynamics/sleep.h"
#include "sim/speculative_contacts.h"

namespace polysim::sim {

/// A scene file that cannot be used. what() is the whole message: one line per problem,
/// each naming the file, the body and the field.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The scene-level contact settings (SPEC.md defaults).
struct ContactSettings {
  double tolerance = collision::kDefaultContactTolerance;  // m
  double restitution = 0.0;
  double friction = 0.5;
  /// Most sweeps of the contact solver in one solve ("solver_sweeps"), a bound on every
  /// group of contacts; only a settling group sweeps past kMaxSolverIterations
  /// (dynamics/settings.h). Fewer trade convergence on stacks and piles for cost (the
  /// sweep charts it).
  int solverSweeps = dynamics::kSettlingSolverSweeps;
  /// How far apart (m) features of settled convex bodies may be and still go to the
  /// solver as speculative contacts ("speculative_reach", sim/speculative_contacts.h);
  /// 0: none, every new touch backs the island up to just contact.
  double speculativeReach = kSpeculativeReach;
  /// Pairs that have hardly moved against each other keep their contacts from one test
  /// to the next ("reuse_contacts", collision/contact_reuse.h); false tests every pair
  /// afresh each time.
  bool reuseContacts = true;
};

struct BodySpec {
  std::string name;
  std::string shapeType;  // "box", "mesh", "obj" or "icosphere"
  Eigen::Vector3d boxSize = Eigen::Vector3d::Zero();  // for boxes (m)
  collision::MeshData mesh;                            // every shape, boxes included
  bool isStatic = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();           // m, world
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();           // m/s, world
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();    // rad/s, world
  std::optional<double> mass;     // kg
  std::optional<double> density;  // kg/m^3 (default 1000 when neither is given)
  std::optional<double> restitution, friction;  // override the scene's

  Eigen::Isometry3d pose() const;
  /// A dynamic body's mass properties: its mesh at its density (1000 kg/m^3 when neither
  /// is given), scaled to its mass when that is given.
  dynamics::MassProperties massProperties() const;
  /// Its farthest vertex from `point` (m, body frame): the size the at-rest rule uses.
  double reachFrom(const Eigen::Vector3d& point) const;
};

struct Scene {
  std::string name;
  std::string file;  // as given on the command line
  Eigen::Vector3d gravity{0, 0, -9.81};  // m/s^2
  double dt = 1.0 / 240.0;               // s
  double duration = 1.0;                 // s
  ContactSettings contact;
  dynamics::SleepSettings sleep;  // "sleep": {"enabled", "speed" (m/s), "time" (s)}
  std::vector<BodySpec> bodies;

  /// The unit vector against gravity, along which heights are measured (+z without gravity).
  Eigen::Vector3d up() const;
};

/// Reads and validates a scene file. Throws SceneError listing every problem found:
/// malformed JSON, missing, mistyped or unknown fields, non-finite numbers, non-positive
/// sizes, masses or densities, duplicate names, bad meshes (see validateMesh), open
/// meshes on dynamic bodies, inside-out meshes. Interpenetration at the start is checked
/// by checkInitialState (it needs the collision module).
Scene loadScene(const std::string& path);

/// The same for scene text read from `in`, reported as the file `path` (OBJ files are
/// looked up next to it).
Scene readScene(std::istream& in, const std::string& path);

/// The collision database of the scene's bodies at their initial poses, in scene order.
collision::ObjectDatabase buildObjectDatabase(const Scene& scene);

/// Throws SceneError naming each pair of bodies that interpenetrates at the start.
void checkInitialState(const Scene& scene);

}  // namespace polysim::sim
