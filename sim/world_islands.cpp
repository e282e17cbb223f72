// World's islands (world.h, islands.h): which bodies step together, the order their
// events are taken in, and what happens when an event turns a body towards another
// island's.

#include "sim/world.h"

#include <algorithm>
#include <iterator>

#include "collision/aabb.h"
#include "sim/islands.h"

namespace polysim::sim {

void World::startIsland(IslandRun& run, std::vector<char>& stepped) {
  for (int i : run.bodies) {
    if (asleep_[i]) wake(i);  // within reach of a moving body: it rests through this step, then moves
    stepped[i] = 1;
    eventsOf_[i] = 0;
  }
  for (const collision::PairResult& p : contacts_)
    if (std::binary_search(run.bodies.begin(), run.bodies.end(), bodies_[p.a].isStatic ? p.b : p.a)) run.contacts.push_back(p);
  run.serial = ++islandsNumbered_;
  run.reportEntry = static_cast<int>(report_.islands.size());
  report_.islands.push_back({static_cast<int>(run.bodies.size()), 0});
  run.state = IslandRun::State::Stepping;
}

void World::findNextEvent(IslandRun& run) {
  collision::ObjectDatabase& db = databaseFor(run.bodies);
  predictMotion(run.bodies, run.remaining);  // each body's path over the rest of the step
  for (int i : run.bodies) {
    const collision::ObjNode& node = db_.objects[i];
    reachBoxes_[i] = collision::grow(collision::worldContainer(node), node.motionBound + db_.tolerance);
  }
  run.toc = detectCollisions(db);  // back up to the island's first contact, if any
  run.elapsed = run.toc.time * run.remaining;
}

void World::finishIsland(IslandRun& run, double dt) {
  commitPoses(run.bodies, run.elapsed);
  run.remaining -= run.elapsed;
  run.contacts = std::move(run.toc.pairs);  // every pair was gathered at the step's end
  noteContacts(run.contacts, time_ + (dt - run.remaining));
}

SweptBody World::pathFrom(int i, const Eigen::AlignedBox3d& start, double duration) const {
  const dynamics::RigidBody& b = bodies_[i];
  SweptBody path;
  path.start = path.swept = start;
  path.dynamic = !b.isStatic;
  if (b.isStatic) return path;
  path.velocity = b.velocity + b.pushVelocity;  // as predictMotion() gives it (body_path.h)
  path.gravity = free_[i] ? scene_.gravity : Eigen::Vector3d::Zero();
  path.turn = (b.angularVelocity + b.pushAngularVelocity).norm() * sizes_[i] * duration;
  return path;
}

std::vector<std::vector<int>> World::islandsOfStep(double duration) {
  sweptBodies_.assign(bodies_.size(), SweptBody());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    // Grown by the tolerance: bodies that end the step within it of each other (in
    // contact) share an island, so a sleeping body never touches one that is awake.
    SweptBody& s = sweptBodies_[i] = pathFrom(static_cast<int>(i),
        collision::grow(collision::worldContainer(db_.objects[i]), db_.tolerance), duration);
    if (s.dynamic) s.swept = collision::grow(s.start, pathMotionBound(bodies_[i], sizes_[i], duration, s.gravity));
  }
  std::vector<std::pair<int, int>> touching;
  for (const collision::PairResult& p : contacts_) touching.emplace_back(p.a, p.b);
  for (size_t i = 0; i < bodies_.size(); ++i) reachBoxes_[i] = sweptBodies_[i].swept;
  return findIslands(sweptBodies_, duration, touching, kBoundsRoundOff);
}

void World::stepIslands(const std::vector<std::vector<int>>& islands, double dt,
                        std::vector<collision::PairResult>& contactsAfter, std::vector<char>& stepped) {
  runs_.assign(islands.size(), IslandRun());
  runOf_.assign(bodies_.size(), -1);
  for (size_t k = 0; k < islands.size(); ++k) {
    IslandRun& run = runs_[k];
    run.bodies = islands[k];
    run.remaining = dt;
    for (int i : run.bodies) runOf_[i] = static_cast<int>(k);
    if (std::all_of(run.bodies.begin(), run.bodies.end(), [this](int i) { return asleep_[i] != 0; })) continue;
    startIsland(run, stepped);
    findNextEvent(run);
  }
  // The events in the order of their times: an island waits at its next event (or at the
  // step's end) while another's comes first, so that an event that turns a body towards
  // it finds its clock behind the event's, never past it.
  for (;;) {
    int next = -1;
    double nextAt = 0.0;
    for (size_t k = 0; k < runs_.size(); ++k) {
      const IslandRun& run = runs_[k];
      if (run.state != IslandRun::State::Stepping || run.toc.stoppedBy == collision::TocStop::NoInterpenetration) continue;
      const double at = (dt - run.remaining) + run.elapsed;
      if (next < 0 || at < nextAt) next = static_cast<int>(k), nextAt = at;
    }
    if (next < 0) break;
    IslandRun& taking = runs_[next];
    std::swap(speculativeFound_, taking.speculativeFound);  // its own last test, whatever islands took events since
    speculativeIsland_ = taking.speculativeSerial;
    const std::vector<int> turned = takeEvent(taking, dt);
    std::swap(speculativeFound_, taking.speculativeFound);
    taking.speculativeSerial = speculativeIsland_;
    if (runs_.size() > 1) joinIslandsReached(next, turned, dt - runs_[next].remaining, dt, stepped);
    if (runs_[next].state == IslandRun::State::Stepping) findNextEvent(runs_[next]);
  }
  for (IslandRun& run : runs_) {
    if (run.state == IslandRun::State::Asleep || run.state == IslandRun::State::Joined) continue;
    if (run.state == IslandRun::State::Stepping) finishIsland(run, dt);
    contactsAfter.insert(contactsAfter.end(), run.contacts.begin(), run.contacts.end());
    sleepIfSettled(run.bodies, dt);
  }
  report_.islands.erase(std::remove_if(report_.islands.begin(), report_.islands.end(),
                                       [](const IslandReport& r) { return r.bodies == 0; }),
                        report_.islands.end());
}

SweptBody World::pathAt(int i, double t, double dt) const {
  const IslandRun& run = runs_[runOf_[i]];
  if (run.state == IslandRun::State::Asleep) return alongPath(sweptBodies_[i], t, dt);  // at rest all step
  const Eigen::AlignedBox3d here =
      collision::grow(collision::transformBox(bodies_[i].pose(), db_.objects[i].grid->container()), db_.tolerance);
  if (run.state == IslandRun::State::Stopped) {  // its clock stopped: it moves no more this step
    SweptBody still;
    still.start = still.swept = here;
    still.dynamic = true;
    return still;
  }
  // Its island's clock stands at or before t; its path from there is the one
  // findNextEvent() gave it (predictMotion).
  return alongPath(pathFrom(i, here, run.remaining), t - (dt - run.remaining), run.remaining);
}

void World::joinIslandsReached(int k, const std::vector<int>& turned, double t, double dt, std::vector<char>& stepped) {
  const double remaining = dt - t;
  for (int i : turned) {
    if (bodies_[i].isStatic) continue;
    const SweptBody now = pathAt(i, t, dt);
    const double bound = pathMotionBound(bodies_[i], sizes_[i], remaining, now.gravity);
    const Eigen::AlignedBox3d reach = collision::grow(now.start, bound);
    // Boxes first: they lie side by side, while each body is a long read.
    for (size_t j = 0; j < bodies_.size(); ++j) {
      if (!reachBoxes_[j].intersects(reach) || runOf_[j] == k || bodies_[j].isStatic) continue;
      if (!pathsMayMeet(now, pathAt(static_cast<int>(j), t, dt), remaining, kBoundsRoundOff)) continue;
      IslandRun& other = runs_[runOf_[j]];
      IslandRun& run = runs_[k];
      if (other.state == IslandRun::State::Asleep) {
        startIsland(other, stepped);  // at rest: its clock moves to t for nothing
      } else if (other.state == IslandRun::State::Stepping) {
        commitPoses(other.bodies, other.remaining - remaining);  // along the paths it was given
        for (int m : other.bodies) db_.objects[m].X_WO = bodies_[m].pose();
      }
      for (int m : other.bodies) runOf_[m] = k;
      std::vector<int> both;
      std::merge(run.bodies.begin(), run.bodies.end(), other.bodies.begin(), other.bodies.end(), std::back_inserter(both));
      run.bodies = std::move(both);
      run.contacts.insert(run.contacts.end(), other.contacts.begin(), other.contacts.end());
      IslandReport& entry = report_.islands[run.reportEntry];
      IslandReport& joined = report_.islands[other.reportEntry];
      entry.bodies += joined.bodies, entry.events += joined.events;
      joined = IslandReport{};  // dropped once the step's islands are done
      other.state = IslandRun::State::Joined;
      other.bodies.clear(), other.contacts.clear();
      run.serial = ++islandsNumbered_;  // its speculative contacts were another island's
      if (run.state == IslandRun::State::Stopped) run.state = IslandRun::State::Stepping;
      ++report_.islandsJoined;
    }
  }
}

}  // namespace polysim::sim
