#pragma once
// Contact reuse: a pair of objects that has hardly moved against itself since its last
// full test keeps that test's contacts (Box2D v3 keeps a manifold within 5 cm and 11
// degrees; Jolt caches by relative pose too). Exactness sets the threshold here: a pair
// is reused only while no point of one object has moved by more than
// kContactReuseFraction of the tolerance relative to the other, so every reused gap is
// within that distance of what a fresh test would measure. A resting pyramid (moving
// 1e-11 m in half a second) then pays for its contacts once; a settling pile, whose
// bodies move millimetres a step, tests afresh.
// Only pairs of convex objects with separating axes are kept: their verdict is their
// separation by the separating axis test, which a motion of at most d changes by at most
// d. A pair judged by its polygons' depth (not convex, or too many faces for the axes)
// has no one number that bounds its verdict, and its contacts' gaps do not: at the edge
// of interpenetrating, random such pairs read 2.9 to 7.3 um shallower than the verdict
// (tolerance 100 um), and a cup in a column 66 um. Kept on its gaps, such a pair stayed
// "in contact" where a fresh test found it interpenetrating.

#include <Eigen/Geometry>
#include <optional>
#include <unordered_map>

#include "collision/contact.h"
#include "collision/object.h"

namespace polysim::collision {

class ContactReuse {
 public:
  /// Reuse is off until enabled: a workspace shared by unrelated databases (tests, the
  /// command line) then never mixes them up. Objects without an id (ObjNode::id < 0)
  /// are never reused.
  void enable(bool on = true) { enabled_ = on; }
  bool enabled() const { return enabled_; }

  /// The kept result of objects a and b of the database (normals from b towards a) when
  /// it is still valid at their poses now: the same meshes, the same tolerance, no point
  /// of a moved by more than kContactReuseFraction * tolerance relative to b, the kept
  /// separation (separating axis test) that far above -tolerance and the kept contacts'
  /// deepest gap that far below it, so the pair's status cannot have changed. Its
  /// contacts ride on b's pose; its indices are a and b.
  std::optional<PairResult> find(const ObjectDatabase& db, int a, int b);
  /// Keeps the full test's result of a pair of convex objects in contact, with
  /// `separation`, theirs by the separating axis test at the tested poses (as
  /// testObjectPair() measured it). Pairs in no contact, or without that separation (not
  /// measured by axes), are not kept.
  void keep(const ObjectDatabase& db, const PairResult& pair, const std::optional<double>& separation);
  /// Ends one test of the database with contacts: results no test has used for
  /// kStaleQueries such tests are dropped, so the memory follows the pairs in contact, not
  /// every pair ever seen. Verdict-only tests do not count: collisionDetect() leaves out
  /// of them pairs that cannot interpenetrate, which still rest and are still wanted.
  void endQuery();
  /// How many pairs were reused since construction.
  long reused() const { return reused_; }

 private:
  struct Key {
    int a, b;
    double tolerance;
    bool operator==(const Key& o) const { return a == o.a && b == o.b && tolerance == o.tolerance; }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const;
  };
  struct Kept {
    const PolygonMesh* meshA;
    const PolygonMesh* meshB;
    Eigen::Isometry3d X_BA;  // a's pose in b's frame when tested
    double reachA;           // m, farthest vertex of a from a's origin
    double separation;       // m, by the separating axis test: what decides interpenetration
    std::vector<Contact> contacts;  // in b's frame; the pair was in contact
    long usedAt;
  };
  static constexpr long kStaleQueries = 64;

  bool enabled_ = false;
  long query_ = 0;
  long reused_ = 0;
  std::unordered_map<Key, Kept, KeyHash> results_;
};

}  // namespace polysim::collision
