#include "sim/warm_start.h"

#include <algorithm>
#include <unordered_map>

namespace polysim::sim {

void warmStartFromLastSolve(const std::vector<dynamics::ContactPoint>& lastSolved, std::vector<dynamics::ContactPoint>& points,
                            double horizon) {
  // The old points looked up by unordered pair: a pile has thousands. Matched by ordered
  // pairs, a sixth of the points of a pile's resting towers started from nothing each
  // step (their bodies hovered about the speed that marks them still), their solves
  // began up to 6 m/s from the answer, and the towers crept sideways at 1 cm/s for good.
  const auto pairKey = [](int a, int b) {
    return static_cast<long long>(std::min(a, b)) << 32 | static_cast<unsigned>(std::max(a, b));
  };
  std::unordered_map<long long, std::vector<const dynamics::ContactPoint*>> oldOfPair;
  for (const dynamics::ContactPoint& old : lastSolved) oldOfPair[pairKey(old.a, old.b)].push_back(&old);
  for (dynamics::ContactPoint& p : points) {
    const auto found = oldOfPair.find(pairKey(p.a, p.b));
    if (found == oldOfPair.end()) continue;
    for (const dynamics::ContactPoint* old : found->second) {
      const double sameOrder = old->a == p.a ? 1.0 : -1.0;
      if ((old->point - p.point).norm() <= kWarmStartRadius && sameOrder * old->normal.dot(p.normal) > 0) {
        p.normalImpulse = old->normalImpulse * horizon;
        p.frictionImpulse = sameOrder * old->frictionImpulse * horizon;
        break;
      }
    }
  }
}

}  // namespace polysim::sim
