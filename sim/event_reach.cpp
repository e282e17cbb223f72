#include "sim/event_reach.h"

#include <algorithm>

#include "dynamics/disjoint_sets.h"
#include "dynamics/settings.h"

namespace polysim::sim {

EventReach::EventReach(int bodyCount) : solved_(static_cast<size_t>(bodyCount)) {}

void EventReach::newStep() {
  ++stamp_;
  pairs_.clear();
}

std::uint64_t EventReach::key(int a, int b) {
  const auto [lo, hi] = std::minmax(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(lo)) << 32) | static_cast<std::uint32_t>(hi);
}

void EventReach::noteSolved(const std::vector<collision::PairResult>& pairs, const std::vector<dynamics::RigidBody>& bodies) {
  for (const collision::PairResult& p : pairs) {
    pairs_[key(p.a, p.b)] = p.contacts.size();
    for (int i : {p.a, p.b}) solved_[i] = {stamp_, bodies[i].velocity, bodies[i].angularVelocity};
  }
}

bool EventReach::disturbed(int body, const dynamics::RigidBody& state) const {
  const Solved& s = solved_[body];
  return s.stamp != stamp_ || s.velocity != state.velocity || s.angularVelocity != state.angularVelocity;
}

std::vector<collision::PairResult> EventReach::reached(std::vector<collision::PairResult> contacts,
                                                       const std::vector<std::pair<int, int>>& crossing,
                                                       const std::vector<dynamics::RigidBody>& bodies,
                                                       const std::vector<double>& sizes) const {
  dynamics::DisjointSets groups(static_cast<int>(bodies.size()));
  for (const collision::PairResult& p : contacts)
    if (!bodies[p.a].isStatic && !bodies[p.b].isStatic) groups.join(p.a, p.b);
  std::vector<char> reachedRoot(bodies.size(), 0);  // per group root
  const auto disturb = [&](int i) {
    if (!bodies[i].isStatic) reachedRoot[groups.root(i)] = 1;
  };
  for (const auto& [a, b] : crossing) disturb(a), disturb(b);
  for (const collision::PairResult& p : contacts) {
    const auto at = pairs_.find(key(p.a, p.b));
    const bool newPair = at == pairs_.end() || at->second != p.contacts.size();
    for (int i : {p.a, p.b})
      if (newPair || (!bodies[i].isStatic && disturbed(i, bodies[i]))) disturb(i);
  }
  // A settling group (every body slower than kSettlingSpeed, not every one at rest after
  // its last solve) is swept again too: its sweeps carry it to rest (kSettlingSolverSweeps).
  struct Motion {
    bool seen = false, someFast = false, allRested = true;
  };
  std::vector<Motion> motionOf(bodies.size());  // per group root
  for (const collision::PairResult& p : contacts)
    for (int i : {p.a, p.b}) {
      const dynamics::RigidBody& b = bodies[i];
      if (b.isStatic) continue;
      Motion& m = motionOf[groups.root(i)];
      m.seen = true;
      m.someFast = m.someFast || b.velocity.norm() + b.angularVelocity.norm() * sizes[i] >= dynamics::kSettlingSpeed;
      m.allRested = m.allRested && b.restedAfterLastSolve;
    }
  for (size_t root = 0; root < motionOf.size(); ++root)
    if (motionOf[root].seen && !motionOf[root].someFast && !motionOf[root].allRested) reachedRoot[root] = 1;
  contacts.erase(std::remove_if(contacts.begin(), contacts.end(),
                                [&](const collision::PairResult& p) {
                                  return !reachedRoot[groups.root(bodies[p.a].isStatic ? p.b : p.a)];
                                }),
                 contacts.end());
  return contacts;
}

}  // namespace polysim::sim
