#include "sim/speculative_contacts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "sim/contact_points.h"

namespace polysim::sim {
namespace {

// Adds to `widened` each of the detector's contacts of the same pair (`detected`) whose
// normal none of the widened contacts shares (kCoplanarContactAngle): the widened test
// may see a face where the detector saw two edges crossing at its rim, and the detector's
// verdict is the one a step must keep. A solve on the face's normal alone let the edges
// sink past the tolerance: a box landing spinning on another's edge took one event after
// another, each a few microseconds on, to the event bound. Where they agree, nothing is
// added, and the solver sees what it saw before.
void keepContactsMissed(const collision::PairResult& detected, collision::PairResult& widened) {
  const double sameDirection = std::cos(kCoplanarContactAngle);
  const double orientation = detected.a == widened.a ? 1.0 : -1.0;  // normals point from b towards a
  const size_t widenedCount = widened.contacts.size();
  for (const collision::Contact& c : detected.contacts) {
    const Eigen::Vector3d normal = orientation * c.normal;
    const auto first = widened.contacts.begin(), last = first + static_cast<std::ptrdiff_t>(widenedCount);
    if (std::any_of(first, last, [&](const collision::Contact& w) { return w.normal.dot(normal) >= sameDirection; })) continue;
    collision::Contact& kept = widened.contacts.emplace_back(c);
    kept.normal = normal;
    if (orientation < 0) std::swap(kept.featureA, kept.featureB);
  }
}

}  // namespace

std::vector<collision::PairResult> withSpeculativeContacts(
    const collision::ObjectDatabase& db, collision::IntersectionWorkspace& workspace, double reach,
    const std::vector<int>& bodyOf, const std::vector<collision::PairResult>& touching,
    const std::function<SpeculativeRole(int)>& roleOf, const std::function<bool(const collision::PairResult&)>& speculate) {
  // The database of the objects tested, still ones marked static: the test skips pairs
  // of static objects, so bodies at rest cost nothing against each other.
  collision::ObjectDatabase near;
  near.tolerance = reach;
  std::vector<int> bodyOfNear;
  bool anyMoving = false;
  for (int k = 0; k < static_cast<int>(db.objects.size()); ++k) {
    const SpeculativeRole role = roleOf(k);
    if (role == SpeculativeRole::Left) continue;
    anyMoving = anyMoving || (role == SpeculativeRole::Moving && !db.objects[k].isStatic);
    near.objects.push_back(db.objects[k]);
    near.objects.back().isStatic = near.objects.back().isStatic || role == SpeculativeRole::Still;
    bodyOfNear.push_back(bodyOf.empty() ? k : bodyOf[k]);
  }
  if (!anyMoving) return touching;
  collision::IntersectionResult found = collision::test4Intersection(near, workspace);

  // Nothing interpenetrates within the tolerance, so nothing should within the reach; a
  // pair classed so anyway (judged by the wider band) keeps its contacts.
  std::map<std::pair<int, int>, collision::PairResult*> widened;
  const auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (collision::PairResult& p : found.pairs) {
    p.a = bodyOfNear[p.a], p.b = bodyOfNear[p.b];
    if (p.status == collision::Status::Contact && speculate(p)) widened.emplace(key(p.a, p.b), &p);
  }
  std::vector<collision::PairResult> contacts;
  contacts.reserve(widened.size() + touching.size());
  for (const collision::PairResult& p : touching) {
    const auto at = widened.find(key(p.a, p.b));
    if (at == widened.end()) {
      contacts.push_back(p);
      continue;
    }
    contacts.push_back(std::move(*at->second));
    widened.erase(at);
    keepContactsMissed(p, contacts.back());
  }
  for (const auto& [pair, p] : widened) contacts.push_back(std::move(*p));  // the new ones
  return contacts;
}

}  // namespace polysim::sim
