#include "sim/speculative_contacts.h"

#include <algorithm>
#include <map>
#include <utility>

namespace polysim::sim {

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
  }
  for (const auto& [pair, p] : widened) contacts.push_back(std::move(*p));  // the new ones
  return contacts;
}

}  // namespace polysim::sim
