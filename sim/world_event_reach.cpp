// What an event reaches (world.h): the bodies whose pairs an event tests again at its
// time, and the contacts the solver is given for the groups it disturbs. An island's
// other pairs keep their last test: an event elsewhere in a landing pile does not make
// them any more wanted, and testing them at every event cost a pile of 1000 a sixth of
// its work (README, "Events that test and solve only what they reach").

#include <algorithm>
#include <iterator>
#include <utility>

#include "collision/broadphase.h"
#include "collision/intersection.h"
#include "dynamics/disjoint_sets.h"
#include "sim/world.h"

namespace polysim::sim {

std::vector<char> World::bodiesAnEventReaches(const std::vector<int>& island,
                                              const std::vector<collision::PairResult>& contacts,
                                              const collision::TocResult& toc, bool everyBody) const {
  std::vector<char> want(bodies_.size(), 0);
  if (everyBody) {
    for (int i : island) want[i] = 1;
    return want;
  }
  dynamics::DisjointSets groups(static_cast<int>(bodies_.size()));  // bodies joined by contacts, not through the ground
  for (const collision::PairResult& p : contacts)
    if (!bodies_[p.a].isStatic && !bodies_[p.b].isStatic) groups.join(p.a, p.b);
  std::vector<char> reached(bodies_.size(), 0);  // by group root
  for (const auto& [a, b] : toc.crossing) reached[groups.root(a)] = reached[groups.root(b)] = 1;
  // A pair that may have come within the band and has no contacts yet is a new touch,
  // as an event's is: found only once it interpenetrated, it would be an event of its
  // own, and an approach left unsolved keeps its pairs in every bisection's tests.
  std::vector<std::pair<int, int>> held;
  if (!toc.nearing.empty())
    for (const collision::PairResult& p : contacts) held.push_back(bodyPair(p.a, p.b));
  std::sort(held.begin(), held.end());
  for (const auto& [a, b] : toc.nearing)
    if (!std::binary_search(held.begin(), held.end(), bodyPair(a, b))) reached[groups.root(a)] = reached[groups.root(b)] = 1;
  for (int i : island) want[i] = reached[groups.root(i)];
  return want;
}

std::vector<collision::PairResult> World::retestPairsOf(const collision::ObjectDatabase& db, const std::vector<char>& want,
                                                        std::vector<char>& tested,
                                                        std::vector<collision::PairResult>& contacts) {
  const auto bodyAt = [this](int k) { return islandIds_.empty() ? k : islandIds_[k]; };
  std::vector<char> now(bodies_.size(), 0);
  bool any = false;
  for (int k = 0; k < static_cast<int>(db.objects.size()); ++k) {
    const int i = bodyAt(k);
    if (want[i] && !tested[i] && !bodies_[i].isStatic) now[i] = 1, any = true;
  }
  if (!any) return {};
  const auto retested = [&](int a, int b) { return (now[a] || now[b]) && !tested[a] && !tested[b]; };
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<std::pair<int, int>> pairs;
  collision::candidateObjectPairs(db, boxes, pairs);
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const std::pair<int, int>& p) { return !retested(bodyAt(p.first), bodyAt(p.second)); }),
              pairs.end());
  collision::IntersectionOptions options;
  options.onlyPairs = &pairs;
  options.agesKeptContacts = false;  // the island's other pairs are still wanted
  std::vector<collision::PairResult> found = collision::test4Intersection(db, workspace_, options).pairs;
  for (collision::PairResult& p : found) p.a = bodyAt(p.a), p.b = bodyAt(p.b);
  contacts.erase(std::remove_if(contacts.begin(), contacts.end(),
                                [&](const collision::PairResult& p) { return retested(p.a, p.b); }),
                 contacts.end());
  contacts.insert(contacts.end(), found.begin(), found.end());
  for (size_t i = 0; i < now.size(); ++i) tested[i] = tested[i] || now[i];
  return found;
}

std::vector<collision::PairResult> World::reachedAtEvent(
    const collision::ObjectDatabase& db, std::vector<collision::PairResult> solverContacts,
    const std::vector<std::pair<int, int>>& crossing, std::vector<char>& tested, std::vector<collision::PairResult>& contacts,
    const std::function<std::vector<collision::PairResult>(const std::vector<collision::PairResult>&)>& remake) {
  for (;;) {
    // solverContacts is not read again before it is remade below.
    std::vector<collision::PairResult> reached = reach_.reached(std::move(solverContacts), crossing, bodies_, sizes_);
    std::vector<char> want(bodies_.size(), 0);
    bool more = false;
    for (const collision::PairResult& p : reached)
      for (int i : {p.a, p.b})
        if (!bodies_[i].isStatic && !tested[i]) want[i] = 1, more = true;
    if (!more) return reached;
    std::vector<collision::PairResult> found = retestPairsOf(db, want, tested, contacts);
    noteContacts(found, report_.events.back().time);
    std::vector<collision::PairResult>& logged = report_.events.back().toc.pairs;
    logged.insert(logged.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
    solverContacts = remake(contacts);
  }
}

}  // namespace polysim::sim
