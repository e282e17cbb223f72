#include "collision/time_of_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "collision/aabb.h"
#include "collision/broadphase.h"
#include "collision/convex_separation.h"
#include "collision/polygon_distance.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

using PairIds = std::vector<std::pair<int, int>>;

// The state of the search: the database, its workspace and the count of tests made.
struct Search {
  ObjectDatabase& db;
  IntersectionWorkspace& ws;
  int tests = 0;

  // Sets the database to time t and returns the status of every pair, with their
  // contacts when asked.
  IntersectionResult statusAt(double t, bool contacts = false) {
    db.setTime(t);
    ++tests;
    IntersectionOptions options;
    options.contacts = contacts;
    return test4Intersection(db, ws, options);
  }
};

PairIds interpenetratingPairs(const IntersectionResult& r) {
  PairIds ids;
  for (const PairResult& p : r.pairs)
    if (p.status == Status::Interpenetrating) ids.emplace_back(p.a, p.b);
  return ids;
}

// True when every pair of `ids` is in contact (not separate, not interpenetrating) in r.
bool allInContact(const IntersectionResult& r, const PairIds& ids) {
  for (const auto& [a, b] : ids) {
    const auto it = std::find_if(r.pairs.begin(), r.pairs.end(), [&](const PairResult& p) { return p.a == a && p.b == b; });
    if (it == r.pairs.end() || it->status != Status::Contact) return false;
  }
  return true;
}

// True when no pair of `ids` is in contact in r.
bool noneInContact(const IntersectionResult& r, const PairIds& ids) {
  for (const auto& [a, b] : ids)
    for (const PairResult& p : r.pairs)
      if (p.a == a && p.b == b && p.status == Status::Contact) return false;
  return true;
}

// Into how many sub-intervals the interval must be split so that no pair moves farther
// than kTunnelingSafety times its thinner object's thickness between two tests.
int subintervalsAgainstTunnelling(const ObjectDatabase& db) {
  double worst = 0.0;
  const int n = static_cast<int>(db.objects.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const ObjNode& A = db.objects[a];
      const ObjNode& B = db.objects[b];
      const double motion = A.motionBound + B.motionBound;
      const double thickness = std::min(A.thickness, B.thickness);
      if (motion <= 0.0 || !std::isfinite(thickness)) continue;
      // Every pose in the interval lies within the t = 1 box grown by the motion bound.
      if (!grow(worldContainer(A), A.motionBound).intersects(grow(worldContainer(B), B.motionBound))) continue;
      worst = std::max(worst, motion / (kTunnelingSafety * thickness));
    }
  return static_cast<int>(std::clamp(std::ceil(worst), 1.0, static_cast<double>(kMaxSubintervals)));
}

// Signed separation of the given pairs at the current state: the least over them of the
// distance apart, or minus the deepest penetration when one goes inside. Convex pairs
// are measured exactly by the separating axis test; others polygon by polygon, only out
// to the reach: beyond it their value is clamped to +-reach and only a bound.
struct Separation {
  double value = std::numeric_limits<double>::infinity();
  bool onlyBound = false;  // the least came from a clamped measure
  bool byAxes = true;      // every pair was measured by the separating axis test
};

Separation signedSeparation(Search& s, const PairIds& ids, double reach) {
  Separation least;
  auto take = [&least](double value, bool onlyBound) {
    if (value < least.value) least.value = value, least.onlyBound = onlyBound;
  };
  for (const auto& [a, b] : ids) {
    const ObjNode& A = s.db.objects[a];
    const ObjNode& B = s.db.objects[b];
    if (const std::optional<double> convex = convexSeparation(A, B)) {
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
      const PolygonView p = fa.view(pa), q = fb.view(pb);
      const double d = penetrationDepth(p, q, s.db.tolerance, s.ws.scratch);
      if (d > 0.0) depth = std::max(depth, d);
      else if (depth == 0.0) distance = std::min(distance, polygonDistance(p, q, s.ws.scratch));
      return depth < reach;  // deeper than the reach is only known to be deep
    });
    depth = std::min(depth, reach);
    const double value = depth > 0.0 ? -depth : distance;
    take(value, std::abs(value) >= reach);
  }
  return least;
}

// True when the pairs of `ids` are convex (measured by the separating axis test) and no
// other pair can come within eps anywhere in the interval: then the separation alone
// tells which side of the first contact a time lies on, and the full test is needed only
// to confirm the root.
bool separationDecidesAlone(const ObjectDatabase& db, const PairIds& ids) {
  for (const auto& [a, b] : ids)
    if (!hasSeparatingAxes(*db.objects[a].mesh) || !hasSeparatingAxes(*db.objects[b].mesh)) return false;
  const int n = static_cast<int>(db.objects.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const ObjNode& A = db.objects[a];
      const ObjNode& B = db.objects[b];
      if ((A.isStatic && B.isStatic) || std::find(ids.begin(), ids.end(), std::pair(a, b)) != ids.end() ||
          std::find(ids.begin(), ids.end(), std::pair(b, a)) != ids.end())
        continue;
      // Every pose in the interval lies within the current box grown by the motion bound.
      if (grow(worldContainer(A), A.motionBound + db.tolerance).intersects(grow(worldContainer(B), B.motionBound)))
        return false;
    }
  return true;
}

struct Bracket {
  double lo, hi;
  PairIds hiPairs;  // the pairs interpenetrating at hi
  /// False when one of hiPairs already touched at the bracket's start: then "the pair is
  /// in contact" says nothing about the new touch, and only narrowing the bracket helps.
  bool fresh = true;
  /// Largest relative motion (m) of the objects over the whole interval [0, 1].
  double motion = 0.0;
};

// True when the bracket is narrow enough that nothing moves more than eps inside it (or
// below kTimeTolerance when the motion is unknown): its start is then "just contact".
bool narrowEnough(const Bracket& br, double eps) {
  if (br.motion > 0.0) return (br.hi - br.lo) * br.motion <= eps;
  return br.hi - br.lo < kTimeTolerance;
}

double pairMotion(const ObjectDatabase& db, const PairIds& ids) {
  double motion = 0.0;
  for (const auto& [a, b] : ids) motion = std::max(motion, db.objects[a].motionBound + db.objects[b].motionBound);
  return motion;
}

struct Found {
  double time;
  TocStop stop;
  /// The full test (with contacts) at `time`, when the search already made it.
  std::optional<IntersectionResult> atTime = std::nullopt;
};

Found bisect(Search& s, Bracket br) {
  while (s.tests < kMaxTimeOfContactIterations) {
    if (narrowEnough(br, s.db.tolerance)) return {br.lo, TocStop::TimeTolerance};
    const double t = 0.5 * (br.lo + br.hi);
    const IntersectionResult r = s.statusAt(t);
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

Found regulaFalsi(Search& s, Bracket br) {
  const double reach = kSeparationReach * s.db.tolerance;
  const double target = kRootDistanceFraction * s.db.tolerance;
  s.db.setTime(br.hi);
  Separation sHi = signedSeparation(s, br.hiPairs, reach);
  bool alone = separationDecidesAlone(s.db, br.hiPairs);
  s.db.setTime(br.lo);
  Separation sLo = signedSeparation(s, br.hiPairs, reach);
  int kept = 0;  // +1: lo moved last time, -1: hi moved (Illinois: halve the stale end)
  // A state in contact past the root, returned if the bracket closes before reaching
  // the target (its pairs touch, nothing interpenetrates).
  std::optional<double> fallback;
  while (s.tests < kMaxTimeOfContactIterations) {
    // A fresh pair is chased to the exact touching time; otherwise the bracket only narrows.
    const bool narrow = br.fresh ? br.hi - br.lo < kTimeTolerance : narrowEnough(br, s.db.tolerance);
    if (narrow) return {fallback.value_or(br.lo), TocStop::TimeTolerance};
    // The secant's root. When it falls within this fraction of the bracket from an end
    // (regula falsi's one-sided creep), an exact measure (convex pairs) is trusted and
    // the guess only kept that far from the end; the polygon measure is not, and the
    // bracket is bisected, as it is while an end's separation is only a bound.
    constexpr double kStallFraction = 1e-3;
    const double margin = kStallFraction * (br.hi - br.lo);
    const double secant = br.lo + sLo.value / (sLo.value - sHi.value) * (br.hi - br.lo);
    const bool exact = sLo.byAxes && sHi.byAxes;
    double t = std::clamp(secant, br.lo + margin, br.hi - margin);
    if (!br.fresh || sLo.onlyBound || sHi.onlyBound || !std::isfinite(secant) || (!exact && t != secant))
      t = 0.5 * (br.lo + br.hi);
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
      alone = separationDecidesAlone(s.db, br.hiPairs);
      return true;
    };
    if (alone) s.db.setTime(t);
    else test();
    Separation sT = signedSeparation(s, br.hiPairs, reach);
    if (br.fresh && std::abs(sT.value) <= target) {
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
      if (br.fresh && r && !interpenetrating && allInContact(*r, br.hiPairs)) fallback = t;
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

[[noreturn]] void reportInitialInterpenetration(const ObjectDatabase& db, const IntersectionResult& r) {
  std::string names;
  for (const PairResult& p : r.pairs)
    if (p.status == Status::Interpenetrating)
      names += (names.empty() ? "" : ", ") + ("\"" + db.objects[p.a].name + "\" and \"" + db.objects[p.b].name + "\"");
  throw InitialInterpenetration("objects interpenetrate at the start of the interval: " + names);
}

}  // namespace

TocResult collisionDetect(ObjectDatabase& db, const TocOptions& options) {
  IntersectionWorkspace workspace;
  return collisionDetect(db, workspace, options);
}

TocResult collisionDetect(ObjectDatabase& db, IntersectionWorkspace& workspace, const TocOptions& options) {
  Search s{db, workspace, 0};
  TocResult result;
  result.subintervals = subintervalsAgainstTunnelling(db);

  // Test the ends of the sub-intervals in order until one interpenetrates.
  std::optional<Bracket> bracket;
  IntersectionResult atStart;  // the state at the bracket's start, once tested
  for (int k = 1; k <= result.subintervals && !bracket; ++k) {
    const double t = static_cast<double>(k) / result.subintervals;
    IntersectionResult r = s.statusAt(t);
    if (r.status == Status::Interpenetrating)
      bracket = Bracket{static_cast<double>(k - 1) / result.subintervals, t, interpenetratingPairs(r)};
    else
      atStart = std::move(r);
  }

  Found found{1.0, TocStop::NoInterpenetration};
  if (bracket) {
    if (bracket->lo == 0.0) {  // later starts were tested as the end of the previous sub-interval
      atStart = s.statusAt(0.0);
      if (atStart.status == Status::Interpenetrating) reportInitialInterpenetration(db, atStart);
    }
    bracket->fresh = noneInContact(atStart, bracket->hiPairs);
    bracket->motion = pairMotion(db, bracket->hiPairs);
    found = options.method == TocMethod::Bisection ? bisect(s, *bracket) : regulaFalsi(s, *bracket);
  }

  if (!found.atTime) {
    db.setTime(found.time);
    found.atTime = test4Intersection(db, s.ws);
    ++s.tests;
  }
  const IntersectionResult& final = *found.atTime;
  result.time = found.time;
  result.status = final.status;
  result.pairs = final.pairs;
  result.iterations = s.tests;
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
