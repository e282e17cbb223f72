#include "sim/ode_world.h"

#include <cmath>
#include <sstream>

#include "dynamics/mass_properties.h"
#include "dynamics/rigid_body.h"
#include "dynamics/settings.h"

namespace polysim::sim {
namespace {

Eigen::Vector3d vec(const dReal* v) { return {v[0], v[1], v[2]}; }

}  // namespace

struct OdeWorld::Body {
  OdeGeom geom;
  dBodyID body = nullptr;  // null for static
  Eigen::Vector3d centerOfMassLocal = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, body axes
  double mass = 0.0, restitution = 0.0, friction = 0.0, size = 0.0;
};

OdeCapabilities OdeCapabilities::ofLinkedLibrary() {
  ensureOdeInitialised();
  OdeCapabilities c;
  c.doublePrecision = dCheckConfiguration("ODE_double_precision") == 1;
  c.triMesh = dCheckConfiguration("ODE_EXT_trimesh") == 1;
  c.maxTriMeshVertices = dCheckConfiguration("ODE_OPC_16bit_indices") == 1 ? 65535 : 0;
  return c;
}

void checkOdeCanModel(const Scene& scene, const OdeCapabilities& capabilities) {
  std::ostringstream problems;
  if (!capabilities.doublePrecision)
    problems << scene.file << ": ODE is built in single precision; its contacts cannot be compared with polysim's\n";
  for (const BodySpec& b : scene.bodies) {
    if (b.shapeType == "box") continue;
    if (!capabilities.triMesh)
      problems << scene.file << ": body \"" << b.name << "\": shape: \"" << b.shapeType
               << "\" needs ODE's triangle-mesh collider, which this ODE build lacks (only boxes can be compared)\n";
    else if (capabilities.maxTriMeshVertices > 0 &&
             static_cast<long>(b.mesh.vertices.size()) > capabilities.maxTriMeshVertices)
      problems << scene.file << ": body \"" << b.name << "\": shape: " << b.mesh.vertices.size()
               << " vertices, more than this ODE build's 16-bit triangle indices reach ("
               << capabilities.maxTriMeshVertices << ")\n";
  }
  std::string message = problems.str();
  if (message.empty()) return;
  message.pop_back();
  throw SceneError(message);
}

OdeGeom makeOdeGeom(const BodySpec& body, dSpaceID space) {
  return body.shapeType == "box" ? OdeGeom::box(body.boxSize, space) : OdeGeom::triMesh(body.mesh, space);
}

OdeWorld::OdeWorld(const Scene& scene, const OdeSettings& settings) : scene_(scene), settings_(settings) {
  checkOdeCanModel(scene, OdeCapabilities::ofLinkedLibrary());
  checkInitialState(scene);
  messagesBefore_ = odeMessages().count;
  world_ = dWorldCreate();
  space_ = dHashSpaceCreate(nullptr);
  contactJoints_ = dJointGroupCreate(0);
  dWorldSetGravity(world_, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
  dWorldSetERP(world_, settings.erp);
  dWorldSetCFM(world_, settings.cfm);
  dWorldSetQuickStepNumIterations(world_, settings.quickStepIterations);
  if (scene.sleep.enabled) {  // ODE's auto-disable with the scene's rule (dynamics/sleep.h)
    dWorldSetAutoDisableFlag(world_, 1);
    dWorldSetAutoDisableLinearThreshold(world_, scene.sleep.speed);
    dWorldSetAutoDisableTime(world_, scene.sleep.time);
    dWorldSetAutoDisableSteps(world_, 1);  // the time alone decides, as in polysim
  }
  scratch_.resize(settings.maxContactsPerPair);

  for (const BodySpec& spec : scene.bodies) {
    auto b = std::make_unique<Body>(Body{makeOdeGeom(spec, space_)});
    b->restitution = spec.restitution.value_or(scene.contact.restitution);
    b->friction = spec.friction.value_or(scene.contact.friction);
    dGeomSetData(b->geom.geom(), b.get());
    const dQuaternion q = {spec.orientation.w(), spec.orientation.x(), spec.orientation.y(), spec.orientation.z()};
    if (spec.isStatic) {
      dGeomSetPosition(b->geom.geom(), spec.position.x(), spec.position.y(), spec.position.z());
      dGeomSetQuaternion(b->geom.geom(), q);
      bodies_.push_back(std::move(b));
      continue;
    }
    const dynamics::MassProperties props = spec.massProperties();
    b->mass = props.mass;
    b->inertia = props.inertia;
    b->centerOfMassLocal = props.centerOfMass;
    b->size = spec.reachFrom(props.centerOfMass);
    b->body = dBodyCreate(world_);
    dMass m;
    const Eigen::Matrix3d& I = props.inertia;
    dMassSetParameters(&m, props.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
    dBodySetMass(b->body, &m);
    const Eigen::Vector3d com = spec.position + spec.orientation * props.centerOfMass;
    dBodySetPosition(b->body, com.x(), com.y(), com.z());
    dBodySetQuaternion(b->body, q);
    dBodySetLinearVel(b->body, spec.velocity.x(), spec.velocity.y(), spec.velocity.z());
    dBodySetAngularVel(b->body, spec.angularVelocity.x(), spec.angularVelocity.y(), spec.angularVelocity.z());
    if (scene.sleep.enabled) dBodySetAutoDisableAngularThreshold(b->body, scene.sleep.speed / b->size);  // spin at its farthest point
    dGeomSetBody(b->geom.geom(), b->body);
    dGeomSetOffsetPosition(b->geom.geom(), -props.centerOfMass.x(), -props.centerOfMass.y(), -props.centerOfMass.z());
    bodies_.push_back(std::move(b));
  }
}

OdeWorld::~OdeWorld() {
  bodies_.clear();  // geoms before their space
  dJointGroupDestroy(contactJoints_);
  dSpaceDestroy(space_);
  dWorldDestroy(world_);
}

void OdeWorld::nearCallback(void* self, dGeomID g1, dGeomID g2) {
  OdeWorld& w = *static_cast<OdeWorld*>(self);
  const dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (!b1 && !b2) return;  // static pairs cost nothing
  const auto* o1 = static_cast<const Body*>(dGeomGetData(g1));
  const auto* o2 = static_cast<const Body*>(dGeomGetData(g2));
  const int n = dCollide(g1, g2, w.settings_.maxContactsPerPair, &w.scratch_[0].geom, sizeof(dContact));
  if (n > 0 && !w.firstContact_) w.firstContact_ = w.time_;
  for (int i = 0; i < n; ++i) {
    dContact& c = w.scratch_[i];
    c.surface.mode = dContactApprox1 | dContactBounce;
    c.surface.mu = std::sqrt(o1->friction * o2->friction);
    c.surface.bounce = std::max(o1->restitution, o2->restitution);
    c.surface.bounce_vel = dynamics::kBounceThreshold;
    w.deepest_ = std::max(w.deepest_, static_cast<double>(c.geom.depth));
    dJointAttach(dJointCreateContact(w.world_, w.contactJoints_, &c), b1, b2);
  }
}

void OdeWorld::step(double dt) {
  deepest_ = 0.0;
  dSpaceCollide(space_, this, &nearCallback);
  // QuickStep shuffles its rows with ODE's one global random generator: each world keeps
  // its own seed, so that a run's figures do not depend on what ran before it in the
  // process (the serial sweep and a planned run of one setting must agree).
  dRandSetSeed(randomSeed_);
  if (settings_.quickStep) dWorldQuickStep(world_, dt);
  else dWorldStep(world_, dt);
  randomSeed_ = dRandGetSeed();
  dJointGroupEmpty(contactJoints_);
  time_ += dt;
}

std::vector<BodyState> OdeWorld::bodyStates() const {
  std::vector<BodyState> states;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const Body& b = *bodies_[i];
    if (!b.body) continue;
    const dReal* q = dBodyGetQuaternion(b.body);
    const Eigen::Quaterniond orientation(q[0], q[1], q[2], q[3]);
    const Eigen::Vector3d v = vec(dBodyGetLinearVel(b.body)), omega = vec(dBodyGetAngularVel(b.body));
    const Eigen::Vector3d origin = vec(dBodyGetPosition(b.body)) - orientation * b.centerOfMassLocal;
    states.push_back({scene_.bodies[i].name, origin, orientation, v, omega, dynamics::atRest(v, omega, b.size)});
  }
  return states;
}

int OdeWorld::sleepingBodies() const {
  int sleeping = 0;
  for (const auto& b : bodies_) sleeping += b->body && !dBodyIsEnabled(b->body);
  return sleeping;
}

double OdeWorld::energy() const {
  double e = 0.0;
  for (const auto& b : bodies_) {
    if (!b->body) continue;
    const dReal* q = dBodyGetQuaternion(b->body);
    const Eigen::Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    const Eigen::Vector3d v = vec(dBodyGetLinearVel(b->body));
    const Eigen::Vector3d omegaBody = R.transpose() * vec(dBodyGetAngularVel(b->body));
    e += 0.5 * b->mass * v.squaredNorm() + 0.5 * omegaBody.dot(b->inertia * omegaBody) -
         b->mass * scene_.gravity.dot(vec(dBodyGetPosition(b->body)));
  }
  return e;
}

OdeContactProbe::OdeContactProbe(const Scene& scene) {
  checkOdeCanModel(scene, OdeCapabilities::ofLinkedLibrary());
  for (const BodySpec& b : scene.bodies) geoms_.push_back(makeOdeGeom(b));
}

std::vector<dContactGeom> OdeContactProbe::contacts(int a, int b, const Eigen::Isometry3d& X_WA,
                                                    const Eigen::Isometry3d& X_WB, int maxContacts) {
  setPose(geoms_[a].geom(), X_WA);
  setPose(geoms_[b].geom(), X_WB);
  std::vector<dContactGeom> out(maxContacts);
  out.resize(dCollide(geoms_[a].geom(), geoms_[b].geom(), maxContacts, out.data(), sizeof(dContactGeom)));
  return out;
}

}  // namespace polysim::sim
