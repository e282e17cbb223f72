#include "collision/contact_reduction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>

#include "collision/clip.h"
#include "collision/normal_cone.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Area pieces in one plane, as 2D polygons of that plane's frame, with every corner's
// own 3D point and gap: a merged polygon's corners are corners of its pieces, and keep
// where they were found (midway between the faces) and how deep.
struct AreaCluster {
  PlaneFrame frame;
  std::vector<Polygon2> pieces;
  std::vector<double> areas;
  std::vector<Eigen::Vector2d> corners2d;
  std::vector<Eigen::Vector3d> corners3d;
  std::vector<double> gaps;
  Feature featureA, featureB;

  // The piece corner at x (2D): merging and simplifying only pick corners, never make them.
  size_t cornerAt(const Eigen::Vector2d& x) const {
    size_t best = 0;
    for (size_t i = 1; i < corners2d.size(); ++i)
      if ((corners2d[i] - x).squaredNorm() < (corners2d[best] - x).squaredNorm()) best = i;
    return best;
  }
};

// Merges pieces whose union is convex: the union of disjoint pieces is their hull exactly
// when the hull has no more area than the pieces, up to a strip eps wide on its boundary.
std::vector<Polygon2> mergeConvexUnions(std::vector<Polygon2> pieces, std::vector<double> areas, double eps) {
  auto tryMerge = [eps](const std::vector<const Polygon2*>& group, double area, Polygon2& hull) {
    std::vector<Eigen::Vector2d> all;
    for (const Polygon2* g : group) all.insert(all.end(), g->begin(), g->end());
    hull = convexHull(std::move(all));
    return hull.size() >= 3 && signedArea(hull) - area <= eps * perimeter(hull);
  };
  Polygon2 hull;
  std::vector<const Polygon2*> everything;
  double total = 0.0;
  for (size_t i = 0; i < pieces.size(); ++i) everything.push_back(&pieces[i]), total += areas[i];
  if (tryMerge(everything, total, hull)) return {hull};
  // Not convex as a whole (a face over an L-shaped patch): merge greedily two at a time.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < pieces.size() && !merged; ++i)
      for (size_t j = i + 1; j < pieces.size() && !merged; ++j)
        if (tryMerge({&pieces[i], &pieces[j]}, areas[i] + areas[j], hull)) {
          pieces[i] = hull;
          areas[i] += areas[j];
          pieces.erase(pieces.begin() + static_cast<long>(j));
          areas.erase(areas.begin() + static_cast<long>(j));
          merged = true;
        }
  }
  return pieces;
}

// Drops corners closer than eps to the previous corner or to the line through their
// neighbours: clipping leaves near-duplicate and near-collinear corners that say
// nothing at the contact tolerance.
Polygon2 simplify(Polygon2 poly, double eps) {
  for (bool changed = true; changed && poly.size() > 3;) {
    changed = false;
    for (size_t i = 0; i < poly.size() && poly.size() > 3; ++i) {
      const Eigen::Vector2d& prev = poly[(i + poly.size() - 1) % poly.size()];
      const Eigen::Vector2d& next = poly[(i + 1) % poly.size()];
      const Eigen::Vector2d chord = next - prev;
      const double offChord = chord.norm() > 0 ? std::abs(cross2(chord, poly[i] - prev)) / chord.norm() : 0.0;
      if ((poly[i] - prev).norm() <= eps || offChord <= eps) {
        poly.erase(poly.begin() + static_cast<long>(i));
        changed = true;
      }
    }
  }
  return poly;
}

struct AreaPolygon {
  PlaneFrame frame;
  Polygon2 polygon;
};

bool onArea(const Eigen::Vector3d& x, const AreaPolygon& a, double eps) {
  return std::abs(a.frame.normal.dot(x - a.frame.origin)) <= eps && distanceToConvex(a.polygon, a.frame.to2d(x)) <= eps;
}

bool onArea(const Eigen::Vector3d& x, const std::vector<AreaPolygon>& areas, double eps) {
  return std::any_of(areas.begin(), areas.end(), [&](const AreaPolygon& a) { return onArea(x, a, eps); });
}

double distanceToSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = d.squaredNorm() > 0 ? std::clamp(d.dot(x - a) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * d - x).norm();
}

// Joins line b into line a when they are collinear within eps and overlap or touch. The
// joined line runs between the outermost of the four ends, each keeping its gap.
bool joinCollinear(Contact& a, const Contact& b, double eps) {
  const Eigen::Vector3d origin = a.points[0], dir = (a.points[1] - a.points[0]).normalized();
  auto offLine = [&](const Eigen::Vector3d& x) { return (x - origin - dir.dot(x - origin) * dir).norm(); };
  if (offLine(b.points[0]) > eps || offLine(b.points[1]) > eps) return false;
  const double a0 = 0.0, a1 = dir.dot(a.points[1] - origin);
  const double b0 = dir.dot(b.points[0] - origin), b1 = dir.dot(b.points[1] - origin);
  const double lo = std::min(b0, b1), hi = std::max(b0, b1);
  if (lo > a1 + eps || hi < a0 - eps) return false;
  const std::array<std::pair<double, const Contact*>, 4> ends{{{a0, &a}, {a1, &a}, {b0, &b}, {b1, &b}}};
  auto endOf = [&](size_t k) { return std::make_pair(ends[k].second->points[k % 2], ends[k].second->gapAt(k % 2)); };
  size_t first = 0, last = 0;
  for (size_t k = 1; k < ends.size(); ++k) {
    if (ends[k].first < ends[first].first) first = k;
    if (ends[k].first > ends[last].first) last = k;
  }
  const auto [p0, g0] = endOf(first);  // copies: a's own ends are about to be replaced
  const auto [p1, g1] = endOf(last);
  a.points.clear();
  a.gaps.clear();
  a.addPoint(p0, g0);
  a.addPoint(p1, g1);
  return true;
}

// Whether A and B, at the features of piece c, can be touched along n (from B towards A).
std::pair<bool, bool> admits(const PairGeometry& g, const Contact& c, const Eigen::Vector3d& n, double eps) {
  const Eigen::Vector3d outwardA = -(g.R_WA.transpose() * n), outwardB = g.R_WB.transpose() * n;
  return {inNormalCone(*g.meshA, c.featureA, outwardA, eps), inNormalCone(*g.meshB, c.featureB, outwardB, eps)};
}

// The normal of pieces found to be one contact (see reduceContacts); false when no piece
// admits any of the proposed normals at both its features: a contact at the rim of a face
// from the side it cannot be touched from, which a true contact elsewhere covers.
bool jointNormal(const std::vector<const Contact*>& pieces, const PairGeometry* geometry, double eps,
                 Eigen::Vector3d& normal) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  bool agree = true;
  for (const Contact* c : pieces) {
    sum += c->normal;
    agree = agree && (c->normal - pieces[0]->normal).norm() <= kNormalConeSlack;
  }
  normal = sum.norm() > kParallelSine ? Eigen::Vector3d(sum.normalized()) : pieces[0]->normal;
  if (!geometry) return true;
  bool admitted = false;
  int bestVotes = -1;
  for (const Contact* candidate : pieces) {
    const Eigen::Vector3d& n = candidate->normal;  // from B towards A: A is touched from -n, B from n
    int votes = 0;
    bool wholly = false;  // some piece admits n at both its features
    for (const Contact* c : pieces) {
      const auto [a, b] = admits(*geometry, *c, n, eps);
      votes += a + b;
      wholly = wholly || (a && b);
    }
    if (!wholly) continue;
    admitted = true;
    if (agree) break;  // pieces that agree keep their mean normal
    if (votes > bestVotes) bestVotes = votes, normal = n;
  }
  return admitted;
}

// Each end of a joined contact takes its gap as measured along the joint normal: the
// smallest gap at that place (within eps) among the pieces found with that normal. The
// pieces of one corner can disagree: a vertex 39 um off a side face, and beside it two
// edges crossing 98 um deep along the normal taken; keeping the first piece's gap hid
// overlaps from the solver that the next intersection test then found too deep.
// The contact's features become those of the deepest such piece, the pair whose normal
// it is.
void takeGapsAlongNormal(Contact& c, const std::vector<const Contact*>& pieces, double eps) {
  c.gaps.resize(c.points.size(), c.separation);  // a contact built without gaps: one for all
  c.separation = std::numeric_limits<double>::infinity();
  const Contact* deepest = nullptr;
  double deepestGap = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < c.points.size(); ++i) {
    double gap = std::numeric_limits<double>::infinity();
    for (const Contact* piece : pieces) {
      if ((piece->normal - c.normal).norm() > kNormalConeSlack) continue;
      for (size_t j = 0; j < piece->points.size(); ++j) {
        if ((piece->points[j] - c.points[i]).norm() > eps) continue;
        gap = std::min(gap, piece->gapAt(j));
        if (piece->gapAt(j) < deepestGap) deepestGap = piece->gapAt(j), deepest = piece;
      }
    }
    if (gap < std::numeric_limits<double>::infinity()) c.gaps[i] = gap;
    c.separation = std::min(c.separation, c.gaps[i]);
  }
  if (deepest) c.featureA = deepest->featureA, c.featureB = deepest->featureB;
}

// For a pair judged polygon pair by polygon pair (PairGeometry::sunkHeldAlongEachFace):
// the pieces of one point sunk behind faces other than the joint contact's, each as a
// contact of its own along its face's normal, at most one per normal.
void addSunkAlongOtherNormals(const Eigen::Vector3d& jointNormal, const std::vector<const Contact*>& pieces,
                              const PairGeometry& g, double eps, std::vector<Contact>& kept) {
  std::vector<Eigen::Vector3d> taken{jointNormal};
  for (const Contact* piece : pieces) {
    if (piece->separation >= 0.0) continue;
    const Eigen::Vector3d& n = piece->normal;
    auto same = [&n](const Eigen::Vector3d& m) { return (m - n).norm() <= kNormalConeSlack; };
    if (std::any_of(taken.begin(), taken.end(), same)) continue;
    const auto [a, b] = admits(g, *piece, n, eps);
    if (!a || !b) continue;
    Contact c = *piece;
    takeGapsAlongNormal(c, pieces, eps);
    taken.push_back(n);
    kept.push_back(std::move(c));
  }
}

// The joined contacts with their joint normals and gaps, less those no piece admits.
std::vector<Contact> withJointNormals(std::vector<Contact> joined, const std::vector<std::vector<const Contact*>>& pieces,
                                      const PairGeometry* geometry, double eps) {
  std::vector<Contact> kept;
  for (size_t k = 0; k < joined.size(); ++k) {
    if (!jointNormal(pieces[k], geometry, eps, joined[k].normal)) continue;
    takeGapsAlongNormal(joined[k], pieces[k], eps);
    kept.push_back(std::move(joined[k]));
    if (geometry && geometry->sunkHeldAlongEachFace) {
      const Eigen::Vector3d normal = kept.back().normal;  // a copy: kept grows under it
      addSunkAlongOtherNormals(normal, pieces[k], *geometry, eps, kept);
    }
  }
  return kept;
}

}  // namespace

std::vector<Contact> reduceContacts(const std::vector<Contact>& raw, double eps, const PairGeometry* geometry) {
  std::vector<AreaCluster> clusters;
  std::vector<const Contact*> lines, points;
  std::vector<Contact> out;
  for (const Contact& c : raw) {
    if (c.type == ContactType::Line) lines.push_back(&c);
    if (c.type == ContactType::Point) points.push_back(&c);
    if (c.type != ContactType::Area) continue;
    AreaCluster* home = nullptr;
    for (AreaCluster& k : clusters)
      if (k.frame.normal.dot(c.normal) >= std::cos(kFlatEdgeAngle) &&
          std::abs(k.frame.normal.dot(c.points[0] - k.frame.origin)) <= eps)
        home = &k;
    if (!home) {
      clusters.push_back({PlaneFrame(c.points[0], c.normal), {}, {}, {}, {}, {}, c.featureA, c.featureB});
      home = &clusters.back();
    }
    Polygon2 poly;
    for (size_t i = 0; i < c.points.size(); ++i) {
      poly.push_back(home->frame.to2d(c.points[i]));
      home->corners2d.push_back(poly.back());
      home->corners3d.push_back(c.points[i]);
      home->gaps.push_back(c.gapAt(i));
    }
    const double area = signedArea(poly);
    home->pieces.push_back(std::move(poly));
    home->areas.push_back(area);
  }

  std::vector<AreaPolygon> areas;
  for (AreaCluster& k : clusters) {
    for (Polygon2& merged : mergeConvexUnions(std::move(k.pieces), std::move(k.areas), eps)) {
      Polygon2 poly = simplify(std::move(merged), eps);
      Contact c;
      c.type = ContactType::Area;
      c.normal = k.frame.normal;
      c.featureA = k.featureA;
      c.featureB = k.featureB;
      for (const Eigen::Vector2d& x : poly) {
        const size_t corner = k.cornerAt(x);
        c.addPoint(k.corners3d[corner], k.gaps[corner]);
      }
      out.push_back(std::move(c));
      areas.push_back({k.frame, std::move(poly)});
    }
  }

  // The same segment found from several feature pairs (an edge along a face, the face's
  // edge along the other's face, the two edges) is one contact: join collinear pieces and
  // give the joined line their joint normal.
  std::vector<Contact> keptLines;
  std::vector<std::vector<const Contact*>> linePieces;
  for (const Contact* line : lines) {
    if (onArea(line->points[0], areas, eps) && onArea(line->points[1], areas, eps)) continue;
    bool joined = false;
    for (size_t k = 0; k < keptLines.size() && !joined; ++k)
      if (joinCollinear(keptLines[k], *line, eps)) joined = true, linePieces[k].push_back(line);
    if (!joined) keptLines.push_back(*line), linePieces.push_back({line});
  }
  for (bool changed = true; changed;) {  // joining can make two kept lines overlap
    changed = false;
    for (size_t i = 0; i < keptLines.size() && !changed; ++i)
      for (size_t j = i + 1; j < keptLines.size() && !changed; ++j)
        if (joinCollinear(keptLines[i], keptLines[j], eps)) {
          linePieces[i].insert(linePieces[i].end(), linePieces[j].begin(), linePieces[j].end());
          keptLines.erase(keptLines.begin() + static_cast<long>(j));
          linePieces.erase(linePieces.begin() + static_cast<long>(j));
          changed = true;
        }
  }
  keptLines = withJointNormals(std::move(keptLines), linePieces, geometry, eps);

  std::vector<Contact> keptPoints;
  std::vector<std::vector<const Contact*>> pointPieces;
  for (const Contact* point : points) {
    const Eigen::Vector3d& x = point->points[0];
    // An area or line covers a point on it; but where the pair is judged polygon pair by
    // polygon pair, not a point sunk along a normal of its own that both its features
    // admit (a cup's bottom edge along another cup's inner wall, dipping under its rim
    // edge at the corner): that contact's normal would not hold it (see
    // addSunkAlongOtherNormals).
    bool ownNormal = false;
    if (geometry && geometry->sunkHeldAlongEachFace && point->separation < 0.0) {
      const auto [a, b] = admits(*geometry, *point, point->normal, eps);
      ownNormal = a && b;
    }
    auto holds = [&](const Eigen::Vector3d& n) { return !ownNormal || (n - point->normal).norm() <= kNormalConeSlack; };
    bool covered = false;
    for (const AreaPolygon& a : areas) covered = covered || (onArea(x, a, eps) && holds(a.frame.normal));
    for (const Contact& l : keptLines)
      covered = covered || (distanceToSegment(x, l.points[0], l.points[1]) <= eps && holds(l.normal));
    for (size_t k = 0; k < keptPoints.size() && !covered; ++k)
      if ((keptPoints[k].points[0] - x).norm() <= eps) covered = true, pointPieces[k].push_back(point);
    if (!covered) keptPoints.push_back(*point), pointPieces.push_back({point});
  }
  keptPoints = withJointNormals(std::move(keptPoints), pointPieces, geometry, eps);
  out.insert(out.end(), std::make_move_iterator(keptLines.begin()), std::make_move_iterator(keptLines.end()));
  out.insert(out.end(), std::make_move_iterator(keptPoints.begin()), std::make_move_iterator(keptPoints.end()));
  return out;
}

}  // namespace polysim::collision
