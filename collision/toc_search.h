#pragma once
// The internals of collisionDetect() (time_of_contact.h), shared by the scan of the
// interval (time_of_contact.cpp) and the root finders that refine a bracket
// (toc_root_finders.cpp). Not part of the module's interface.

#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "collision/intersection.h"
#include "collision/object.h"
#include "collision/time_of_contact.h"

namespace polysim::collision::toc {

/// Object index pairs, each (a, b) with a < b, in increasing order.
using PairIds = std::vector<std::pair<int, int>>;

/// The pairs that may come within the tolerance somewhere in the interval: not both
/// static, and their world boxes grown by their motion bounds overlap.
PairIds pairsThatCanMeet(const ObjectDatabase& db);

/// The pairs of `meeting` that may interpenetrate somewhere in the interval: all but the
/// convex pairs with separating axes whose separation at t = 0, less the motion bounds of
/// both, stays above minus the tolerance (kUnwatchedMarginFraction): a pair resting in a
/// settled stack, while a body lands on top. Leaves the database at t = 1.
/// `from`, when given, receives for each pair returned the earliest times in [0, 1] at
/// which it could interpenetrate and come within the band, by the same separation and
/// ObjNode::motionRate (0 when its separation is not measured by axes or its rates are
/// unknown).
struct WatchedFrom {
  std::vector<double> interpenetrating;
  std::vector<double> touching;
};
PairIds pairsThatCanInterpenetrate(ObjectDatabase& db, IntersectionWorkspace& ws, const PairIds& meeting,
                                   WatchedFrom* from = nullptr);

/// The state of the search: the database, its workspace, the pairs that can meet in the
/// interval, those of them that can interpenetrate, and the count of tests made.
struct Search {
  ObjectDatabase& db;
  IntersectionWorkspace& ws;
  PairIds meeting = pairsThatCanMeet(db);
  WatchedFrom watchedFrom = {};  // per watched pair: the earliest times it could interpenetrate, or touch
  PairIds watched = pairsThatCanInterpenetrate(db, ws, meeting, &watchedFrom);
  /// The watched pairs that can still interpenetrate inside the root finder's bracket,
  /// once it has narrowed them (bisect()); until then, empty and unused.
  PairIds inBracket = {};
  bool narrowed = false;
  int tests = 0;
  long pairTests = 0;   // pairs given to those tests, summed
  int separations = 0;  // states whose signed separation was measured

  /// Sets the database to time t and returns the status of the pairs: with their
  /// contacts, of every pair that can meet; without, only of those watched (a pair that
  /// cannot interpenetrate decides nothing in the search), or of those that can in the
  /// bracket once it has narrowed them.
  IntersectionResult statusAt(double t, bool contacts = false);
  /// The status at time t of the pairs `ids` alone (no contacts): only their objects are
  /// moved to t, the others stay where they were.
  IntersectionResult statusOfPairsAt(const PairIds& ids, double t);
  /// statusAt(t) where only interpenetration is told: a pair that does not interpenetrate
  /// may read separate though it is in contact (IntersectionOptions::tellContactFromApart).
  IntersectionResult interpenetrationAt(double t);
  /// Sets the database to time t and returns the pairs `ids` with their contacts (not
  /// counted as a query of contact reuse: IntersectionOptions::agesKeptContacts).
  IntersectionResult contactsOfPairsAt(const PairIds& ids, double t);
  /// interpenetrationAt(t) of the watched pairs that could interpenetrate by t
  /// (watchedFrom): whether any pair interpenetrates at t, for a time found by testing a
  /// few pairs only.
  IntersectionResult interpenetrationOfWatchedAt(double t);
  /// The watched pairs that may be within the band at t (the database's current time):
  /// those that could touch by t (watchedFrom) whose separation by the axes is at most
  /// the tolerance, and every one not measured by axes.
  PairIds nearingAt(double t);

 private:
  /// test4Intersection() of the pairs `ids` at the objects' current poses, counted.
  IntersectionResult testPairs(const PairIds& ids, bool contacts, bool tellContactFromApart = true, bool agesKept = true);
};

PairIds interpenetratingPairs(const IntersectionResult& r);
/// True when every pair of `ids` is in contact (not separate, not interpenetrating) in r.
bool allInContact(const IntersectionResult& r, const PairIds& ids);
/// True when no pair of `ids` is in contact in r.
bool noneInContact(const IntersectionResult& r, const PairIds& ids);

/// Signed separation (m) of some pairs at the current state: the least over them of the
/// distance apart, or minus the deepest penetration when one goes inside. Convex pairs
/// are measured exactly by the separating axis test; others polygon by polygon, only out
/// to the reach: beyond it their value is clamped to +-reach and only a bound.
struct Separation {
  double value = std::numeric_limits<double>::infinity();
  bool onlyBound = false;  // the least came from a clamped measure
  bool byAxes = true;      // every pair was measured by the separating axis test
};
Separation signedSeparation(Search& s, const PairIds& ids, double reach);

/// True when both objects of every pair list separating axes (convex_separation.h).
bool measuredByAxes(const ObjectDatabase& db, const PairIds& ids);
/// True when the pairs of `ids` are convex (measured by the separating axis test) and no
/// other pair can meet in the interval: then the
/// separation alone tells which side of the first contact a time lies on, and the full
/// test is needed only to confirm the root.
bool separationDecidesAlone(const Search& s, const PairIds& ids);

/// An interval known to hold the first contact.
struct Bracket {
  Bracket(double lo, double hi, PairIds hiPairs) : lo(lo), hi(hi), hiPairs(std::move(hiPairs)) {}
  double lo, hi;
  PairIds hiPairs;  // the pairs interpenetrating at hi
  /// False when one of hiPairs already touched at the bracket's start: then "the pair is
  /// in contact" says nothing about the new touch, and only narrowing the bracket helps.
  bool fresh = true;
  /// Largest relative motion (m) of the objects over the whole interval [0, 1].
  double motion = 0.0;
  /// The separation of hiPairs at lo and at hi, when the scan measured them.
  std::optional<Separation> atLo, atHi;
};

struct Found {
  double time;
  TocStop stop;
  /// The full test (with contacts) at `time`, when the search already made it.
  std::optional<IntersectionResult> atTime = std::nullopt;
};

/// What each guess of bisect() tests.
enum class BisectionTests {
  /// Only the bracket's hiPairs: a pair apart at both ends of a bracket is taken to stay
  /// apart inside it, the premise of the scan itself (collisionDetect(): a touch that
  /// begins and ends between two tests is missed). A landing pile's island watches some
  /// 60 resting pairs at each guess, for the one or two that cross. collisionDetect()
  /// checks the premise at the time found, with every pair that can meet, and bisects
  /// again watching every pair when it did not hold there.
  CrossingPairs,
  /// Every pair that can interpenetrate inside the bracket (Search::watched, narrowed as
  /// the bracket shrinks): the time found never interpenetrates.
  EveryWatchedPair,
};

/// The seed's root finder: halves the bracket until the state is contact. Leaves `br`
/// narrowed to where it stopped (its hiPairs: the pairs interpenetrating just past it).
Found bisect(Search& s, Bracket& br, BisectionTests tests);
/// Regula falsi on the signed separation of the bracket's pairs (TocMethod::RegulaFalsi);
/// leaves `br` as bisect() does.
Found regulaFalsi(Search& s, Bracket& br);

}  // namespace polysim::collision::toc
