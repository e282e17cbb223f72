// World's choice of the contacts each solve is given (world.h): the contacts within the
// tolerance, the speculative contacts of settled convex bodies, and the wide band of
// pairs with a body that is not convex.

#include "sim/world.h"

#include <algorithm>

#include "dynamics/settings.h"
#include "sim/speculative_contacts.h"

namespace polysim::sim {

std::vector<collision::PairResult> World::solverContacts(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                         const std::vector<collision::PairResult>& touching,
                                                         const std::vector<char>* only) {
  return withWideBand(db, bodyOf, speculativeContacts(db, bodyOf, touching, false, only));
}

std::vector<collision::PairResult> World::solverContactsOnceLanded(const collision::ObjectDatabase& db,
                                                                   const std::vector<int>& bodyOf,
                                                                   const std::vector<collision::PairResult>& touching) {
  return withWideBand(db, bodyOf, speculativeContacts(db, bodyOf, touching, true));
}

std::vector<collision::PairResult> World::speculativeContacts(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                              const std::vector<collision::PairResult>& touching,
                                                              bool onceLanded, const std::vector<char>* only) {
  const double reach = scene_.contact.speculativeReach;
  if (reach <= 0.0) return touching;
  // Bodies flying free keep their exact parabolas and impacts (backed up to just
  // contact), and so do pairs that bounce; a sleeping body is moved by no solve. Pairs of
  // convex bodies, and a body that is not convex against a static convex one (the floor,
  // a wall); not two that are not convex: in a band as wide as the reach, the creases of
  // a cup in a cup are judged against walls that do not touch (a frictionless column of
  // cups gained 0.09 J and slid 9 mm in 4 s). Without the floor, a cup lying on its side
  // rocked for good: each step began on one edge, the other lifted past the wide band by
  // the event before (TossedIntoCorner.ACupTossedOntoItsSideComesToRest). Bodies at rest
  // at the step's start are tested only against moving ones, so a resting stack pays
  // nothing.
  const auto roleOfBody = [&](int i) {
    if ((bodies_[i].isStatic && !db_.objects[i].mesh->convex()) || (!bodies_[i].isStatic && (asleep_[i] || free_[i])))
      return SpeculativeRole::Left;
    return bodies_[i].isStatic || still_[i] ? SpeculativeRole::Still : SpeculativeRole::Moving;
  };
  const auto bodyAt = [&](int k) { return bodyOf.empty() ? k : bodyOf[k]; };
  const auto convexOrOnStatic = [this](const collision::PairResult& p) {  // body indices
    const bool convexA = db_.objects[p.a].mesh->convex(), convexB = db_.objects[p.b].mesh->convex();
    return (convexA && convexB) || (convexA && bodies_[p.a].isStatic) || (convexB && bodies_[p.b].isStatic);
  };
  const auto speculate = [this, convexOrOnStatic](const collision::PairResult& p) { return convexOrOnStatic(p) && !bounces(p); };
  const auto roleOf = [&](int k) { return roleOfBody(bodyAt(k)); };
  if (!onceLanded && only && speculativeIsland_ == islandSerial_) {  // the island's others keep their last test
    const auto retested = [only](const collision::PairResult& p) { return (*only)[p.a] || (*only)[p.b]; };
    speculativeFound_.erase(std::remove_if(speculativeFound_.begin(), speculativeFound_.end(), retested),
                            speculativeFound_.end());
    for (collision::PairResult& p : speculativePairs(db, workspace_, reach, bodyOf, roleOf, only))
      speculativeFound_.push_back(std::move(p));
  } else if (!onceLanded) {
    speculativeFound_ = speculativePairs(db, workspace_, reach, bodyOf, roleOf);
    speculativeIsland_ = islandSerial_;
  } else {  // the poses, and every other body's role, are the last test's: only the landed bodies' pairs are new
    std::vector<char> landed(bodies_.size(), 0);
    for (size_t i = 0; i < bodies_.size(); ++i) landed[i] = speculatedFree_[i] && !free_[i];
    for (collision::PairResult& p : speculativePairs(db, workspace_, reach, bodyOf, roleOf, &landed))
      speculativeFound_.push_back(std::move(p));
  }
  speculatedFree_ = free_;
  return mergeSpeculative(speculativeFound_, touching, db.tolerance, speculate);
}

std::vector<collision::PairResult> World::withWideBand(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                      std::vector<collision::PairResult> contacts) {
  const auto bodyAt = [&](int k) { return bodyOf.empty() ? k : bodyOf[k]; };
  bool any = false;  // an awake body that is not convex: without one, no pair is widened
  for (int k = 0; k < static_cast<int>(db.objects.size()) && !any; ++k) any = !db.objects[k].mesh->convex() && awake(bodyAt(k));
  if (!any) return contacts;
  const auto roleOf = [&](int k) {  // a sleeping body is moved by no solve
    const int i = bodyAt(k);
    return !bodies_[i].isStatic && asleep_[i] ? SpeculativeRole::Left : SpeculativeRole::Moving;
  };
  const auto notConvexPair = [this](const collision::PairResult& p) {  // and not bouncing: impacts back up to just contact
    return (!db_.objects[p.a].mesh->convex() || !db_.objects[p.b].mesh->convex()) && !bounces(p);
  };
  return withSpeculativeContacts(db, workspace_, kWideBandFactor * db.tolerance, bodyOf, contacts, roleOf, notConvexPair);
}

bool World::bounces(const collision::PairResult& pair) const {
  const PairMaterial& a = materials_[pair.a];
  const PairMaterial& b = materials_[pair.b];
  if (std::max(a.restitution, b.restitution) <= 0) return false;
  for (const collision::Contact& c : pair.contacts)
    for (const Eigen::Vector3d& x : c.points)
      if (c.normal.dot(bodies_[pair.a].velocityAt(x) - bodies_[pair.b].velocityAt(x)) < -dynamics::kBounceThreshold)
        return true;
  return false;
}

}  // namespace polysim::sim
