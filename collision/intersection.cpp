#include "collision/intersection.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "collision/contact_reduction.h"
#include "collision/containment.h"
#include "collision/convex_separation.h"
#include "collision/separating_plane.h"
#include "collision/tolerances.h"

namespace polysim::collision {

PairResult testObjectPair(const ObjectDatabase& db, int a, int b, IntersectionWorkspace& ws,
                          const IntersectionOptions& options, long* polygonPairsTested,
                          std::optional<double>* axesSeparation) {
  PairResult result;
  result.a = a;
  result.b = b;
  if (axesSeparation) axesSeparation->reset();  // until measured below
  const ObjNode& A = db.objects[a];
  const ObjNode& B = db.objects[b];
  const double eps = db.tolerance;
  const std::optional<Eigen::AlignedBox3d> region = overlapRegion(A, B, eps);
  if (!region || separatedAlongCentreLine(A, B, eps)) return result;
  // Convex objects interpenetrate when their penetration depth (the least translation
  // that parts them, by the separating axis test) exceeds eps. That depth is what the
  // contacts' gaps measure: along a face's normal for a vertex, along the common normal
  // for two crossing edges. The polygons' own measure reads an edge crossing a tilted
  // face deeper than its gap (along the face's normal, over the face grown by eps), and
  // a state whose contacts the solver holds within the band could be judged
  // interpenetrating at once; a step would then never leave it.
  const std::optional<double> separation = ws.separations.measure(A, B);
  if (axesSeparation) *axesSeparation = separation;
  if (separation && *separation > eps) return result;  // a lower bound on their distance
  if (separation && *separation < -eps) {
    result.status = Status::Interpenetrating;
    result.depth = -*separation;
    return result;
  }
  // Convex objects that overlap (no separating axis) touch; when only the verdict is
  // wanted, the polygons would only confirm it. Resting pairs sit here, inside the band.
  if (separation && *separation <= 0.0 && !options.contacts) {
    result.status = Status::Contact;
    return result;
  }
  // Apart by a separating axis, so not interpenetrating: within the tolerance or not,
  // only the polygons would tell.
  if (separation && !options.contacts && !options.tellContactFromApart) return result;
  const DepthVerdict verdict = separation ? DepthVerdict::DecidedByCaller : DepthVerdict::Judged;

  if (ws.faces.size() < db.objects.size()) ws.faces.resize(db.objects.size());
  WorldFaces& facesA = ws.faces[a];
  WorldFaces& facesB = ws.faces[b];
  facesA.reset(A);
  facesB.reset(B);
  recycleContacts(ws.raw, ws.scratch);  // their buffers serve this pair's contacts
  bool touching = false;
  auto judge = [&](int fa, int fb, const AreaCover* cover = nullptr, AreaOnPatch* patch = nullptr) {
    const PolygonPairOutcome o = testPolygonPair(facesA.view(fa), facesB.view(fb), eps,
                                                 options.contacts ? &ws.raw : nullptr, ws.scratch, cover, patch, verdict);
    if (o.status == Status::Interpenetrating) {
      result.status = Status::Interpenetrating;
      result.depth = std::max(result.depth, o.depth);
    }
    touching = touching || o.status == Status::Contact;
    if (o.area) ws.cover.addArea(fa, fb);
    // Without contacts there is nothing more to learn about an interpenetrating pair.
    return !(!options.contacts && result.status == Status::Interpenetrating);
  };
  if (!options.contacts) {
    // Only the verdict is wanted: judge pairs as the descent finds them (a pair may be
    // judged twice) and stop at the first interpenetration.
    long visited = 0;
    forEachCandidatePair(A, facesA, B, facesB, *region, eps, ws.descent, [&](int fa, int fb) { return ++visited, judge(fa, fb); });
    if (polygonPairsTested) *polygonPairsTested += visited;
  } else {
    candidatePolygonPairs(A, facesA, B, facesB, *region, eps, ws.descent, ws.candidates);
    if (polygonPairsTested) *polygonPairsTested += static_cast<long>(ws.candidates.size());
    // Face-on-face pairs first: the areas they find spare the other pairs gathering
    // contacts that would only be dropped on those areas' boundaries (area_cover.h).
    ws.cover.reset(*A.mesh, *B.mesh);
    const double facingCosine = -std::cos(kFaceContactAngle);
    auto facing = [&](const FacePair& fp) {
      return facesA.plane(fp.a).normal.dot(facesB.plane(fp.b).normal) <= facingCosine;
    };
    // The candidates come sorted by A's face: each face's facing pairs form one patch.
    for (size_t i = 0, end = 0; i < ws.candidates.size(); i = end) {
      const int fa = ws.candidates[i].a;
      bool begun = false;
      for (end = i; end < ws.candidates.size() && ws.candidates[end].a == fa; ++end) {
        if (!facing(ws.candidates[end])) continue;
        if (!begun) ws.patch.begin(facesA.view(fa)), begun = true;
        judge(fa, ws.candidates[end].b, nullptr, &ws.patch);
      }
      if (!begun) continue;
      const bool covered = ws.patch.finish(ws.raw, ws.scratch);
      for (const int fb : ws.patch.unsettled()) {
        if (!covered) {
          judge(fa, fb);
          continue;
        }
        // What fb has near fa lies on fa's area, as does what fa's side faces have near fb.
        ws.cover.addArea(fa, fb);
      }
    }
    ws.cover.seal();
    for (const FacePair& fp : ws.candidates)
      if (!facing(fp)) judge(fp.a, fp.b, &ws.cover);
  }
  if (result.status == Status::Interpenetrating) return result;
  if (!touching && !separation) {  // no polygons meet: one object may still lie wholly inside the other
    std::optional<double> depth = containmentDepth(A, B);
    if (!depth) depth = containmentDepth(B, A);
    if (depth) {
      result.status = Status::Interpenetrating;
      result.depth = *depth;
      return result;
    }
  }
  if (touching) {
    result.status = Status::Contact;
    if (options.contacts) {
      const PairGeometry geometry{A.mesh.get(), B.mesh.get(), A.X_WO.linear(), B.X_WO.linear(), !separation};
      result.contacts = reduceContacts(ws.raw, eps, &geometry);
    }
  }
  return result;
}

IntersectionResult test4Intersection(const ObjectDatabase& db, IntersectionWorkspace& ws,
                                     const IntersectionOptions& options) {
  IntersectionResult result;
  if (options.onlyPairs) candidateObjectPairsAmong(db, *options.onlyPairs, ws.containers, ws.objectPairs);
  else candidateObjectPairs(db, ws.containers, ws.objectPairs);  // the pairs whose containers meet
  for (const auto& [a, b] : ws.objectPairs) {
    // In a static-moving pair the moving object is `a`, so that the normal points from
    // the ground (or wall) towards what rests on it.
    const bool flip = db.objects[a].isStatic;
    const int first = flip ? b : a, second = flip ? a : b;
    PairResult pair;
    if (std::optional<PairResult> kept = ws.reuse.find(db, first, second)) {
      pair = std::move(*kept);
      ++result.pairsReused;
      if (!options.contacts) pair.contacts.clear();  // a verdict-only test reports none
    } else {
      std::optional<double> separation;
      pair = testObjectPair(db, first, second, ws, options, &result.polygonPairsTested, &separation);
      if (options.contacts) ws.reuse.keep(db, pair, separation);
    }
    if (pair.status == Status::Separate) continue;
    result.status = std::max(result.status, pair.status);
    result.pairs.push_back(std::move(pair));
    if (result.status == Status::Interpenetrating && options.stopAtInterpenetration) break;
  }
  if (options.contacts && options.agesKeptContacts) ws.reuse.endQuery();  // verdict-only tests may skip pairs that still rest
  return result;
}

IntersectionResult test4Intersection(const ObjectDatabase& db, const IntersectionOptions& options) {
  IntersectionWorkspace ws;
  return test4Intersection(db, ws, options);
}

}  // namespace polysim::collision
