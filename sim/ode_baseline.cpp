#include "sim/ode_baseline.h"

#include <ode/ode.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "dynamics/mass_properties.h"
#include "dynamics/rigid_body.h"
#include "dynamics/settings.h"
#include "sim/json_output.h"

namespace polysim::sim {
namespace {

// ODE's global state, initialised once for the process.
struct OdeLibrary {
  OdeLibrary() { dInitODE2(0); }
  ~OdeLibrary() { dCloseODE(); }
};

struct OdeBody {
  dBodyID body = nullptr;  // null for static
  dGeomID geom = nullptr;
  dTriMeshDataID meshData = nullptr;
  std::vector<double> vertices;
  std::vector<dTriIndex> indices;
  Eigen::Vector3d centerOfMassLocal = Eigen::Vector3d::Zero();
  double mass = 0.0, restitution = 0.0, friction = 0.0, size = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

struct OdeWorld {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<std::unique_ptr<OdeBody>> bodies;
  OdeSettings settings;
  double deepest = 0.0;  // m, this step
  int touching = 0;      // contacts this step
  ~OdeWorld() {
    for (auto& b : bodies) {
      dGeomDestroy(b->geom);
      if (b->meshData) dGeomTriMeshDataDestroy(b->meshData);
    }
    dJointGroupDestroy(contacts);
    dSpaceDestroy(space);
    dWorldDestroy(world);
  }
};

Eigen::Vector3d vec(const dReal* v) { return {v[0], v[1], v[2]}; }

void nearCallback(void* data, dGeomID g1, dGeomID g2) {
  OdeWorld& w = *static_cast<OdeWorld*>(data);
  const dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (!b1 && !b2) return;  // static pairs cost nothing
  const auto* o1 = static_cast<const OdeBody*>(dGeomGetData(g1));
  const auto* o2 = static_cast<const OdeBody*>(dGeomGetData(g2));
  std::vector<dContact> contact(w.settings.maxContactsPerPair);
  const int n = dCollide(g1, g2, w.settings.maxContactsPerPair, &contact[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    dContact& c = contact[i];
    c.surface.mode = dContactApprox1 | dContactBounce;
    c.surface.mu = std::sqrt(o1->friction * o2->friction);
    c.surface.bounce = std::max(o1->restitution, o2->restitution);
    c.surface.bounce_vel = dynamics::kBounceThreshold;
    w.deepest = std::max(w.deepest, static_cast<double>(c.geom.depth));
    dJointAttach(dJointCreateContact(w.world, w.contacts, &c), b1, b2);
  }
  w.touching += n;
}

std::unique_ptr<OdeBody> makeBody(OdeWorld& w, const Scene& scene, const BodySpec& spec) {
  auto b = std::make_unique<OdeBody>();
  b->restitution = spec.restitution.value_or(scene.contact.restitution);
  b->friction = spec.friction.value_or(scene.contact.friction);
  if (spec.shapeType == "box") {
    b->geom = dCreateBox(w.space, spec.boxSize.x(), spec.boxSize.y(), spec.boxSize.z());
  } else {
    for (const Eigen::Vector3d& v : spec.mesh.vertices) b->vertices.insert(b->vertices.end(), {v.x(), v.y(), v.z()});
    for (const auto& f : spec.mesh.faces)
      for (size_t k = 1; k + 1 < f.size(); ++k)
        b->indices.insert(b->indices.end(), {static_cast<dTriIndex>(f[0]), static_cast<dTriIndex>(f[k]),
                                             static_cast<dTriIndex>(f[k + 1])});
    b->meshData = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(b->meshData, b->vertices.data(), 3 * sizeof(double),
                                static_cast<int>(spec.mesh.vertices.size()), b->indices.data(),
                                static_cast<int>(b->indices.size()), 3 * sizeof(dTriIndex));
    b->geom = dCreateTriMesh(w.space, b->meshData, nullptr, nullptr, nullptr);
  }
  dGeomSetData(b->geom, b.get());
  dQuaternion q = {spec.orientation.w(), spec.orientation.x(), spec.orientation.y(), spec.orientation.z()};
  if (spec.isStatic) {
    dGeomSetPosition(b->geom, spec.position.x(), spec.position.y(), spec.position.z());
    dGeomSetQuaternion(b->geom, q);
    return b;
  }
  auto props = dynamics::computeMassProperties(spec.mesh.vertices, spec.mesh.faces, spec.density.value_or(1000.0));
  if (spec.mass) props = dynamics::withMass(props, *spec.mass);
  b->mass = props.mass;
  b->inertia = props.inertia;
  b->centerOfMassLocal = props.centerOfMass;
  for (const Eigen::Vector3d& v : spec.mesh.vertices) b->size = std::max(b->size, (v - props.centerOfMass).norm());
  b->body = dBodyCreate(w.world);
  dMass m;
  const Eigen::Matrix3d& I = props.inertia;
  dMassSetParameters(&m, props.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
  dBodySetMass(b->body, &m);
  const Eigen::Vector3d com = spec.position + spec.orientation * props.centerOfMass;
  dBodySetPosition(b->body, com.x(), com.y(), com.z());
  dBodySetQuaternion(b->body, q);
  dBodySetLinearVel(b->body, spec.velocity.x(), spec.velocity.y(), spec.velocity.z());
  dBodySetAngularVel(b->body, spec.angularVelocity.x(), spec.angularVelocity.y(), spec.angularVelocity.z());
  dGeomSetBody(b->geom, b->body);
  dGeomSetOffsetPosition(b->geom, -props.centerOfMass.x(), -props.centerOfMass.y(), -props.centerOfMass.z());
  return b;
}

Eigen::Quaterniond orientationOf(const OdeBody& b) {
  const dReal* q = dBodyGetQuaternion(b.body);
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

double energyOf(const OdeWorld& w, const Eigen::Vector3d& gravity) {
  double e = 0.0;
  for (const auto& b : w.bodies) {
    if (!b->body) continue;
    const Eigen::Matrix3d R = orientationOf(*b).toRotationMatrix();
    const Eigen::Vector3d v = vec(dBodyGetLinearVel(b->body)), omega = R.transpose() * vec(dBodyGetAngularVel(b->body));
    e += 0.5 * b->mass * v.squaredNorm() + 0.5 * omega.dot(b->inertia * omega) - b->mass * gravity.dot(vec(dBodyGetPosition(b->body)));
  }
  return e;
}

}  // namespace

nlohmann::ordered_json runOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings) {
  static const OdeLibrary library;
  checkInitialState(scene);
  const double dt = options.dt.value_or(scene.dt);
  const long steps = std::lround(options.duration.value_or(scene.duration) / dt);
  OdeWorld w;
  w.settings = settings;
  w.world = dWorldCreate();
  w.space = dHashSpaceCreate(nullptr);
  w.contacts = dJointGroupCreate(0);
  dWorldSetGravity(w.world, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
  dWorldSetERP(w.world, settings.erp);
  dWorldSetCFM(w.world, settings.cfm);
  dWorldSetQuickStepNumIterations(w.world, settings.quickStepIterations);
  for (const BodySpec& spec : scene.bodies) w.bodies.push_back(makeBody(w, scene, spec));

  const double initialEnergy = energyOf(w, scene.gravity);
  double maxIncrease = 0.0, maxPenetration = 0.0, firstContact = -1.0;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    w.deepest = 0.0;
    w.touching = 0;
    dSpaceCollide(w.space, &w, &nearCallback);
    if (w.touching > 0 && firstContact < 0) firstContact = k * dt;
    maxPenetration = std::max(maxPenetration, w.deepest);
    if (settings.quickStep) dWorldQuickStep(w.world, dt);
    else dWorldStep(w.world, dt);
    dJointGroupEmpty(w.contacts);
    maxIncrease = std::max(maxIncrease, energyOf(w, scene.gravity) - initialEnergy);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    const OdeBody& b = *w.bodies[i];
    if (!b.body) continue;
    const Eigen::Quaterniond q = orientationOf(b);
    const Eigen::Vector3d v = vec(dBodyGetLinearVel(b.body)), omega = vec(dBodyGetAngularVel(b.body));
    const Eigen::Vector3d origin = vec(dBodyGetPosition(b.body)) - q * b.centerOfMassLocal;
    nlohmann::ordered_json state = bodyStateToJson(scene.bodies[i].name, origin, q, v, omega);
    state["at_rest"] = dynamics::atRest(v, omega, b.size);
    bodies.push_back(state);
  }
  nlohmann::ordered_json summary;
  summary["engine"] = "ode";
  summary["scene"] = scene.name;
  summary["steps"] = steps;
  summary["sim_time"] = forOutput(steps * dt);
  summary["wall_time_s"] = wall;
  summary["first_contact_time"] = firstContact < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(forOutput(firstContact));
  summary["max_penetration"] = forOutput(maxPenetration);
  summary["energy"] = {{"initial", forOutput(initialEnergy)},
                       {"final", forOutput(energyOf(w, scene.gravity))},
                       {"max_increase", forOutput(maxIncrease)}};
  summary["bodies"] = bodies;
  summary["settings"] = {{"stepper", settings.quickStep ? "quickstep" : "worldstep"},
                         {"iterations", settings.quickStepIterations},
                         {"erp", settings.erp},
                         {"cfm", settings.cfm}};
  return summary;
}

nlohmann::ordered_json compareWithOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings) {
  nlohmann::ordered_json mine = runScene(scene, options);
  const nlohmann::ordered_json ode = runOde(scene, options, settings);
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (size_t i = 0; i < mine["bodies"].size(); ++i) {
    const auto& a = mine["bodies"][i];
    const auto& b = ode["bodies"][i];
    const Eigen::Vector3d pa(a["position"][0], a["position"][1], a["position"][2]);
    const Eigen::Vector3d pb(b["position"][0], b["position"][1], b["position"][2]);
    const Eigen::Quaterniond qa(a["orientation"][0], a["orientation"][1], a["orientation"][2], a["orientation"][3]);
    const Eigen::Quaterniond qb(b["orientation"][0], b["orientation"][1], b["orientation"][2], b["orientation"][3]);
    bodies.push_back({{"name", a["name"]},
                      {"position_difference", forOutput((pa - pb).norm())},
                      {"orientation_difference_rad", forOutput(qa.angularDistance(qb))},
                      {"at_rest", {a["at_rest"], b["at_rest"]}}});
  }
  nlohmann::ordered_json comparison;
  comparison["first_contact_time"] = {mine["first_contact_time"], ode["first_contact_time"]};
  comparison["max_penetration"] = {mine["max_penetration"], ode["max_penetration"]};
  comparison["energy_final"] = {mine["energy"]["final"], ode["energy"]["final"]};
  comparison["wall_time_s"] = {mine["wall_time_s"], ode["wall_time_s"]};
  comparison["bodies"] = bodies;
  mine["engine"] = "polysim";
  return {{"polysim", mine}, {"ode", ode}, {"comparison", comparison}};
}

}  // namespace polysim::sim
