#pragma once
// A scene built in ODE (the Open Dynamics Engine), the project's reference: the same
// gravity, step, masses, inertia, friction and restitution, run with ODE's own stepper.

#include <memory>
#include <optional>
#include <vector>

#include "sim/engine.h"
#include "sim/ode_geometry.h"
#include "sim/scene.h"

namespace polysim::sim {

/// How ODE is set up. ERP and CFM are ODE's error-reduction and constraint-force-mixing
/// parameters. Contacts use ODE's friction pyramid scaled by the normal force
/// (dContactApprox1) with mu = sqrt(mu_a mu_b) and bounce = max(e_a, e_b) above polysim's
/// bounce threshold: the same combination rules as polysim's solver.
struct OdeSettings {
  bool quickStep = true;  // dWorldQuickStep; false: dWorldStep (the direct, big-matrix solver)
  int quickStepIterations = 20;
  double erp = 0.2;   // ODE's default
  double cfm = 1e-9;  // near-rigid contacts (ODE's double-precision default is 1e-10)
  int maxContactsPerPair = 64;
};

/// What the linked ODE library can do (dCheckConfiguration).
struct OdeCapabilities {
  bool doublePrecision = true;
  bool triMesh = true;           // built with a triangle-mesh collider
  long maxTriMeshVertices = 0;   // 65535 with 16-bit indices; 0: no limit
  static OdeCapabilities ofLinkedLibrary();
};

/// Throws SceneError, one line per body, for what ODE cannot model: a non-box shape
/// without a triangle-mesh collider, a mesh with more vertices than ODE's indices reach,
/// and any scene when ODE is built in single precision (its contacts would not be
/// comparable to polysim's at the 1e-4 m tolerance).
void checkOdeCanModel(const Scene& scene, const OdeCapabilities& capabilities);

/// The scene in ODE. Boxes are dBox, other shapes dTriMesh; static bodies are geoms
/// without a body. Each dynamic body sits at its centre of mass with the geometry offset,
/// as ODE requires.
class OdeWorld : public Engine {
 public:
  /// Checks checkOdeCanModel(scene, OdeCapabilities::ofLinkedLibrary()) and the initial state.
  OdeWorld(const Scene& scene, const OdeSettings& settings);
  ~OdeWorld() override;
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  void step(double dt) override;
  std::vector<BodyState> bodyStates() const override;
  double energy() const override;
  /// The deepest contact depth ODE reported in the last step's collision pass.
  double stepPenetration() const override { return deepest_; }
  std::optional<double> firstContactTime() const override { return firstContact_; }
  int sleepingBodies() const override;
  /// ODE's warnings since this world was built (see OdeMessageLog).
  long messages() const { return odeMessages().count - messagesBefore_; }

 private:
  struct Body;
  static void nearCallback(void* self, dGeomID g1, dGeomID g2);

  Scene scene_;
  OdeSettings settings_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contactJoints_ = nullptr;
  std::vector<std::unique_ptr<Body>> bodies_;
  std::vector<dContact> scratch_;  // dCollide's output, reused
  double time_ = 0.0;
  double deepest_ = 0.0;
  std::optional<double> firstContact_;
  long messagesBefore_ = 0;
  unsigned long randomSeed_ = 0;  // ODE's generator, saved between steps (step())
};

/// ODE geoms of the scene's bodies without a world: ODE's collision test alone, for
/// asking ODE about contacts at poses that polysim reached.
class OdeContactProbe {
 public:
  explicit OdeContactProbe(const Scene& scene);
  /// ODE's contacts (at most `maxContacts`) between bodies a and b at the given world
  /// poses of their frames; each normal points from b towards a (ODE's and SPEC's
  /// convention), depth >= 0 is ODE's overlap along it.
  std::vector<dContactGeom> contacts(int a, int b, const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB,
                                     int maxContacts = 64);

 private:
  std::vector<OdeGeom> geoms_;
};

/// The geom ODE gets for a body's shape: dBox for a box, dTriMesh otherwise.
OdeGeom makeOdeGeom(const BodySpec& body, dSpaceID space = nullptr);

}  // namespace polysim::sim
