#include "collision/polygon_tests.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/area_cover.h"
#include "collision/area_on_patch.h"
#include "collision/clip.h"
#include "collision/crease_depth.h"
#include "collision/segment_distance.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void signedDistances(const PolygonView& p, const Plane& plane, std::vector<double>& d) {
  d.resize(p.size);
  for (int i = 0; i < p.size; ++i) d[i] = plane.signedDistance(p.vertices[i]);
}

// The part of p at signed level h of a plane, given p's vertex levels d: a segment [a, b]
// for a convex polygon (a == b when it is one point). False when p misses the level.
bool cutAtLevel(const PolygonView& p, const double* d, double h, Eigen::Vector3d& a, Eigen::Vector3d& b) {
  int found = 0;
  auto add = [&](const Eigen::Vector3d& x) {
    if (found == 0) a = b = x;
    else if ((x - a).squaredNorm() > (b - a).squaredNorm()) b = x;  // keep the two farthest apart
    else if ((x - b).squaredNorm() > (b - a).squaredNorm()) a = x;
    ++found;
  };
  for (int i = 0; i < p.size; ++i) {
    const int j = (i + 1) % p.size;
    const double di = d[i] - h, dj = d[j] - h;
    if (di == 0.0) add(p.vertices[i]);
    else if ((di < 0) != (dj < 0) && dj != 0.0) add(p.vertices[i] + (di / (di - dj)) * (p.vertices[j] - p.vertices[i]));
  }
  return found > 0;
}

// The largest over t in [0,1] of min_k f_k(t), f_k(t) = a_k + b_k t: the deepest point of
// a segment inside a convex region bounded by lines. min of lines is concave, so the
// maximum sits at an end or where two lines cross.
double maxOfMinOfLines(const std::vector<std::pair<double, double>>& lines) {
  if (lines.empty()) return kInfinity;
  auto g = [&](double t) {
    double m = kInfinity;
    for (const auto& [a, b] : lines) m = std::min(m, a + b * t);
    return m;
  };
  double best = std::max(g(0.0), g(1.0));
  for (size_t i = 0; i < lines.size(); ++i)
    for (size_t j = i + 1; j < lines.size(); ++j) {
      const double db = lines[i].second - lines[j].second;
      if (db == 0.0) continue;
      const double t = (lines[j].first - lines[i].first) / db;
      if (t > 0.0 && t < 1.0) best = std::max(best, g(t));
    }
  return best;
}

// How far (m) polygon p goes inside q's object, judged from q alone: the smaller of (1)
// the depth of p behind q's plane over q, in the wedge of q's convex creases
// (crease_depth.h), and (2) the depth of p's cut through q's plane inside q, from q's
// edges that are not flat. Both are taken over q itself, not over q grown by eps: past a
// flat edge the coplanar neighbour's own pair measures what lies there, and a band past
// a crease would be measured without that crease's other face (a cup lying on its side
// read the floor beyond the corner of its rim as nearly eps deep, and stalled). A caller
// that only asks whether the depth exceeds `enough` gets the cut's depth alone once that
// is at most `enough` (the smaller of the two can only be less), or a bound on it.
double depthInto(const PolygonView& p, const double* dP, const PolygonView& q, PolygonScratch& s,
                 double enough = -1.0) {
  const double maxP = *std::max_element(dP, dP + p.size);
  Eigen::Vector3d c0, c1;
  if (!cutAtLevel(p, dP, std::min(0.0, maxP), c0, c1)) return 0.0;
  if (enough >= 0.0) {
    // The usual case is a face's edge resting on the other face (a box's side on a floor
    // triangle): the cut runs just inside one sharp edge. The inside distance from an
    // edge is linear along the cut, so the cut's depth is at most, for any sharp edge, the
    // deeper of the cut's two ends; that settles the case without projecting onto q.
    double bound = kInfinity;
    for (int k = 0; k < q.size; ++k) {
      if (q.edgeFlat[k]) continue;
      const Eigen::Vector3d& u = q.vertices[k];
      bound = std::min(bound, std::max(q.sideNormal[k].dot(u - c0), q.sideNormal[k].dot(u - c1)));
    }
    if (bound <= enough) return bound;
  }

  const PlaneFrame frame(q.vertices[0], q.plane.normal);
  s.q2.resize(q.size);
  for (int k = 0; k < q.size; ++k) s.q2[k] = frame.to2d(q.vertices[k]);
  Eigen::Vector2d a = frame.to2d(c0), b = frame.to2d(c1);
  if (!clipSegment(s.q2, 0.0, a, b)) return 0.0;

  std::vector<std::pair<double, double>>& lines = s.lines;  // inside distance along the cut, per sharp edge
  lines.clear();
  for (int k = 0; k < q.size; ++k) {
    if (q.edgeFlat[k]) continue;
    const Eigen::Vector2d e = s.q2[(k + 1) % q.size] - s.q2[k];
    const double len = e.norm();
    const double fa = cross2(e, a - s.q2[k]) / len;
    lines.emplace_back(fa, cross2(e, b - s.q2[k]) / len - fa);
  }
  const double cutDepth = maxOfMinOfLines(lines);
  if (cutDepth <= enough) return cutDepth;

  // p clipped to the region behind q and inside q's prism.
  s.clipA.assign(p.vertices, p.vertices + p.size);
  clipBelow(s.clipA, q.plane.normal, q.plane.offset, s.clipB);
  for (int k = 0; k < q.size && !s.clipB.empty(); ++k) {
    const Eigen::Vector3d& u = q.vertices[k];
    s.clipA.swap(s.clipB);
    clipBelow(s.clipA, q.sideNormal[k], q.sideNormal[k].dot(u), s.clipB);
  }
  return std::min(cutDepth, deepestInWedge(q, s.clipB, s));
}

// Face-on-face: two faces facing each other whose overlap (p projected on q) lies within
// eps of both planes at every corner; judged on the overlap, not on the whole faces, so
// that a box on a wide floor is face-on-face even when slightly tilted. Appends the
// overlap polygon and returns true when it has a real area (wider than eps).
bool areaContact(const PolygonView& p, const PolygonView& q, double eps, std::vector<Contact>& out,
                 PolygonScratch& s) {
  const PlaneFrame frame(q.vertices[0], q.plane.normal);
  s.q2.resize(q.size);
  for (int k = 0; k < q.size; ++k) s.q2[k] = frame.to2d(q.vertices[k]);
  s.p2.resize(p.size);
  for (int k = 0; k < p.size; ++k) s.p2[p.size - 1 - k] = frame.to2d(p.vertices[k]);  // reversed: CCW about q's normal
  clipConvex(s.q2, s.p2, s.overlap, s.clipWork);
  const Polygon2& overlap = s.overlap;
  if (overlap.size() < 3 || signedArea(overlap) <= 0.5 * eps * perimeter(overlap)) return false;
  // The gap at a corner x of the overlap (on q's plane) is how far p's plane lies above it
  // along q's normal.
  const double along = -p.plane.normal.dot(q.plane.normal);
  Contact c = makeContact(s, ContactType::Area, q.plane.normal, {Feature::Kind::Face, p.faceId},
                          {Feature::Kind::Face, q.faceId});
  c.points.reserve(overlap.size());
  for (const Eigen::Vector2d& x2 : overlap) {
    const Eigen::Vector3d x = frame.to3d(x2);
    const double gap = p.plane.signedDistance(x) / along;
    if (std::abs(gap) > eps) return false;
    c.addPoint(x + (0.5 * gap) * q.plane.normal, gap);  // midway between the planes
  }
  out.push_back(std::move(c));
  return true;
}

// Edges and vertices of `p` lying within eps of face `q` (lines and points), with the
// normal `normal` (from B towards A). `pIsA` tells which object p belongs to.
void featuresOnFace(const PolygonView& p, const double* dP, const PolygonView& q, double eps, bool pIsA,
                    std::vector<Contact>& out, PolygonScratch& s) {
  // Most calls find no vertex of p near q's plane (a floor's far corners against a box's
  // face): nothing to project.
  if (std::none_of(dP, dP + p.size, [eps](double d) { return std::abs(d) <= eps; })) return;
  const PlaneFrame frame(q.vertices[0], q.plane.normal);
  s.q2.resize(q.size);
  for (int k = 0; k < q.size; ++k) s.q2[k] = frame.to2d(q.vertices[k]);
  const Eigen::Vector3d normal = pIsA ? q.plane.normal : Eigen::Vector3d(-q.plane.normal);
  auto features = [&](Feature onP) {
    Feature onQ{Feature::Kind::Face, q.faceId};
    return pIsA ? std::make_pair(onP, onQ) : std::make_pair(onQ, onP);
  };
  // Vertices that end a line contact already reported: their point contact would only be
  // dropped on that line by the reduction.
  s.onLine.assign(p.size, 0);
  for (int i = 0; i < p.size; ++i) {
    const int j = (i + 1) % p.size;
    if (std::abs(dP[i]) > eps) continue;
    if (std::abs(dP[j]) <= eps) {  // edge i lies along q's plane
      // Within eps of q decides contact; the reported segment is the part over q itself
      // (the grown clip would add eps-long stubs at q's corners).
      const Eigen::Vector2d vi = frame.to2d(p.vertices[i]), vj = frame.to2d(p.vertices[j]);
      Eigen::Vector2d a = vi, b = vj, a0 = vi, b0 = vj;
      if (clipSegment(s.q2, eps, a, b)) {
        const bool isLine = clipSegment(s.q2, 0.0, a0, b0) && (b0 - a0).norm() > eps;
        if (isLine) {
          // A vertex the clip kept lies over q: the line's end is its contact.
          s.onLine[i] = s.onLine[i] || a0 == vi;
          s.onLine[j] = b0 == vj;
          a = a0, b = b0;
        }
        // The grown clip overshoots q's sharp corners (by eps over the sine of half the
        // corner's angle): there the edge touches q only where it truly comes within eps.
        Eigen::Vector2d at = 0.5 * (a + b);
        double offQ = isLine ? 0.0 : distanceToConvex(s.q2, at);
        if (offQ > eps) at = nearestPointToConvex(s.q2, a, b), offQ = distanceToConvex(s.q2, at);
        if (offQ <= eps) {
          // The gap varies linearly along the edge; each point gets its own, midway.
          const Eigen::Vector2d along = vj - vi;
          auto addAt = [&](Contact& c, const Eigen::Vector2d& x) {
            const double t = along.squaredNorm() > 0 ? std::clamp(along.dot(x - vi) / along.squaredNorm(), 0.0, 1.0) : 0.0;
            const double gap = dP[i] + t * (dP[j] - dP[i]);
            c.addPoint(frame.to3d(x) + (0.5 * gap) * q.plane.normal, gap);
          };
          const auto [fa, fb] = features({Feature::Kind::Edge, p.edgeIds[i]});
          Contact c = makeContact(s, isLine ? ContactType::Line : ContactType::Point, normal, fa, fb);
          if (isLine) addAt(c, a), addAt(c, b);
          else addAt(c, at);
          out.push_back(std::move(c));
        }
      }
    }
    if (!s.onLine[i] && distanceToConvex(s.q2, frame.to2d(p.vertices[i])) <= eps) {
      const auto [fa, fb] = features({Feature::Kind::Vertex, p.vertexIds[i]});
      Contact c = makeContact(s, ContactType::Point, normal, fa, fb);
      c.addPoint(p.vertices[i] - (0.5 * dP[i]) * q.plane.normal, dP[i]);
      out.push_back(std::move(c));
    }
  }
}

// Edge of p against edge of q: crossing edges give a point, overlapping parallel edges a
// line. Edges that stay more than eps to one side of the other face's plane are skipped.
void edgeEdgeContacts(const PolygonView& p, const double* dP, const PolygonView& q, const double* dQ, double eps,
                      std::vector<Contact>& out, PolygonScratch& s) {
  auto farFromPlane = [eps](double d0, double d1) { return (d0 > eps && d1 > eps) || (d0 < -eps && d1 < -eps); };
  for (int i = 0; i < p.size; ++i) {
    const int i1 = (i + 1) % p.size;
    if (farFromPlane(dP[i], dP[i1])) continue;
    const Eigen::Vector3d& p0 = p.vertices[i];
    const Eigen::Vector3d u = p.vertices[i1] - p0;
    for (int j = 0; j < q.size; ++j) {
      const int j1 = (j + 1) % q.size;
      if (farFromPlane(dQ[j], dQ[j1])) continue;
      const Eigen::Vector3d& q0 = q.vertices[j];
      const Eigen::Vector3d v = q.vertices[j1] - q0;
      // Edges whose boxes lie more than eps apart (a long edge of a floor far from a
      // small object's edges) cannot come within eps.
      const Eigen::Array3d gapBelow = q0.array().min(q0.array() + v.array()) - p0.array().max(p0.array() + u.array());
      const Eigen::Array3d gapAbove = p0.array().min(p0.array() + u.array()) - q0.array().max(q0.array() + v.array());
      if ((gapBelow.max(gapAbove) > eps).any()) continue;
      const SegmentClosestPoints cp = closestPointsOnSegments(p0, u, q0, v);
      if (cp.distance > eps) continue;
      const Eigen::Vector3d outward = q.edgeOutward[j] - p.edgeOutward[i];
      const Feature fa{Feature::Kind::Edge, p.edgeIds[i]}, fb{Feature::Kind::Edge, q.edgeIds[j]};
      const Eigen::Vector3d axis = u.cross(v);
      if (axis.norm() > kParallelSine * u.norm() * v.norm()) {
        const Eigen::Vector3d n = axis.dot(outward) >= 0 ? axis.normalized() : Eigen::Vector3d(-axis.normalized());
        Contact c = makeContact(s, ContactType::Point, n, fa, fb);
        c.addPoint(0.5 * (cp.onFirst + cp.onSecond), n.dot(cp.onFirst - cp.onSecond));
        out.push_back(std::move(c));
        continue;
      }
      // Parallel: the overlap of q's edge projected on p's edge.
      const double s0 = u.dot(q0 - p0) / u.squaredNorm(), s1 = u.dot(q0 + v - p0) / u.squaredNorm();
      const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(1.0, std::max(s0, s1));
      Eigen::Vector3d n = outward - outward.dot(u) / u.squaredNorm() * u;
      n = n.norm() > kParallelSine ? n.normalized() : q.plane.normal;
      const Eigen::Vector3d shift = -0.5 * n.dot(cp.onFirst - cp.onSecond) * n;  // onto the midline
      const double gap = n.dot(cp.onFirst - cp.onSecond);
      if ((hi - lo) * u.norm() > eps) {
        Contact c = makeContact(s, ContactType::Line, n, fa, fb);
        c.addPoint(p0 + lo * u + shift, gap);
        c.addPoint(p0 + hi * u + shift, gap);
        out.push_back(std::move(c));
      } else {
        Contact c = makeContact(s, ContactType::Point, n, fa, fb);
        c.addPoint(0.5 * (cp.onFirst + cp.onSecond), gap);
        out.push_back(std::move(c));
      }
    }
  }
}

// The lowest and highest of a polygon's vertex levels over the other's plane.
struct LevelRange {
  double min, max;
  explicit LevelRange(const std::vector<double>& d) {
    const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
    min = *lo, max = *hi;
  }
  // Wholly beyond the band on one side of the plane: cannot come within eps of the other
  // polygon; whether it lies inside the other object is for other polygon pairs to see.
  bool outOfReach(double eps) const { return min > eps || max < -eps; }
};

}  // namespace

Contact makeContact(PolygonScratch& s, ContactType type, const Eigen::Vector3d& normal, Feature a, Feature b) {
  Contact c;
  if (!s.spare.empty()) {  // only the buffers: every other field starts as a new contact's
    c.points.swap(s.spare.back().points);
    c.gaps.swap(s.spare.back().gaps);
    s.spare.pop_back();
  }
  c.type = type;
  c.normal = normal;
  c.featureA = a;
  c.featureB = b;
  return c;
}

double penetrationDepth(const PolygonView& p, const PolygonView& q, double eps, PolygonScratch& s) {
  signedDistances(p, q.plane, s.dP);
  signedDistances(q, p.plane, s.dQ);
  const LevelRange levelP(s.dP), levelQ(s.dQ);
  if (levelP.outOfReach(eps) || levelQ.outOfReach(eps)) return 0.0;
  double depth = 0.0;
  if (levelP.min < 0) depth = std::max(depth, depthInto(p, s.dP.data(), q, s));
  if (levelQ.min < 0) depth = std::max(depth, depthInto(q, s.dQ.data(), p, s));
  return std::max(depth, deepestCrossing(p, q, eps));
}

PolygonPairOutcome testPolygonPair(const PolygonView& p, const PolygonView& q, double eps,
                                   std::vector<Contact>* contacts, PolygonScratch& s, const AreaCover* cover,
                                   AreaOnPatch* patch, DepthVerdict verdict) {
  signedDistances(p, q.plane, s.dP);
  signedDistances(q, p.plane, s.dQ);
  const LevelRange levelP(s.dP), levelQ(s.dQ);
  if (levelP.outOfReach(eps) || levelQ.outOfReach(eps)) return {};

  if (verdict == DepthVerdict::Judged) {
    double depth = 0.0;
    // Only whether the depth exceeds eps matters here.
    if (levelP.min < -eps) depth = std::max(depth, depthInto(p, s.dP.data(), q, s, eps));
    if (levelQ.min < -eps) depth = std::max(depth, depthInto(q, s.dQ.data(), p, s, eps));
    // Two creases crossing deeper than eps interpenetrate by the gap their edge-edge
    // contact would measure. The measure above reads less where one edge runs along a
    // face of the other's wedge (a cup's bottom edge across another cup's inner rim
    // edge); unjudged, such a crossing would be no contact (its gap is past -eps) and
    // nothing would hold it.
    if (depth <= eps) depth = std::max(depth, deepestCrossing(p, q, eps));
    if (depth > eps) return {Status::Interpenetrating, depth};
  }
  if (cover && cover->covers(p, s.dP.data(), q, s.dQ.data(), eps)) return {Status::Contact, 0.0};

  std::vector<Contact>& out = contacts ? *contacts : s.discard;
  const size_t before = out.size();
  const bool facing = p.plane.normal.dot(q.plane.normal) <= -std::cos(kFaceContactAngle);
  bool area = false;
  if (facing) {
    const AreaOnPatch::Outcome onPatch = patch ? patch->add(q, eps) : AreaOnPatch::Outcome::OffPatch;
    if (onPatch == AreaOnPatch::Outcome::Unsettled) return {};
    area = onPatch == AreaOnPatch::Outcome::Area ||
           (onPatch == AreaOnPatch::Outcome::OffPatch && areaContact(p, q, eps, out, s));
  }
  if (!area) {
    featuresOnFace(p, s.dP.data(), q, eps, true, out, s);
    featuresOnFace(q, s.dQ.data(), p, eps, false, out, s);
    edgeEdgeContacts(p, s.dP.data(), q, s.dQ.data(), eps, out, s);
  }
  const bool touching = area || out.size() > before;
  if (!contacts) recycleContacts(s.discard, s);
  return {touching ? Status::Contact : Status::Separate, 0.0, area};
}

void recycleContacts(std::vector<Contact>& contacts, PolygonScratch& s) {
  for (Contact& c : contacts) {
    if (s.spare.size() >= kMaxSpareContacts) break;
    c.points.clear();  // keeps the capacity
    c.gaps.clear();
    s.spare.push_back(std::move(c));
  }
  contacts.clear();
}

}  // namespace polysim::collision
