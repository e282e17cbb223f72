#pragma once
// ODE (the Open Dynamics Engine) as the reference: a scene built in ODE with the same
// gravity, step, masses, inertia, friction and restitution, run with ODE's own stepper.

#include <nlohmann/json.hpp>

#include "sim/run.h"
#include "sim/scene.h"

namespace polysim::sim {

/// How ODE is set up. ERP and CFM are ODE's error-reduction and constraint-force-mixing
/// parameters; contacts use ODE's friction pyramid scaled by the normal force
/// (dContactApprox1), mu = the pair's friction, bounce = the pair's restitution above
/// the same bounce threshold as polysim's solver.
struct OdeSettings {
  bool quickStep = true;        // dWorldQuickStep; false: dWorldStep (the direct solver)
  int quickStepIterations = 20;
  double erp = 0.2;             // ODE's default
  double cfm = 1e-9;            // near-rigid contacts (ODE's double-precision default is 1e-10)
  int maxContactsPerPair = 64;
};

/// Runs the scene in ODE and returns the same summary as runScene (SPEC.md), plus
/// "engine": "ode". Boxes are dBox (ODE's best path), other shapes dTriMesh (faces
/// fanned into triangles); static bodies are static geoms. Bodies sit at their centre of
/// mass with the geometry offset, since ODE requires it. max_penetration is the deepest
/// contact depth ODE reported at any step.
nlohmann::ordered_json runOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings = {});

/// `polysim compare`: both summaries and the differences of their trajectories (first
/// contact time, final poses, at-rest states, maximum penetration, energy).
nlohmann::ordered_json compareWithOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings = {});

}  // namespace polysim::sim
