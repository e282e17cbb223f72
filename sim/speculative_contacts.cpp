#include "sim/speculative_contacts.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "collision/broadphase.h"
#include "sim/contact_points.h"

namespace polysim::sim {
namespace {

// How far (m) point p lies from contact c's points across its normal (along it, a
// detector's point and a widened one of the same features differ by their gaps): from
// the point, from the segment, or from the polygon (0 over it, else from its rim).
double distanceAcross(const Eigen::Vector3d& p, const collision::Contact& c) {
  const auto across = [&c](const Eigen::Vector3d& d) { return (d - d.dot(c.normal) * c.normal).norm(); };
  const auto toSegment = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double s = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    return across(p - (a + s * ab));
  };
  const std::vector<Eigen::Vector3d>& v = c.points;
  if (v.size() == 1) return across(p - v[0]);
  if (v.size() == 2) return toSegment(v[0], v[1]);
  bool over = true;  // counter-clockwise about the normal: p is over the polygon while left of every edge
  double nearestRim = INFINITY;
  for (size_t k = 0; k < v.size(); ++k) {
    const Eigen::Vector3d& a = v[k];
    const Eigen::Vector3d& b = v[(k + 1) % v.size()];
    over = over && (b - a).cross(p - a).dot(c.normal) >= 0;
    nearestRim = std::min(nearestRim, toSegment(a, b));
  }
  return over ? 0.0 : nearestRim;
}

// Adds to `widened` each of the detector's contacts of the same pair (`detected`) that no
// widened contact covers: none shares its normal (kCoplanarContactAngle) with every one
// of its points within `tolerance` (m) of it across the normal. The detector's verdict is the one a step
// must keep, and the widened test may see it elsewhere. It may see a face where the
// detector saw two edges crossing at its rim: a solve on the face's normal alone let the
// edges sink past the tolerance, and a box landing spinning on another's edge took one
// event after another, each a few microseconds on, to the event bound. And where two
// edges lie nearly parallel, the widened test may put their crossing a long way along
// them: 1.8 cm from the detector's, on boxes turning at several rad/s apart, where the
// solver held the pair apart while the detector's crossing closed at 0.11 m/s (every
// event of that step stalled at once: pile of 1000, seed 6). Where they agree, nothing is
// added, and the solver sees what it saw before.
void keepContactsMissed(const collision::PairResult& detected, collision::PairResult& widened, double tolerance) {
  const double sameDirection = std::cos(kCoplanarContactAngle);
  const double orientation = detected.a == widened.a ? 1.0 : -1.0;  // normals point from b towards a
  const size_t widenedCount = widened.contacts.size();
  for (const collision::Contact& c : detected.contacts) {
    const Eigen::Vector3d normal = orientation * c.normal;
    const auto first = widened.contacts.begin(), last = first + static_cast<std::ptrdiff_t>(widenedCount);
    const auto covers = [&](const collision::Contact& w) {
      return w.normal.dot(normal) >= sameDirection &&
             std::all_of(c.points.begin(), c.points.end(),
                         [&](const Eigen::Vector3d& p) { return distanceAcross(p, w) <= tolerance; });
    };
    if (std::any_of(first, last, covers)) continue;
    collision::Contact& kept = widened.contacts.emplace_back(c);
    kept.normal = normal;
    if (orientation < 0) std::swap(kept.featureA, kept.featureB);
  }
}

// Every gap of the pair's widened contacts raised to at least `floor` (m), where the
// detector, which tests the polygons exactly, found the pair no closer. The widened test
// reads a feature beside a face by its level over the face's plane, and a corner by an
// edge pair's normal, and so may find overlaps that are not there:
// - A pair the detector did not find touching is more than the tolerance apart at every
//   feature. A box's top corner 1.5 cm beside another's bottom face and just above its
//   plane read 30 um to 1 mm deep, and the solver held that box tilted on it for good (a
//   top box of the tilted towers, seed 15, rocking at up to 0.1 m/s at 12 s). Its gaps
//   become the tolerance: the solver lets the feature close by no more than that in a
//   step, and the detector judges any real touch.
// - A touching pair is nowhere deeper than the detector's deepest point. A box leaning
//   across three columns had a corner 35 um above a face read 0.6 mm deep along a normal
//   2.5 degrees off the face's; the pushes out of that overlap moved it by a few mm/s, in
//   a cycle of nine steps, for 15 s, and kept its island of 100 boxes awake (pile of
//   1000, seed 22, at rest by 18.6 s).
void gapsAtLeast(collision::PairResult& pair, double floor) {
  for (collision::Contact& c : pair.contacts) {
    if (c.separation >= floor) continue;
    c.gaps.resize(c.points.size(), c.separation);
    c.separation = INFINITY;
    for (double& gap : c.gaps) c.separation = std::min(c.separation, gap = std::max(gap, floor));
  }
}

// The deepest separation (m) of a pair's contacts.
double deepestOf(const collision::PairResult& pair) {
  double deepest = INFINITY;
  for (const collision::Contact& c : pair.contacts) deepest = std::min(deepest, c.separation);
  return deepest;
}

}  // namespace

std::vector<collision::PairResult> speculativePairs(const collision::ObjectDatabase& db,
                                                    collision::IntersectionWorkspace& workspace, double reach,
                                                    const std::vector<int>& bodyOf,
                                                    const std::function<SpeculativeRole(int)>& roleOf,
                                                    const std::vector<char>* onlyOf) {
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
  if (!anyMoving) return {};
  collision::IntersectionOptions options;
  std::vector<std::pair<int, int>> among;  // the pairs with a marked body the whole test would try
  if (onlyOf) {  // sweep and prune over all, then the pairs with a marked body (in the same order)
    std::vector<Eigen::AlignedBox3d> boxes;
    collision::candidateObjectPairs(near, boxes, among);
    among.erase(std::remove_if(among.begin(), among.end(),
                               [&](const std::pair<int, int>& p) {
                                 return !(*onlyOf)[bodyOfNear[p.first]] && !(*onlyOf)[bodyOfNear[p.second]];
                               }),
                among.end());
    options.onlyPairs = &among;
  }
  std::vector<collision::PairResult> found = collision::test4Intersection(near, workspace, options).pairs;
  for (collision::PairResult& p : found) p.a = bodyOfNear[p.a], p.b = bodyOfNear[p.b];
  return found;
}

std::vector<collision::PairResult> mergeSpeculative(const std::vector<collision::PairResult>& found,
                                                    const std::vector<collision::PairResult>& touching, double tolerance,
                                                    const std::function<bool(const collision::PairResult&)>& speculate) {
  // Nothing interpenetrates within the tolerance, so nothing should within the reach; a
  // pair classed so anyway (judged by the wider band) keeps its contacts.
  // The widened pairs by their body pair, smaller index first: a sorted array searched by
  // halves (a map allocated a node per pair, for each of a landing pile's events).
  struct Widened {
    std::pair<int, int> key;
    const collision::PairResult* pair;
    bool taken = false;  // merged into a pair of `touching`
  };
  const auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  std::vector<Widened> widened;
  for (const collision::PairResult& p : found)
    if (p.status == collision::Status::Contact && speculate(p)) widened.push_back({key(p.a, p.b), &p});
  const auto byKey = [](const Widened& x, const Widened& y) { return x.key < y.key; };
  std::stable_sort(widened.begin(), widened.end(), byKey);  // of a pair found twice, the first counts
  widened.erase(std::unique(widened.begin(), widened.end(), [](const Widened& x, const Widened& y) { return x.key == y.key; }),
                widened.end());
  std::vector<collision::PairResult> contacts;
  contacts.reserve(widened.size() + touching.size());
  for (const collision::PairResult& p : touching) {
    const Widened wanted{key(p.a, p.b), nullptr};
    const auto at = std::lower_bound(widened.begin(), widened.end(), wanted, byKey);
    if (at == widened.end() || at->key != wanted.key || at->taken) {
      contacts.push_back(p);
      continue;
    }
    contacts.push_back(*at->pair);
    at->taken = true;
    gapsAtLeast(contacts.back(), deepestOf(p));
    keepContactsMissed(p, contacts.back(), tolerance);
  }
  for (const Widened& w : widened)  // the new ones
    if (!w.taken) contacts.push_back(*w.pair), gapsAtLeast(contacts.back(), tolerance);
  return contacts;
}

std::vector<collision::PairResult> withSpeculativeContacts(
    const collision::ObjectDatabase& db, collision::IntersectionWorkspace& workspace, double reach,
    const std::vector<int>& bodyOf, const std::vector<collision::PairResult>& touching,
    const std::function<SpeculativeRole(int)>& roleOf, const std::function<bool(const collision::PairResult&)>& speculate) {
  return mergeSpeculative(speculativePairs(db, workspace, reach, bodyOf, roleOf), touching, db.tolerance, speculate);
}

}  // namespace polysim::sim
