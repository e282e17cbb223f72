#include "sim/event_reach.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

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

std::vector<collision::PairResult> EventReach::reached(const std::vector<collision::PairResult>& contacts,
                                                       const std::vector<std::pair<int, int>>& crossing,
                                                       const std::vector<dynamics::RigidBody>& bodies,
                                                       const std::vector<double>& sizes) const {
  dynamics::DisjointSets groups(static_cast<int>(bodies.size()));
  for (const collision::PairResult& p : contacts)
    if (!bodies[p.a].isStatic && !bodies[p.b].isStatic) groups.join(p.a, p.b);
  std::unordered_set<int> reachedRoots;
  const auto disturb = [&](int i) {
    if (!bodies[i].isStatic) reachedRoots.insert(groups.root(i));
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
    bool someFast = false, allRested = true;
  };
  std::unordered_map<int, Motion> motionOf;  // per group root
  for (const collision::PairResult& p : contacts)
    for (int i : {p.a, p.b}) {
      const dynamics::RigidBody& b = bodies[i];
      if (b.isStatic) continue;
      Motion& m = motionOf[groups.root(i)];
      m.someFast = m.someFast || b.velocity.norm() + b.angularVelocity.norm() * sizes[i] >= dynamics::kSettlingSpeed;
      m.allRested = m.allRested && b.restedAfterLastSolve;
    }
  for (const auto& [root, m] : motionOf)
    if (!m.someFast && !m.allRested) reachedRoots.insert(root);
  std::vector<collision::PairResult> kept;
  for (const collision::PairResult& p : contacts)
    if (reachedRoots.count(groups.root(bodies[p.a].isStatic ? p.b : p.a))) kept.push_back(p);
  return kept;
}

}  // namespace polysim::sim
