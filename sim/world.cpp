#include "sim/world.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>

#include "collision/intersection.h"
#include "dynamics/integrator.h"
#include "dynamics/settings.h"
#include "dynamics/sleep.h"
#include "sim/warm_start.h"

namespace polysim::sim {

World::World(const Scene& scene, collision::TocMethod method)
    : scene_(scene), db_(buildObjectDatabase(scene)), reach_(static_cast<int>(scene.bodies.size())) {
  checkInitialState(scene_);
  tocOptions_.method = method;
  tocOptions_.gatherAtEvent = false;  // an event's contacts are those of the groups it reaches (takeEvent)
  workspace_.reuse.enable(scene_.contact.reuseContacts);
  workspace_.separations.enable();  // its meshes live as long as the world
  for (const BodySpec& spec : scene_.bodies) {
    dynamics::RigidBody body = dynamics::RigidBody::fixed();
    if (!spec.isStatic) {
      body = dynamics::RigidBody::dynamic(spec.massProperties());
      body.velocity = spec.velocity;
      body.angularVelocity = spec.angularVelocity;
    }
    body.position = spec.position;
    body.orientation = spec.orientation;
    bodies_.push_back(body);
    materials_.push_back({spec.restitution.value_or(scene_.contact.restitution), spec.friction.value_or(scene_.contact.friction)});
    sizes_.push_back(spec.reachFrom(body.centerOfMassLocal));
  }
  for (size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].isStatic) staticBodies_.push_back(static_cast<int>(i));
  paths_.resize(bodies_.size());  // never resized again: the database points into it
  free_.assign(bodies_.size(), 1);
  slowFor_.assign(bodies_.size(), 0.0);
  asleep_.assign(bodies_.size(), 0);
  eventsOf_.assign(bodies_.size(), 0);
  still_.assign(bodies_.size(), 0);
  reachBoxes_.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    paths_[i].body = &bodies_[i];
    db_.objects[i].info = &paths_[i];
  }
  contacts_ = collision::test4Intersection(db_, workspace_).pairs;
  if (!contacts_.empty()) firstContact_ = 0.0;
}

const StepReport& World::step(double dt) {
  StepReport next;
  next.step = report_.step + 1;
  report_ = std::move(next);
  reach_.newStep();
  for (size_t i = 0; i < bodies_.size(); ++i) free_[i] = !asleep_[i];  // a sleeping body rests: no gravity, no path
  for (dynamics::RigidBody& b : bodies_) b.pushVelocity.setZero(), b.pushAngularVelocity.setZero();  // set by this step's solves
  for (size_t i = 0; i < bodies_.size(); ++i) still_[i] = atRest(static_cast<int>(i));
  std::vector<collision::PairResult> moving;  // the contacts of bodies that are awake
  for (const collision::PairResult& p : contacts_)
    if (awake(p.a) || awake(p.b)) moving.push_back(p);
  const BodyPairs bouncingAtStart = bouncingPairs(moving);  // judged before the step's gravity
  supportTouchingBodies(moving, bouncingAtStart, dt);  // gravity into the velocities of bodies in contact; the others fly free
  resolveContacts(solverContacts(db_, {}, moving), dt, true,  // the contacts the step starts with
                  dynamics::kAllowedOverlapFraction * db_.tolerance, &bouncingAtStart);
  std::vector<collision::PairResult> contactsAfter;
  std::vector<char> stepped(bodies_.size(), 0);
  stepIslands(islandsOfStep(dt), dt, contactsAfter, stepped);
  for (collision::PairResult& p : contacts_)  // sleeping pairs keep their contacts (moved: contacts_ is replaced)
    if (!stepped[bodies_[p.a].isStatic ? p.b : p.a]) contactsAfter.push_back(std::move(p));
  contacts_ = std::move(contactsAfter);
  report_.sleeping = static_cast<int>(std::count(asleep_.begin(), asleep_.end(), 1));
  const double y = dt - timeCompensation_, sum = time_ + y;  // compensated time_ += dt
  timeCompensation_ = (sum - time_) - y;
  time_ = sum;
  report_.time = time_;
  return report_;
}

void World::placeBody(int body, const Eigen::Isometry3d& pose, const Eigen::Vector3d& velocity,
                      const Eigen::Vector3d& angularVelocity) {
  dynamics::RigidBody& b = bodies_[body];
  const std::string& name = scene_.bodies[body].name;
  if (b.isStatic) throw std::invalid_argument("placeBody: \"" + name + "\" is static");
  dynamics::RigidBody placed = b;
  placed.position = pose.translation();
  placed.orientation = Eigen::Quaterniond(pose.linear());
  placed.velocity = velocity;
  placed.angularVelocity = angularVelocity;
  collision::ObjNode& node = db_.objects[body];
  const Eigen::Isometry3d before = node.X_WO;
  node.X_WO = placed.pose();  // exactly the pose the body's state gives, as after a step
  node.ctrans = nullptr;
  collision::IntersectionResult now = collision::test4Intersection(db_, workspace_);
  if (now.status == collision::Status::Interpenetrating) {
    node.X_WO = before;
    throw std::invalid_argument("placeBody: \"" + name + "\" would interpenetrate another body there");
  }
  for (const collision::PairResult& p : contacts_)  // what rested on it falls once it is gone
    if (p.a == body || p.b == body)
      for (int other : {p.a, p.b}) asleep_[other] = 0, slowFor_[other] = 0.0;
  asleep_[body] = 0;
  slowFor_[body] = 0.0;
  b = placed;
  contacts_ = std::move(now.pairs);
  lastSolved_.erase(std::remove_if(lastSolved_.begin(), lastSolved_.end(),
                                   [body](const dynamics::ContactPoint& p) { return p.a == body || p.b == body; }),
                    lastSolved_.end());
}

void World::wake(int body) {
  asleep_[body] = 0;
  slowFor_[body] = 0.0;
  report_.woke.push_back(body);
}

void World::sleepIfSettled(const std::vector<int>& island, double dt) {
  if (!scene_.sleep.enabled) return;
  double settled = scene_.sleep.time;
  for (int i : island) {
    slowFor_[i] = dynamics::slowTimeAfterStep(bodies_[i], sizes_[i], dt, slowFor_[i], scene_.sleep);
    settled = std::min(settled, slowFor_[i]);
  }
  if (settled < scene_.sleep.time) return;
  for (int i : island) {
    asleep_[i] = 1;
    bodies_[i].velocity.setZero();
    bodies_[i].angularVelocity.setZero();
    report_.fellAsleep.push_back(i);
  }
}

std::vector<int> World::takeEvent(IslandRun& run, double dt) {
  const std::vector<int>& island = run.bodies;
  std::vector<collision::PairResult>& contacts = run.contacts;
  collision::ObjectDatabase& db = databaseFor(island);  // as findNextEvent() left its poses
  islandSerial_ = run.serial;
  const double elapsed = run.elapsed;
  commitPoses(island, elapsed);  // its bodies move to the event's state
  run.remaining -= elapsed;
  const double remaining = run.remaining;
  struct Path {
    Eigen::Vector3d v, w, pushV, pushW;
    char free;
  };
  std::vector<Path> before;  // to tell which bodies the event turns aside
  for (int i : island) {
    const dynamics::RigidBody& b = bodies_[i];
    before.push_back({b.velocity, b.angularVelocity, b.pushVelocity, b.pushAngularVelocity, free_[i]});
  }
  const auto turnedAside = [&] {
    std::vector<int> turned;
    for (size_t k = 0; k < island.size(); ++k) {
      const dynamics::RigidBody& b = bodies_[island[k]];
      const Path& p = before[k];
      if (b.velocity != p.v || b.angularVelocity != p.w || b.pushVelocity != p.pushV || b.pushAngularVelocity != p.pushW ||
          free_[island[k]] != p.free)
        turned.push_back(island[k]);
    }
    return turned;
  };
  ++report_.islands[run.reportEntry].events;
  collision::TocResult toc = std::move(run.toc);
  const bool bodyAtBound = countEventOfBodies(toc.crossing);
  const std::vector<std::pair<int, int>> crossing = toc.crossing;
  // The event's contacts: those of the groups it reaches, tested at its time; the
  // island's other pairs keep their last test (bodiesAnEventReaches). When the clock
  // stops or nothing moved, every pair is tested: the step ends on those contacts, or a
  // stall solves them all.
  std::vector<char> tested(bodies_.size(), 0);
  const std::vector<char> want = bodiesAnEventReaches(island, contacts, toc, bodyAtBound || elapsed == 0.0);
  toc.pairs = retestPairsOf(db, want, tested, contacts);
  noteContacts(toc.pairs, time_ + (dt - remaining));
  report_.events.push_back({time_ + (dt - remaining), std::move(toc)});
  if (bodyAtBound) {  // the island's clock stops (see kMaxEventsPerStep)
    report_.eventLimitHit = true;
    if (remaining == dt) stopTouchingBodies(contacts);  // it did not move at all
    else takeBackUnflownGravity(island, remaining);
    run.state = IslandRun::State::Stopped;
    return turnedAside();
  }
  // No progress at all: the solver's contacts approach nowhere, yet the detector finds
  // a pair interpenetrating at once (see kStalledGapFraction); push them apart.
  const double allowedOverlap = elapsed > 0.0 ? dynamics::kAllowedOverlapFraction * db_.tolerance
                                              : -kStalledGapFraction * db_.tolerance;
  // A stalled event is solved on the detector's own contacts, which it disagrees with.
  // The speculative test, too, covers the pairs of the bodies tested at this event
  // (after the island's first event; its others keep their last test).
  std::vector<char> speculated(bodies_.size(), 0);
  const auto newlyTested = [&] {
    std::vector<char> only(bodies_.size(), 0);
    for (size_t i = 0; i < only.size(); ++i) only[i] = tested[i] && !speculated[i], speculated[i] = tested[i];
    return only;
  };
  const auto remakeSolverContacts = [&](const std::vector<collision::PairResult>& now) {
    const std::vector<char> only = newlyTested();
    return solverContacts(db, islandIds_, now, &only);
  };
  std::vector<collision::PairResult> solved = elapsed > 0.0 ? remakeSolverContacts(contacts) : contacts;
  // Which pairs bounce is judged before the solve turns their approach into a rebound:
  // judged after it, a bounced box was taken for landed and given the rest of the step's
  // gravity at once (at dt 1 s, 9 m/s down, which it then bounced off: +12 J a step).
  const BodyPairs bouncing = bouncingPairs(contacts);
  // Only the groups of contacts the event disturbed are solved again (event_reach.h); a
  // stalled event pushes all of its contacts apart.
  if (elapsed > 0.0) solved = reachedAtEvent(db, std::move(solved), crossing, tested, contacts, remakeSolverContacts);
  resolveContacts(solved, remaining, false, allowedOverlap);  // impulses at the contact
  if (supportTouchingBodies(contacts, bouncing, remaining)) {  // bodies that landed take the rest of the step's gravity,
    if (elapsed > 0.0) {                                       // and may now speculate (settled)
      const auto remakeOnceLanded = [&](const std::vector<collision::PairResult>& now) {
        return solverContactsOnceLanded(db, islandIds_, now);
      };
      solved = reachedAtEvent(db, remakeOnceLanded(contacts), crossing, tested, contacts, remakeOnceLanded);
    }
    resolveContacts(solved, remaining, false, allowedOverlap, &bouncing);  // after their impact, bouncing no more
  }
  return turnedAside();
}

collision::ObjectDatabase& World::databaseFor(const std::vector<int>& island) {
  islandIds_.clear();
  if (island.size() + staticBodies_.size() == bodies_.size()) return db_;
  // The island's bodies and the static ones, in the order of the body array: the two
  // sorted lists merged, so that a pile's hundreds of one-box islands each cost their
  // own size, not the world's.
  std::merge(island.begin(), island.end(), staticBodies_.begin(), staticBodies_.end(), std::back_inserter(islandIds_));
  islandDb_.tolerance = db_.tolerance;
  islandDb_.objects.clear();
  for (int i : islandIds_) islandDb_.objects.push_back(db_.objects[i]);
  return islandDb_;
}

void World::stopTouchingBodies(const std::vector<collision::PairResult>& contacts) {
  for (const collision::PairResult& p : contacts)
    for (int i : {p.a, p.b}) {
      dynamics::RigidBody& b = bodies_[i];
      if (b.isStatic) continue;
      b.velocity.setZero(), b.angularVelocity.setZero();
      b.pushVelocity.setZero(), b.pushAngularVelocity.setZero();
    }
}

void World::takeBackUnflownGravity(const std::vector<int>& island, double unflown) {
  const double g = scene_.gravity.norm();
  if (g == 0.0) return;
  const Eigen::Vector3d down = scene_.gravity / g;
  for (int i : island) {
    dynamics::RigidBody& b = bodies_[i];
    if (b.isStatic || free_[i]) continue;
    const double falling = b.velocity.dot(down);
    b.velocity -= std::min(g * unflown, std::max(0.0, falling)) * down;
  }
}

bool World::supportTouchingBodies(const std::vector<collision::PairResult>& contacts, const BodyPairs& bouncing,
                                  double duration) {
  bool any = false;
  for (const collision::PairResult& p : contacts)
    if (!bouncing.count(bodyPair(p.a, p.b)))
      for (int i : {p.a, p.b})
        if (free_[i]) {
          dynamics::integrateVelocity(bodies_[i], scene_.gravity, duration);  // nothing for a static body
          free_[i] = 0;
          any = any || !bodies_[i].isStatic;
        }
  return any;
}

BodyPairs World::bouncingPairs(const std::vector<collision::PairResult>& contacts) const {
  BodyPairs pairs;
  for (const collision::PairResult& p : contacts)
    if (bounces(p)) pairs.insert(bodyPair(p.a, p.b));
  return pairs;
}

void World::resolveContacts(const std::vector<collision::PairResult>& contacts, double horizon, bool stepStart,
                            double allowedOverlap, const BodyPairs* bouncing) {
  std::vector<dynamics::ContactPoint> points;
  for (const collision::PairResult& pair : contacts) {
    const PairMaterial& a = materials_[pair.a];
    const PairMaterial& b = materials_[pair.b];
    const bool mayBounce = !bouncing || bouncing->count(bodyPair(pair.a, pair.b));
    const auto edgeDirection = [this, &pair](bool ofA, int edgeId) -> Eigen::Vector3d {
      const collision::ObjNode& object = db_.objects[ofA ? pair.a : pair.b];
      const collision::MeshEdge& e = object.mesh->edges()[edgeId];
      return (object.X_WO.linear() * (object.mesh->vertices()[e.v1] - object.mesh->vertices()[e.v0])).normalized();
    };
    appendContactPoints(pair.a, pair.b, pair.contacts,
                        {mayBounce ? std::max(a.restitution, b.restitution) : 0.0, std::sqrt(a.friction * b.friction)}, points,
                        edgeDirection);
  }
  if (points.empty()) return;
  // Bottom-up along gravity: each sweep of the sequential solver then carries a stack's
  // weight down to the ground in one pass instead of one level per sweep.
  const Eigen::Vector3d down = scene_.gravity;
  std::stable_sort(points.begin(), points.end(), [&down](const dynamics::ContactPoint& p, const dynamics::ContactPoint& q) {
    return p.point.dot(down) > q.point.dot(down);
  });
  // Only the step's start is warm-started: a solve after an event adds impulses to
  // velocities that already hold the step's gravity and its support, so a resting
  // contact needs none, and the event's own pair is new. Warm-started with the step's
  // forces over the remaining time, such a solve pushed every resting contact of its
  // island apart and then took it back: a fifth of a settling pile's cost (tilted piles
  // of 343, seeds 1 to 3, first 8 s: 11.2 against 9.1 s of CPU).
  if (stepStart) warmStartFromLastSolve(lastSolved_, points, horizon);
  const Eigen::Vector3d up = scene_.gravity.isZero(0.0) ? Eigen::Vector3d::Zero() : scene_.up();  // zero: no support order
  std::optional<SolveProblem> observed;
  if (solveObserver_) observed = SolveProblem{bodies_, points, horizon, allowedOverlap, scene_.contact.solverSweeps, up, stepStart};
  const dynamics::SolveStats solved =
      dynamics::solveContacts(bodies_, points, horizon, allowedOverlap, scene_.contact.solverSweeps, up);
  if (observed) solveObserver_(*observed, bodies_);
  report_.solverIterations += solved.iterations;
  report_.shockSweeps += solved.shockSweeps;
  reach_.noteSolved(contacts, bodies_);
  if (!stepStart) return;
  for (dynamics::ContactPoint& p : points) {
    p.normalImpulse /= horizon;
    p.frictionImpulse /= horizon;
  }
  for (const dynamics::ContactPoint& old : lastSolved_)  // sleeping pairs keep theirs for when they wake
    if (!awake(old.a) && !awake(old.b)) points.push_back(old);
  lastSolved_ = std::move(points);
}

void World::predictMotion(const std::vector<int>& island, double duration) {
  for (int i : island) {
    collision::ObjNode& node = db_.objects[i];
    const dynamics::RigidBody& b = bodies_[i];
    const bool falling = free_[i] && !scene_.gravity.isZero(0.0);
    const bool moving = falling || !b.velocity.isZero(0.0) || !b.angularVelocity.isZero(0.0) ||
                        !b.pushVelocity.isZero(0.0) || !b.pushAngularVelocity.isZero(0.0);
    node.ctrans = moving ? bodyPathPose : nullptr;  // a body at rest costs no update
    paths_[i].duration = duration;
    paths_[i].gravity = falling ? scene_.gravity : Eigen::Vector3d::Zero();
    node.motionBound = moving ? pathMotionBound(b, sizes_[i], duration, paths_[i].gravity) : 0.0;
    node.motionRate = moving ? pathMotionRate(b, sizes_[i], duration, paths_[i].gravity) : 0.0;
  }
}

collision::TocResult World::detectCollisions(collision::ObjectDatabase& db) {
  if (islandIds_.empty()) {
    db.setTime(1.0);  // collisionDetect() starts from the end of the interval
    return collision::collisionDetect(db, workspace_, tocOptions_);
  }
  for (size_t k = 0; k < islandIds_.size(); ++k) db.objects[k] = db_.objects[islandIds_[k]];  // this round's paths
  db.setTime(1.0);
  collision::TocResult toc = collision::collisionDetect(db, workspace_, tocOptions_);
  for (size_t k = 0; k < islandIds_.size(); ++k) db_.objects[islandIds_[k]].X_WO = db.objects[k].X_WO;
  for (collision::PairResult& p : toc.pairs) p.a = islandIds_[p.a], p.b = islandIds_[p.b];
  for (auto& [a, b] : toc.crossing) a = islandIds_[a], b = islandIds_[b];
  for (auto& [a, b] : toc.nearing) a = islandIds_[a], b = islandIds_[b];
  return toc;
}

bool World::countEventOfBodies(const std::vector<std::pair<int, int>>& crossing) {
  // An event always names a pair (an interpenetration stopped it); were one to name none,
  // its island's clock stops, so that an island's events stay bounded whatever happens.
  bool atBound = crossing.empty();
  for (const auto& [a, b] : crossing)
    for (int i : {a, b}) {
      if (bodies_[i].isStatic) continue;
      if (++eventsOf_[i] >= kMaxEventsPerStep) atBound = true;
    }
  return atBound;
}

void World::commitPoses(const std::vector<int>& island, double elapsed) {
  // The same path and the same product s * duration as ctrans used: the committed poses
  // are exactly the state collisionDetect() tested.
  // Bodies without a path did not move (and are not re-derived from their centre of mass).
  for (int i : island)
    if (db_.objects[i].ctrans) dynamics::advancePose(bodies_[i], elapsed, paths_[i].gravity);
}

void World::noteContacts(const std::vector<collision::PairResult>& contacts, double at) {
  if (!contacts.empty() && firstContact_ < 0) firstContact_ = at;
  for (const collision::PairResult& p : contacts)
    for (const collision::Contact& c : p.contacts) report_.penetration = std::max(report_.penetration, -c.separation);
}

double World::energy() const {
  double e = 0.0;
  for (const dynamics::RigidBody& b : bodies_)
    if (!b.isStatic) e += b.kineticEnergy() - b.mass * scene_.gravity.dot(b.centerOfMass());
  return e;
}

bool World::atRest(int i) const {
  const dynamics::RigidBody& b = bodies_[i];
  return b.isStatic || dynamics::atRest(b.velocity, b.angularVelocity, sizes_[i]);
}

}  // namespace polysim::sim
