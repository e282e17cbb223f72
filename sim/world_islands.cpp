// World's islands (world.h, islands.h): which bodies step together, and what happens
// when an event's impulses carry a body out of the swept bounds its island was found by.

#include "sim/world.h"

#include <algorithm>

#include "collision/aabb.h"
#include "sim/islands.h"

namespace polysim::sim {

namespace {

bool holds(const std::vector<int>& island, int body) { return std::binary_search(island.begin(), island.end(), body); }

/// The dynamic body of an event's first crossing pair (or first pair), -1 when it names none.
int bodyOfEvent(const StepEvent& event, const std::vector<dynamics::RigidBody>& bodies) {
  if (!event.toc.crossing.empty()) {
    const auto [a, b] = event.toc.crossing.front();
    return bodies[a].isStatic ? b : a;
  }
  if (!event.toc.pairs.empty()) {
    const collision::PairResult& p = event.toc.pairs.front();
    return bodies[p.a].isStatic ? p.b : p.a;
  }
  return -1;
}

}  // namespace

std::vector<std::vector<int>> World::islandsOfStep(double duration) {
  std::vector<Eigen::AlignedBox3d>& bounds = stepBounds_;
  bounds.assign(bodies_.size(), Eigen::AlignedBox3d());
  std::vector<char> dynamic(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const dynamics::RigidBody& b = bodies_[i];
    dynamic[i] = !b.isStatic;
    if (b.isStatic) continue;
    const Eigen::Vector3d gravity = free_[i] ? scene_.gravity : Eigen::Vector3d::Zero();
    // Grown by the tolerance too: bodies that end the step within it of each other (in
    // contact) share an island, so a sleeping body never touches one that is awake.
    bounds[i] = collision::grow(collision::worldContainer(db_.objects[i]),
                                pathMotionBound(b, sizes_[i], duration, gravity) + db_.tolerance);
  }
  std::vector<std::pair<int, int>> touching;
  for (const collision::PairResult& p : contacts_) touching.emplace_back(p.a, p.b);
  return findIslands(bounds, dynamic, touching);
}

void World::stepIslands(std::vector<std::vector<int>> islands, double dt, std::vector<collision::PairResult>& contactsAfter,
                        std::vector<char>& stepped) {
  watchBounds_ = islands.size() > 1;
  std::vector<int> islandOf(bodies_.size(), -1);
  for (size_t k = 0; k < islands.size(); ++k)
    for (int i : islands[k]) islandOf[i] = static_cast<int>(k);
  std::vector<int> reportEntry(islands.size(), -1);  // its place in report_.islands once stepped
  std::vector<char> merged(islands.size(), 0);       // taken into a later island
  for (size_t k = 0; k < islands.size(); ++k) {
    if (merged[k]) continue;
    const std::vector<int> island = islands[k];  // a copy: islands grows below
    if (std::all_of(island.begin(), island.end(), [this](int i) { return asleep_[i] != 0; })) continue;
    for (int i : island) {
      startOf_[i] = {bodies_[i], db_.objects[i], free_[i], asleep_[i], slowFor_[i]};
      if (asleep_[i]) wake(i);  // within reach of a moving body: it rests through this step, then moves
      stepped[i] = 1;
    }
    reportEntry[k] = static_cast<int>(report_.islands.size());
    outgrown_ = false;
    stepIsland(island, dt, contactsAfter);
    if (!outgrown_) {
      sleepIfSettled(island, dt);
      continue;
    }
    // Its body may now reach island `other`'s: both start the step again as one island,
    // the others keep what they did.
    const int other = islandOf[outgrownLink_.second];
    takeBack(island, reportEntry[k], contactsAfter);
    if (reportEntry[other] >= 0) takeBack(islands[other], reportEntry[other], contactsAfter);
    std::vector<int> both;
    std::merge(island.begin(), island.end(), islands[other].begin(), islands[other].end(), std::back_inserter(both));
    merged[k] = merged[other] = 1;
    for (int i : both) islandOf[i] = static_cast<int>(islands.size());
    islands.push_back(std::move(both));
    reportEntry.push_back(-1);
    merged.push_back(0);
    ++report_.islandsRedone;
  }
  report_.islands.erase(std::remove_if(report_.islands.begin(), report_.islands.end(),
                                       [](const IslandReport& r) { return r.bodies == 0; }),
                        report_.islands.end());
}

bool World::outgrewItsBounds(const std::vector<int>& island) {
  if (!watchBounds_) return false;
  for (int i : island) {
    const collision::ObjNode& node = db_.objects[i];
    const Eigen::AlignedBox3d reach = collision::grow(collision::worldContainer(node), node.motionBound + db_.tolerance);
    if (collision::grow(stepBounds_[i], kBoundsRoundOff).contains(reach)) continue;
    // Bounds first: they lie side by side, while each body is a long read (a landing pile
    // of 1000 spent 5% of its run in this loop when bodies came first).
    for (size_t j = 0; j < bodies_.size(); ++j)
      if (stepBounds_[j].intersects(reach) && !bodies_[j].isStatic && !holds(island, static_cast<int>(j))) {
        outgrownLink_ = {i, static_cast<int>(j)};
        return outgrown_ = true;
      }
  }
  return false;
}

void World::takeBack(const std::vector<int>& island, int reportEntry, std::vector<collision::PairResult>& contactsAfter) {
  for (int i : island) {
    const BodyStart& start = startOf_[i];
    bodies_[i] = start.body, db_.objects[i] = start.object;
    free_[i] = start.free, asleep_[i] = start.asleep, slowFor_[i] = start.slowFor;
  }
  const auto ofIsland = [this, &island](int a, int b) { return holds(island, bodies_[a].isStatic ? b : a); };
  contactsAfter.erase(std::remove_if(contactsAfter.begin(), contactsAfter.end(),
                                     [&ofIsland](const collision::PairResult& p) { return ofIsland(p.a, p.b); }),
                      contactsAfter.end());
  std::vector<StepEvent>& events = report_.events;
  events.erase(std::remove_if(events.begin(), events.end(),
                              [this, &island](const StepEvent& e) { return holds(island, bodyOfEvent(e, bodies_)); }),
               events.end());
  for (std::vector<int>* named : {&report_.fellAsleep, &report_.woke})
    named->erase(std::remove_if(named->begin(), named->end(), [&island](int i) { return holds(island, i); }), named->end());
  report_.islands[reportEntry].bodies = 0;  // dropped once the step's islands are done
}

}  // namespace polysim::sim
