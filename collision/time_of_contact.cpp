#include "collision/time_of_contact.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "collision/aabb.h"
#include "collision/broadphase.h"
#include "collision/convex_separation.h"
#include "collision/toc_search.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

using namespace toc;

// Into how many sub-intervals the interval must be split so that no pair moves farther
// than kTunnelingSafety times its thinner object's thickness between two tests; may be
// more than kMaxSubintervals (and is not a whole number).
double subintervalsAgainstTunnelling(const ObjectDatabase& db) {
  // Every pose in the interval lies within the t = 1 box grown by the motion bound; the
  // pairs whose such boxes meet, by sweep and prune (a pile's island: N log N, not N^2 / 2).
  std::vector<Eigen::AlignedBox3d> swept(db.objects.size());
  for (size_t i = 0; i < swept.size(); ++i) swept[i] = grow(worldContainer(db.objects[i]), db.objects[i].motionBound);
  std::vector<std::pair<int, int>> candidates;
  overlappingBoxPairs(db, swept, candidates);
  double worst = 0.0;
  for (const auto& [a, b] : candidates) {
    const ObjNode& A = db.objects[a];
    const ObjNode& B = db.objects[b];
    const double motion = A.motionBound + B.motionBound;
    const double thickness = std::min(A.thickness, B.thickness);
    if (motion <= 0.0 || !std::isfinite(thickness)) continue;
    worst = std::max(worst, motion / (kTunnelingSafety * thickness));
  }
  return worst;
}

[[noreturn]] void reportInitialInterpenetration(const ObjectDatabase& db, const IntersectionResult& r) {
  std::string names;
  for (const PairResult& p : r.pairs)
    if (p.status == Status::Interpenetrating)
      names += (names.empty() ? "" : ", ") + ("\"" + db.objects[p.a].name + "\" and \"" + db.objects[p.b].name + "\"");
  throw InitialInterpenetration("objects interpenetrate at the start of the interval: " + names);
}

double pairMotion(const ObjectDatabase& db, const PairIds& ids) {
  double motion = 0.0;
  for (const auto& [a, b] : ids) motion = std::max(motion, db.objects[a].motionBound + db.objects[b].motionBound);
  return motion;
}

// The seed's scan: the test at the end of each sub-interval in order, until one
// interpenetrates. It tells only interpenetration (Search::interpenetrationAt): which
// pairs already touch at the bracket's start is startBracket()'s to find.
std::optional<Bracket> scanByTests(Search& s, int subintervals) {
  for (int k = 1; k <= subintervals; ++k) {
    const double t = static_cast<double>(k) / subintervals;
    const IntersectionResult r = s.interpenetrationAt(t);
    if (r.status == Status::Interpenetrating)
      return Bracket{static_cast<double>(k - 1) / subintervals, t, interpenetratingPairs(r)};
  }
  return std::nullopt;
}

// The same scan when the separating axis test measures every pair that can meet: an end
// where each of them is apart (separation >= 0) cannot interpenetrate and needs no full
// test, nor does a pair whose boxes are farther apart than the tolerance need measuring.
// A pair that overlaps by more than the tolerance along every axis interpenetrates:
// the full test judges convex pairs by that same depth (testObjectPair). Between the
// two the full test decides.
std::optional<Bracket> scanBySeparation(Search& s, int subintervals) {
  const double eps = s.db.tolerance;
  for (int k = 1; k <= subintervals; ++k) {
    const double lo = static_cast<double>(k - 1) / subintervals, t = static_cast<double>(k) / subintervals;
    s.db.setTime(t);
    Bracket br{lo, t, {}};
    Separation least;
    bool unsure = false;
    bool measured = false;
    for (const auto& [a, b] : s.meeting) {
      const ObjNode& A = s.db.objects[a];
      const ObjNode& B = s.db.objects[b];
      if (!grow(worldContainer(A), eps).intersects(worldContainer(B))) continue;
      const double separation = *s.ws.separations.measure(A, B);
      measured = true;
      if (separation < -eps) br.hiPairs.emplace_back(a, b), least.value = std::min(least.value, separation);
      else unsure = unsure || separation < 0.0;
    }
    s.separations += measured;
    if (unsure) {
      const IntersectionResult r = s.interpenetrationAt(t);
      if (r.status == Status::Interpenetrating) return Bracket{lo, t, interpenetratingPairs(r)};
    } else if (!br.hiPairs.empty()) {
      br.atHi = least;
      return br;
    }
  }
  return std::nullopt;
}

// Fills in what the root finders need to know about the bracket's start: whether its
// pairs already touch there (Bracket::fresh, by their own test), and that nothing
// interpenetrates at t = 0 (a later start is a time the scan found clean). Measured by
// the separating axis test when that scanned (only a pair within the tolerance then
// needs the full test).
void startBracket(Search& s, Bracket& br, bool byAxes) {
  br.motion = pairMotion(s.db, br.hiPairs);
  if (byAxes) {
    s.db.setTime(br.lo);
    const double reach = kSeparationReach * s.db.tolerance;
    br.atLo = signedSeparation(s, br.hiPairs, reach);
    const double least = br.lo == 0.0 ? signedSeparation(s, s.meeting, reach).value : br.atLo->value;
    if (least > s.db.tolerance) return;  // nothing touches, nothing interpenetrates
  }
  if (br.lo == 0.0) {
    const IntersectionResult r = s.interpenetrationAt(0.0);
    if (r.status == Status::Interpenetrating) reportInitialInterpenetration(s.db, r);
  }
  br.fresh = noneInContact(s.statusOfPairsAt(br.hiPairs, br.lo), br.hiPairs);
}

// bisect() testing the crossing pairs, its premise checked at the time it found with
// every pair that can meet (with `gather`, the test whose contacts are returned; else
// the verdict of those that can interpenetrate): when another pair interpenetrates
// there, the bracket is bisected again from the start watching every pair (counted in
// `redone`).
Found bisectCheckingItsPremise(Search& s, Bracket& br, int& redone, bool gather) {
  const Bracket whole = br;
  Found found = bisect(s, br, BisectionTests::CrossingPairs);
  if (gather) {
    found.atTime = s.statusAt(found.time, true);
    if (found.atTime->status != Status::Interpenetrating) return found;
  } else if (s.interpenetrationOfWatchedAt(found.time).status != Status::Interpenetrating) {
    return found;
  }
  ++redone;
  br = whole;
  return bisect(s, br, BisectionTests::EveryWatchedPair);
}

}  // namespace

TocResult collisionDetect(ObjectDatabase& db, const TocOptions& options) {
  IntersectionWorkspace workspace;
  return collisionDetect(db, workspace, options);
}

TocResult collisionDetect(ObjectDatabase& db, IntersectionWorkspace& workspace, const TocOptions& options) {
  Search s{db, workspace};
  TocResult result;
  const double needed = subintervalsAgainstTunnelling(db);
  result.subintervals = static_cast<int>(std::clamp(std::ceil(needed), 1.0, static_cast<double>(kMaxSubintervals)));
  result.tunnellingGuarded = needed <= kMaxSubintervals;
  // Regula falsi measures separations anyway; where the separating axis test measures
  // every pair that can meet, it also scans. Bisection keeps the seed's tests.
  const bool scanByAxes = options.method == TocMethod::RegulaFalsi && measuredByAxes(db, s.meeting);
  std::optional<Bracket> bracket = scanByAxes ? scanBySeparation(s, result.subintervals) : scanByTests(s, result.subintervals);

  Found found{1.0, TocStop::NoInterpenetration};
  if (bracket) {
    startBracket(s, *bracket, scanByAxes);
    if (options.method == TocMethod::RegulaFalsi) found = regulaFalsi(s, *bracket);
    else if (options.watchEveryPairWhileBisecting) found = bisect(s, *bracket, BisectionTests::EveryWatchedPair);
    else found = bisectCheckingItsPremise(s, *bracket, result.bisectionsRedone, options.gatherAtEvent);
    result.crossing = std::move(bracket->hiPairs);
  }

  if (!found.atTime && bracket && !options.gatherAtEvent) {
    found.atTime = s.contactsOfPairsAt(result.crossing, found.time);
    for (const std::pair<int, int>& p : s.nearingAt(found.time))
      if (std::find(result.crossing.begin(), result.crossing.end(), p) == result.crossing.end()) result.nearing.push_back(p);
  } else if (!found.atTime) {
    found.atTime = s.statusAt(found.time, true);
  }
  result.time = found.time;
  result.status = found.atTime->status;
  result.pairs = std::move(found.atTime->pairs);
  result.iterations = s.tests;
  result.pairTests = s.pairTests;
  result.pairsMeeting = static_cast<int>(s.meeting.size());
  result.pairsWatched = static_cast<int>(s.watched.size());
  result.separations = s.separations;
  result.stoppedBy = found.stop;
  return result;
}

std::string toString(TocMethod method) {
  return method == TocMethod::Bisection ? "bisection" : "regula-falsi";
}

TocMethod tocMethodNamed(const std::string& name) {
  for (TocMethod m : {TocMethod::Bisection, TocMethod::RegulaFalsi})
    if (toString(m) == name) return m;
  throw std::invalid_argument("unknown time-of-contact method \"" + name + "\" (bisection or regula-falsi)");
}

std::string toString(TocStop stop) {
  switch (stop) {
    case TocStop::NoInterpenetration: return "no-interpenetration";
    case TocStop::Contact: return "contact";
    case TocStop::TimeTolerance: return "time-tolerance";
    case TocStop::IterationLimit: return "iteration-limit";
  }
  return "?";
}

}  // namespace polysim::collision
