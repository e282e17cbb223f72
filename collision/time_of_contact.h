#pragma once
// collisionDetect(): the seed's search for the time of "just contact" in an interval.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "collision/intersection.h"
#include "collision/object.h"

namespace polysim::collision {

/// How the time of contact is guessed once an interval is known to hold it.
enum class TocMethod {
  /// The seed's method: the middle of the bracket, until the state is contact.
  Bisection,
  /// Regula falsi (Illinois variant, with interpolation through the latest points for
  /// exact measures) on the signed separation of the pairs that interpenetrate (distance
  /// apart, minus depth inside), with a bisection step whenever it stalls; aims at the
  /// exact touching time. Where the separating axis test measures every pair that can
  /// meet (convex objects with few face directions), it also scans the sub-intervals
  /// and tests only to decide the band within the tolerance and to confirm the root.
  RegulaFalsi,
};

/// Why collisionDetect() returned.
enum class TocStop {
  NoInterpenetration,  // nothing interpenetrated up to t = 1: returned t = 1
  Contact,             // found a state of just contact before the interpenetration
  TimeTolerance,       // the bracket narrowed until nothing moves more than the contact
                       // tolerance inside it (kTimeTolerance without motion bounds): returned its start
  IterationLimit,      // kMaxTimeOfContactIterations guesses made: returned the bracket's start
};

struct TocOptions {
  TocMethod method = TocMethod::Bisection;
  /// Bisection: each guess tests every pair that can interpenetrate inside the bracket,
  /// not only those crossing at its end (toc_search.h). Slower; the reference the
  /// default is checked against, as the seed's search was written.
  bool watchEveryPairWhileBisecting = false;
  /// At an event (a time found before the interval's end), gather the contacts of every
  /// pair that can meet (the seed's behaviour). Off: only the pairs that stopped the
  /// interval (TocResult::crossing) are given with their contacts, for a caller that
  /// gathers the others it needs itself (the step loop: the pairs of the groups an event
  /// reaches); the verdict still covers every pair, so nothing interpenetrates at the
  /// time returned. At the interval's end every pair is gathered either way.
  bool gatherAtEvent = true;
};

struct TocResult {
  /// The returned time in [0, 1]; the database is left at this time.
  double time = 1.0;
  /// Contact or separate, never interpenetrating.
  Status status = Status::Separate;
  /// The pairs that are not separate at `time`, with their contacts (at an event without
  /// TocOptions::gatherAtEvent, only those of `crossing`).
  std::vector<PairResult> pairs;
  /// Intersection tests made (each setTime + test counts one).
  int iterations = 0;
  /// Pairs those tests were given, summed over the tests: the search's work.
  long pairTests = 0;
  /// States whose signed separation regula falsi measured instead of testing them (0
  /// for bisection); a separation of convex objects costs a fraction of a test.
  int separations = 0;
  /// Bisections done again testing every watched pair at each guess (toc_search.h,
  /// bisect()): the time found by testing only the crossing pairs had another pair
  /// interpenetrating. 0 or 1.
  int bisectionsRedone = 0;
  /// The pairs (object indices, a < b) found interpenetrating just past `time`: what
  /// stopped the interval there. Empty when nothing interpenetrated up to t = 1.
  std::vector<std::pair<int, int>> crossing;
  /// At an event without TocOptions::gatherAtEvent: the pairs other than `crossing` among
  /// those that can interpenetrate in the interval (pairsWatched) that may have come
  /// within the band by `time` (toc::Search::nearingAt()), whose contacts were not
  /// gathered (a pair that cannot interpenetrate in it is gathered at its end). A caller that keeps contacts from earlier tests retests those it
  /// does not hold.
  std::vector<std::pair<int, int>> nearing;
  /// Pairs that can meet in the interval, and those of them the search's verdict tests
  /// watched: the pairs that can interpenetrate in it (a settled stack's resting pairs
  /// cannot while a body lands on top). The contacts returned are of every pair that can meet.
  int pairsMeeting = 0;
  int pairsWatched = 0;
  /// Sub-intervals the interval was split into against tunnelling (1: none).
  int subintervals = 1;
  /// False when the split against tunnelling needed more than kMaxSubintervals: some pair
  /// moves so far for its thickness that it may pass through another between two tests.
  bool tunnellingGuarded = true;
  TocStop stoppedBy = TocStop::NoInterpenetration;
};

/// The database interpenetrates at t = 0; what() names the pairs.
class InitialInterpenetration : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Finds the time of just contact in the interval [0, 1] (the seed's collisionDetect).
///
/// Expects every object at its t = 1 pose; moving objects have ctrans set. Tests t = 1;
/// when nothing interpenetrates, returns t = 1 with the contacts there. Otherwise sets
/// the database to guessed times (bisection or regula falsi) until the state is contact
/// within the tolerance band and no pair interpenetrates, and returns that time. A pair
/// that already touched at the bracket's start (a box rocking onto another corner)
/// shows "contact" all along, so for it the bracket is narrowed until no object moves
/// more than the tolerance inside it, and its start is returned.
///
/// Tunnelling: when the objects' motion bounds (ObjNode::motionBound) let a pair move
/// farther than kTunnelingSafety times the thinner one's thickness, the interval is first
/// split into sub-intervals tested in order, so an object cannot pass through another
/// between two tests. Guaranteed only when the motion bounds hold (they must cover
/// rotation: angle times the farthest vertex's distance from the rotation centre) and
/// the split stays within kMaxSubintervals; contacts shorter than a sub-interval that
/// begin and end inside it (a glancing touch) can still be missed.
///
/// Throws InitialInterpenetration if the database interpenetrates at t = 0.
TocResult collisionDetect(ObjectDatabase& db, const TocOptions& options = {});
/// The same with the caller's scratch memory, so that repeated calls (every step of a
/// simulation) do not allocate per-face caches again.
TocResult collisionDetect(ObjectDatabase& db, IntersectionWorkspace& workspace, const TocOptions& options = {});

std::string toString(TocMethod method);
/// The method toString names ("bisection", "regula-falsi"); throws std::invalid_argument
/// for any other name.
TocMethod tocMethodNamed(const std::string& name);
std::string toString(TocStop stop);

}  // namespace polysim::collision
