// The root finders of collisionDetect(): given a bracket [lo, hi] whose end hi
// interpenetrates, find the time of just contact inside it.

#include <algorithm>
#include <cmath>
#include <utility>

#include "collision/aabb.h"
#include "collision/broadphase.h"
#include "collision/convex_separation.h"
#include "collision/polygon_distance.h"
#include "collision/toc_search.h"
#include "collision/tolerances.h"

namespace polysim::collision::toc {

IntersectionResult Search::statusAt(double t, bool contacts) {
  db.setTime(t);
  // No other pair comes within the tolerance in the interval; of those, only the watched
  // can interpenetrate, and a verdict wants nothing else.
  return testPairs(contacts ? meeting : narrowed ? inBracket : watched, contacts);
}

IntersectionResult Search::statusOfPairsAt(const PairIds& ids, double t) {
  for (const auto& [a, b] : ids)
    for (int i : {a, b})
      if (ObjNode& o = db.objects[i]; o.ctrans) o.ctrans(t, o.info, o.X_WO);
  return testPairs(ids, false);
}

IntersectionResult Search::interpenetrationAt(double t) {
  db.setTime(t);
  return testPairs(narrowed ? inBracket : watched, false, false);
}

IntersectionResult Search::interpenetrationOfWatchedAt(double t) {
  PairIds ids;
  for (size_t k = 0; k < watched.size(); ++k)
    if (watchedFrom.interpenetrating[k] <= t) ids.push_back(watched[k]);
  db.setTime(t);
  return testPairs(ids, false, false);
}

PairIds Search::nearingAt(double t) {
  PairIds ids;
  for (size_t k = 0; k < watched.size(); ++k) {
    if (watchedFrom.touching[k] > t) continue;
    const auto [a, b] = watched[k];
    const std::optional<double> separation = ws.separations.measure(db.objects[a], db.objects[b]);
    if (!separation || *separation <= db.tolerance) ids.push_back(watched[k]);
  }
  return ids;
}

IntersectionResult Search::contactsOfPairsAt(const PairIds& ids, double t) {
  db.setTime(t);
  return testPairs(ids, true, true, false);
}

IntersectionResult Search::testPairs(const PairIds& ids, bool contacts, bool tellContactFromApart, bool agesKept) {
  ++tests;
  pairTests += static_cast<long>(ids.size());
  IntersectionOptions options;
  options.contacts = contacts;
  options.tellContactFromApart = tellContactFromApart;
  options.onlyPairs = &ids;
  options.agesKeptContacts = agesKept;
  return test4Intersection(db, ws, options);
}

namespace {

// False when A and B are convex and their separation at their current poses, less
// `motion` (m, how far their points can move towards each other), stays above the
// depth of interpenetration by a margin (kUnwatchedMarginFraction): then no pose within
// that motion interpenetrates.
bool mayInterpenetrate(SeparationMemo& memo, const ObjNode& A, const ObjNode& B, double motion, double tolerance) {
  const double least = -(1.0 - kUnwatchedMarginFraction) * tolerance;
  // Far enough apart by the last measure, less how far both have moved since: no need to
  // measure again (the verdict cannot be interpenetrating either way).
  if (const std::optional<double> bound = memo.lowerBound(A, B); bound && *bound - motion > least) return false;
  const std::optional<double> separation = memo.measure(A, B);
  return !separation || *separation - motion <= least;
}

}  // namespace

PairIds pairsThatCanInterpenetrate(ObjectDatabase& db, IntersectionWorkspace& ws, const PairIds& meeting,
                                   WatchedFrom* from) {
  PairIds ids;
  db.setTime(0.0);
  const auto rate = [](const ObjNode& o) { return o.ctrans ? o.motionRate : 0.0; };
  for (const auto& [a, b] : meeting) {
    const ObjNode& A = db.objects[a];
    const ObjNode& B = db.objects[b];
    if (!mayInterpenetrate(ws.separations, A, B, A.motionBound + B.motionBound, db.tolerance)) continue;
    ids.emplace_back(a, b);
    if (!from) continue;
    // Its points close by at most (rate A + rate B) t by time t (the memo has the
    // separation just measured).
    const std::optional<double> separation = ws.separations.measure(A, B);
    const double closing = rate(A) + rate(B);
    const auto timeToClose = [&](double room) {
      return !separation || room <= 0.0 || !std::isfinite(closing) ? 0.0 : room / closing;
    };
    from->interpenetrating.push_back(timeToClose(separation.value_or(0.0) + (1.0 - kUnwatchedMarginFraction) * db.tolerance));
    from->touching.push_back(timeToClose(separation.value_or(0.0) - db.tolerance));
  }
  db.setTime(1.0);
  return ids;
}

namespace {

// A pair result's object indices in PairIds order (a < b; a result may list the moving
// object first).
std::pair<int, int> idsOf(const PairResult& p) { return std::minmax(p.a, p.b); }

}  // namespace

PairIds interpenetratingPairs(const IntersectionResult& r) {
  PairIds ids;
  for (const PairResult& p : r.pairs)
    if (p.status == Status::Interpenetrating) ids.push_back(idsOf(p));
  std::sort(ids.begin(), ids.end());
  return ids;
}

bool allInContact(const IntersectionResult& r, const PairIds& ids) {
  for (const std::pair<int, int>& pair : ids) {
    const auto it = std::find_if(r.pairs.begin(), r.pairs.end(), [&](const PairResult& p) { return idsOf(p) == pair; });
    if (it == r.pairs.end() || it->status != Status::Contact) return false;
  }
  return true;
}

bool noneInContact(const IntersectionResult& r, const PairIds& ids) {
  for (const PairResult& p : r.pairs)
    if (p.status == Status::Contact && std::find(ids.begin(), ids.end(), idsOf(p)) != ids.end()) return false;
  return true;
}

Separation signedSeparation(Search& s, const PairIds& ids, double reach) {
  ++s.separations;
  Separation least;
  auto take = [&least](double value, bool onlyBound) {
    if (value < least.value) least.value = value, least.onlyBound = onlyBound;
  };
  for (const auto& [a, b] : ids) {
    const ObjNode& A = s.db.objects[a];
    const ObjNode& B = s.db.objects[b];
    if (const std::optional<double> convex = s.ws.separations.measure(A, B)) {
      take(*convex, false);
      continue;
    }
    least.byAxes = false;
    const std::optional<Eigen::AlignedBox3d> region = overlapRegion(A, B, reach);
    if (!region) {
      take(reach, true);
      continue;
    }
    if (s.ws.faces.size() < s.db.objects.size()) s.ws.faces.resize(s.db.objects.size());
    WorldFaces& fa = s.ws.faces[a];
    WorldFaces& fb = s.ws.faces[b];
    fa.reset(A);
    fb.reset(B);
    double depth = 0.0, distance = reach;
    forEachCandidatePair(A, fa, B, fb, *region, reach, s.ws.descent, [&](int pa, int pb) {
      // Polygons whose boxes lie farther apart than the tolerance cannot go inside each
      // other (penetrationDepth sees a polygon only within the tolerance of the other's
      // plane and over it), nor come nearer than their boxes.
      const double apart = fa.box(pa).exteriorDistance(fb.box(pb));
      if (apart > s.db.tolerance && (depth > 0.0 || apart >= distance)) return true;
      const PolygonView p = fa.view(pa), q = fb.view(pb);
      const double d = penetrationDepth(p, q, s.db.tolerance, s.ws.scratch);
      if (d > 0.0) depth = std::max(depth, d);
      else if (depth == 0.0) distance = std::min(distance, polygonDistance(p, q, s.ws.scratch, distance));
      return depth < reach;  // deeper than the reach is only known to be deep
    });
    depth = std::min(depth, reach);
    const double value = depth > 0.0 ? -depth : distance;
    take(value, std::abs(value) >= reach);
  }
  return least;
}

PairIds pairsThatCanMeet(const ObjectDatabase& db) {
  const size_t n = db.objects.size();
  std::vector<Eigen::AlignedBox3d> containers(n), reach(n);
  for (size_t i = 0; i < n; ++i) {
    containers[i] = worldContainer(db.objects[i]);
    reach[i] = grow(containers[i], db.objects[i].motionBound + db.tolerance);  // a superset: both grown by eps
  }
  PairIds candidates, ids;
  overlappingBoxPairs(db, reach, candidates);
  for (const auto& [a, b] : candidates) {
    const ObjNode& A = db.objects[a];
    const ObjNode& B = db.objects[b];
    // Every pose in the interval lies within the current box grown by the motion bound.
    if (grow(containers[a], A.motionBound + db.tolerance).intersects(grow(containers[b], B.motionBound))) ids.emplace_back(a, b);
  }
  return ids;
}

bool measuredByAxes(const ObjectDatabase& db, const PairIds& ids) {
  for (const auto& [a, b] : ids)
    if (!hasSeparatingAxes(*db.objects[a].mesh) || !hasSeparatingAxes(*db.objects[b].mesh)) return false;
  return true;
}

bool separationDecidesAlone(const Search& s, const PairIds& ids) {
  if (!measuredByAxes(s.db, ids)) return false;
  for (const std::pair<int, int>& pair : s.meeting)
    if (std::find(ids.begin(), ids.end(), pair) == ids.end()) return false;
  return true;
}

namespace {

// True when the bracket is narrow enough that nothing moves more than eps inside it (or
// below kTimeTolerance when the motion is unknown): its start is then "just contact".
bool narrowEnough(const Bracket& br, double eps) {
  if (br.motion > 0.0) return (br.hi - br.lo) * br.motion <= eps;
  return br.hi - br.lo < kTimeTolerance;
}

}  // namespace

namespace {

// How much the bracket shrinks between two narrowings of its pairs (bisect()): each costs
// a separation per pair still watched (a fraction of a test of the pair), and the pairs
// it can drop are few until the bracket is a small part of the step.
constexpr double kNarrowingShrink = 4.0;

// Keeps, of the pairs watched in the bracket, those that can interpenetrate somewhere in
// it: measured at its middle, each pair's points move towards each other by at most the
// sum of the objects' motion rates times half its width (ObjNode::motionRate). The pairs
// interpenetrating at its end always stay. In a landing pile's island of 600 boxes,
// most of the 500 pairs watched are resting contacts that need the whole step to sink
// a tolerance, not the few microseconds a bisection ends on.
void narrowToBracket(Search& s, const Bracket& br) {
  s.db.setTime(0.5 * (br.lo + br.hi));
  const double reach = 0.5 * (br.hi - br.lo);  // from the middle to either end
  const auto rate = [](const ObjNode& o) { return o.ctrans ? o.motionRate : 0.0; };
  PairIds kept;
  for (const auto& [a, b] : s.narrowed ? s.inBracket : s.watched) {
    const ObjNode& A = s.db.objects[a];
    const ObjNode& B = s.db.objects[b];
    const bool crossing = std::find(br.hiPairs.begin(), br.hiPairs.end(), std::pair{a, b}) != br.hiPairs.end();
    if (crossing || mayInterpenetrate(s.ws.separations, A, B, (rate(A) + rate(B)) * reach, s.db.tolerance)) kept.emplace_back(a, b);
  }
  s.inBracket = std::move(kept);
  s.narrowed = true;
}

}  // namespace

Found bisect(Search& s, Bracket& br, BisectionTests tests) {
  const bool watchAll = tests == BisectionTests::EveryWatchedPair;
  double narrowedAt = 2.0 * kNarrowingShrink;  // wider than any bracket: narrow at once
  for (int guess = 0; guess < kMaxTimeOfContactIterations; ++guess) {
    if (narrowEnough(br, s.db.tolerance)) return {br.lo, TocStop::TimeTolerance};
    if (watchAll && br.hi - br.lo <= narrowedAt / kNarrowingShrink) {
      narrowToBracket(s, br);
      narrowedAt = br.hi - br.lo;
    }
    const double t = 0.5 * (br.lo + br.hi);
    const IntersectionResult r = watchAll ? s.statusAt(t) : s.statusOfPairsAt(br.hiPairs, t);
    if (r.status == Status::Interpenetrating) {
      br.hi = t;
      br.hiPairs = interpenetratingPairs(r);
    } else if (br.fresh && allInContact(r, br.hiPairs)) {
      return {t, TocStop::Contact};
    } else {
      br.lo = t;
    }
  }
  return {br.lo, TocStop::IterationLimit};
}

namespace {

struct Sample {
  double t, value;
};

// Where the curve t(value) through the samples (two or three, distinct values) crosses
// value 0: the secant's root, or inverse quadratic interpolation's. NaN or infinite
// when values repeat.
double interpolatedRoot(const Sample* p, int n) {
  const Sample& a = p[n - 2];
  const Sample& b = p[n - 1];
  if (n == 2) return b.t - b.value * (b.t - a.t) / (b.value - a.value);
  const Sample& c = p[0];
  return c.t * a.value * b.value / ((c.value - a.value) * (c.value - b.value)) +
         a.t * c.value * b.value / ((a.value - c.value) * (a.value - b.value)) +
         b.t * c.value * a.value / ((b.value - c.value) * (b.value - a.value));
}

}  // namespace

Found regulaFalsi(Search& s, Bracket& br) {
  const double reach = kSeparationReach * s.db.tolerance;
  const double target = kRootDistanceFraction * s.db.tolerance;
  auto measureAt = [&](double t, const std::optional<Separation>& known) {
    if (known) return *known;
    s.db.setTime(t);
    return signedSeparation(s, br.hiPairs, reach);
  };
  Separation sHi = measureAt(br.hi, br.atHi), sLo = measureAt(br.lo, br.atLo);
  // A pair touching at the start but still apart there (within the band) crosses zero
  // inside the bracket: its touching time is a root like any other.
  if (!br.fresh && sLo.value > target) br.fresh = true;
  if (!br.fresh) {
    // Touching exactly at a scanned time: that time is the root.
    if (br.lo > 0.0 && sLo.value >= -target) return {br.lo, TocStop::Contact};
    // Overlapping within the band at the start (a box rocking onto its next corner, one
    // corner already in): the feature touching since then keeps the measure negative all
    // along, so it has no sign change to chase, and taking "negative" for "past the root"
    // would narrow the bracket onto its start and return the very state it began from.
    // Only the test's verdict tells the two sides apart there, as in bisection.
    return bisect(s, br, BisectionTests::EveryWatchedPair);
  }
  bool alone = separationDecidesAlone(s, br.hiPairs);
  // The last separations measured, newest last: the interpolation through them is the
  // next guess of an exact measure (see below).
  Sample recent[3] = {{br.lo, sLo.value}, {br.hi, sHi.value}, {}};
  int measured = 2;
  int kept = 0;  // +1: lo moved last time, -1: hi moved (Illinois: halve the stale end)
  // A state in contact past the root, returned if the bracket closes before reaching
  // the target (its pairs touch, nothing interpenetrates).
  std::optional<double> fallback;
  for (int guess = 0; guess < kMaxTimeOfContactIterations; ++guess) {
    // The pairs are chased to the exact touching time.
    if (br.hi - br.lo < kTimeTolerance) return {fallback.value_or(br.lo), TocStop::TimeTolerance};
    // The secant through the bracket's ends (regula falsi). When it falls within this
    // fraction of the bracket from an end (regula falsi's one-sided creep), an exact
    // measure (convex pairs) is trusted and the guess only kept that far from the end;
    // the polygon measure is not, and the bracket is bisected, as it is while an end's
    // separation is only a bound. An exact measure first tries the interpolation through
    // the last points measured (inverse quadratic through three, the secant through
    // two), which converges faster near the root, whenever it falls inside the bracket.
    constexpr double kStallFraction = 1e-3;
    const double margin = kStallFraction * (br.hi - br.lo);
    const double secant = br.lo + sLo.value / (sLo.value - sHi.value) * (br.hi - br.lo);
    const double interpolated = interpolatedRoot(recent, measured);
    const bool exact = sLo.byAxes && sHi.byAxes;
    double t = std::clamp(secant, br.lo + margin, br.hi - margin);
    if (sLo.onlyBound || sHi.onlyBound || !std::isfinite(secant) || (!exact && t != secant))
      t = 0.5 * (br.lo + br.hi);
    else if (exact && interpolated > br.lo + margin && interpolated < br.hi - margin)
      t = interpolated;
    // The full test at t: always, unless the separation decides alone and t is not yet
    // a candidate root.
    std::optional<IntersectionResult> r;
    bool withContacts = false;
    auto test = [&] {  // true when it found other pairs interpenetrating
      withContacts = alone;  // alone, this test is likely the last: it gathers the contacts
      r = s.statusAt(t, withContacts);
      if (r->status != Status::Interpenetrating) return false;
      PairIds now = interpenetratingPairs(*r);
      if (now == br.hiPairs) return false;
      br.hiPairs = std::move(now);
      alone = separationDecidesAlone(s, br.hiPairs);
      return true;
    };
    if (alone) s.db.setTime(t);
    else test();
    Separation sT = signedSeparation(s, br.hiPairs, reach);
    if (measured == 3) recent[0] = recent[1], recent[1] = recent[2], --measured;
    recent[measured++] = {t, sT.value};
    if (std::abs(sT.value) <= target) {
      if (!r && test()) sT = signedSeparation(s, br.hiPairs, reach);
      if (std::abs(sT.value) <= target && allInContact(*r, br.hiPairs)) {
        if (withContacts) return {t, TocStop::Contact, std::move(r)};
        return {t, TocStop::Contact};
      }
    }
    const bool interpenetrating = r && r->status == Status::Interpenetrating;
    // Past the root (interpenetrating, or inside the band by more than the target): the
    // new upper end. A tested state stays acceptable as a fallback only while not
    // interpenetrating.
    if (sT.value < 0 || interpenetrating) {
      if (r && !interpenetrating && allInContact(*r, br.hiPairs)) fallback = t;
      br.hi = t;
      sHi = sT;
      if (kept == -1) sLo = {0.5 * sLo.value, false, sLo.byAxes};  // Illinois: a weight, no longer a bound
      kept = -1;
      continue;
    }
    br.lo = t;
    sLo = sT;
    if (kept == 1) sHi = {0.5 * sHi.value, false, sHi.byAxes};
    kept = 1;
  }
  return {fallback.value_or(br.lo), TocStop::IterationLimit};
}

}  // namespace polysim::collision::toc
