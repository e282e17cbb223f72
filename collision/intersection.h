#pragma once
// test4Intersection(): the seed's static test of the object database.

#include <optional>
#include <vector>

#include "collision/area_cover.h"
#include "collision/area_on_patch.h"
#include "collision/broadphase.h"
#include "collision/contact.h"
#include "collision/contact_reuse.h"
#include "collision/object.h"
#include "collision/polygon_tests.h"
#include "collision/separation_memo.h"

namespace polysim::collision {

struct IntersectionOptions {
  /// Gather the contact geometry of pairs in contact (points, lines, areas). Without
  /// it, a pair's test stops at its first interpenetrating polygon pair (its depth is
  /// then a lower bound).
  bool contacts = true;
  /// Return as soon as one pair interpenetrates (its depth is then a lower bound), for
  /// callers that only need the verdict, such as collisionDetect()'s bisection.
  bool stopAtInterpenetration = false;
  /// Without contacts, whether a pair that cannot interpenetrate is told in contact from
  /// apart. Off: two convex objects that the separating axis test finds apart, by no more
  /// than the tolerance, are reported separate without their polygons' test, though they
  /// may be within the tolerance (in contact); for callers that want only which pairs
  /// interpenetrate, such as collisionDetect()'s scan. A settling pile's pairs sit there
  /// by the thousand: 30% of a landing pile's verdicts went to the polygons for it.
  bool tellContactFromApart = true;
  /// When set, only these pairs of objects (i < j each, sorted) are tested, in place of
  /// the sweep and prune over all objects: the caller promises that no other pair is
  /// within the tolerance (collisionDetect() gives the pairs that can meet in its
  /// interval). The result is the same, at the cost of the pairs given.
  const std::vector<std::pair<int, int>>* onlyPairs = nullptr;
  /// With contacts: the test counts as one of the queries after which contact reuse drops
  /// what no query used (ContactReuse::endQuery). Off for a test of a few pairs among
  /// many (the pairs an event reaches), which would otherwise age the rest: a resting
  /// pile's pairs, tested once a step, would be dropped by a landing's dozens of events.
  bool agesKeptContacts = true;
};

struct IntersectionResult {
  /// The worst status over all pairs.
  Status status = Status::Separate;
  /// Every pair that is not separate, in database order; in a pair of a static and a
  /// moving object, the moving one is `a`.
  std::vector<PairResult> pairs;
  /// Polygon pairs that reached the polygon-level test: the work the broad steps left.
  long polygonPairsTested = 0;
  /// Pairs whose contacts were reused rather than tested (contact_reuse.h).
  int pairsReused = 0;
};

/// Reusable scratch memory of the test (per-object world faces, candidate lists), so that
/// repeated queries do not allocate. One workspace serves one thread.
struct IntersectionWorkspace {
  std::vector<Eigen::AlignedBox3d> containers;  // per object, for the pairs' sweep and prune
  std::vector<std::pair<int, int>> objectPairs;
  std::vector<WorldFaces> faces;
  DescentScratch descent;
  std::vector<FacePair> candidates;
  std::vector<Contact> raw;
  PolygonScratch scratch;
  AreaCover cover;
  AreaOnPatch patch;
  /// Pairs in contact kept from earlier tests; off unless enabled (contact_reuse.h).
  ContactReuse reuse;
  /// Separations by the separating axis test kept with their poses; off unless enabled
  /// (separation_memo.h). Exact: a pair measured again at the same poses gets the same value.
  SeparationMemo separations;
};

/// Tests every pair of objects of the database at their current transforms (static pairs
/// excepted; pairs whose containers are apart are skipped by a sweep and prune) with the database's tolerance: separate, contact (within tolerance; touching
/// counts) or interpenetrating (a feature more than the tolerance inside the other; for
/// two convex objects with separating axes, their penetration depth more than it).
/// With the workspace's contact reuse enabled, a pair in contact that has hardly moved
/// since its last full test keeps that test's contacts (to within
/// kContactReuseFraction of the tolerance).
IntersectionResult test4Intersection(const ObjectDatabase& db, IntersectionWorkspace& workspace,
                                     const IntersectionOptions& options = {});
IntersectionResult test4Intersection(const ObjectDatabase& db, const IntersectionOptions& options = {});

/// The same test for objects a and b of the database only (normals from b towards a).
/// `axesSeparation`, when given, receives the pair's separation by the separating axis
/// test (convexSeparation()) when the test measured it, and is left empty otherwise.
PairResult testObjectPair(const ObjectDatabase& db, int a, int b, IntersectionWorkspace& workspace,
                          const IntersectionOptions& options, long* polygonPairsTested = nullptr,
                          std::optional<double>* axesSeparation = nullptr);

}  // namespace polysim::collision
