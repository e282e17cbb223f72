#include "collision/clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace polysim::collision {

PlaneFrame::PlaneFrame(const Eigen::Vector3d& o, const Eigen::Vector3d& n) : origin(o), normal(n) {
  // Any unit vector perpendicular to n; pick the axis least aligned with n.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  if (std::abs(n.y()) < std::abs(n.x()) && std::abs(n.y()) <= std::abs(n.z())) axis = Eigen::Vector3d::UnitY();
  else if (std::abs(n.z()) < std::abs(n.x())) axis = Eigen::Vector3d::UnitZ();
  u = n.cross(axis).normalized();
  v = n.cross(u);
}

double signedArea(const Polygon2& poly) {
  double twice = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) twice += cross2(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * twice;
}

double perimeter(const Polygon2& poly) {
  double sum = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) sum += (poly[(i + 1) % poly.size()] - poly[i]).norm();
  return sum;
}

Polygon2 clipConvex(const Polygon2& subject, const Polygon2& clipper) {
  Polygon2 out, work;
  clipConvex(subject, clipper, out, work);
  return out;
}

void clipConvex(const Polygon2& subject, const Polygon2& clipper, Polygon2& out, Polygon2& in) {
  out.assign(subject.begin(), subject.end());
  for (size_t e = 0; e < clipper.size() && !out.empty(); ++e) {
    const Eigen::Vector2d& a = clipper[e];
    const Eigen::Vector2d edge = clipper[(e + 1) % clipper.size()] - a;
    // side(p) >= 0: p is on the left of the edge, inside.
    auto side = [&](const Eigen::Vector2d& p) { return cross2(edge, p - a); };
    // Most edges of a small clipper keep the whole subject (a floor triangle under a box):
    // nothing to copy.
    if (std::all_of(out.begin(), out.end(), [&](const Eigen::Vector2d& p) { return side(p) >= 0; })) continue;
    in.swap(out);
    out.clear();
    for (size_t i = 0; i < in.size(); ++i) {
      const Eigen::Vector2d& p = in[i];
      const Eigen::Vector2d& q = in[(i + 1) % in.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
    }
  }
}

bool clipSegment(const Polygon2& convex, double grow, Eigen::Vector2d& a, Eigen::Vector2d& b) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (size_t e = 0; e < convex.size(); ++e) {
    const Eigen::Vector2d& p = convex[e];
    const Eigen::Vector2d edge = convex[(e + 1) % convex.size()] - p;
    const double len = edge.norm();
    // Signed distance to the edge's line, positive inside: f(t) = fa + t * fd >= -grow.
    const double fa = cross2(edge, a - p) / len + grow;
    const double fd = cross2(edge, d) / len;
    if (std::abs(fd) < std::numeric_limits<double>::min()) {
      if (fa < 0) return false;
      continue;
    }
    const double t = -fa / fd;
    if (fd > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  // An end the clip did not move is kept exactly (callers compare it).
  const Eigen::Vector2d a0 = a;
  if (t0 > 0.0) a = a0 + t0 * d;
  if (t1 < 1.0) b = a0 + t1 * d;
  return true;
}

Eigen::Vector2d nearestPointToConvex(const Polygon2& convex, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  Eigen::Vector2d best = a;
  double bestDistance = distanceToConvex(convex, a);
  auto consider = [&](const Eigen::Vector2d& x) {
    const double d = distanceToConvex(convex, x);
    if (d < bestDistance) best = x, bestDistance = d;
  };
  consider(b);
  const Eigen::Vector2d ab = b - a;
  if (ab.squaredNorm() > 0)
    for (const Eigen::Vector2d& corner : convex) consider(a + std::clamp(ab.dot(corner - a) / ab.squaredNorm(), 0.0, 1.0) * ab);
  return best;
}

double distanceToConvex(const Polygon2& convex, const Eigen::Vector2d& p) {
  bool inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < convex.size(); ++e) {
    const Eigen::Vector2d& a = convex[e];
    const Eigen::Vector2d edge = convex[(e + 1) % convex.size()] - a;
    if (cross2(edge, p - a) < 0) inside = false;
    const double len2 = edge.squaredNorm();
    const double t = len2 > 0 ? std::clamp(edge.dot(p - a) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * edge - p).norm());
  }
  return inside ? 0.0 : best;
}

namespace {

// Drops the points strictly inside the quadrilateral of the leftmost, lowest, rightmost
// and highest points: they cannot be hull corners (Akl and Toussaint's throw-away step).
// Area contacts merged from many small pieces have most of their points inside.
void dropInteriorPoints(std::vector<Eigen::Vector2d>& pts) {
  if (pts.size() < 8) return;
  auto lexLess = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  };
  Eigen::Vector2d left = pts[0], right = pts[0], low = pts[0], high = pts[0];
  for (const Eigen::Vector2d& p : pts) {
    if (lexLess(p, left)) left = p;
    if (lexLess(right, p)) right = p;
    if (p.y() < low.y() || (p.y() == low.y() && p.x() > low.x())) low = p;
    if (p.y() > high.y() || (p.y() == high.y() && p.x() < high.x())) high = p;
  }
  const std::array<Eigen::Vector2d, 4> quad{left, low, right, high};  // counter-clockwise
  auto strictlyInside = [&](const Eigen::Vector2d& p) {
    for (int i = 0; i < 4; ++i)
      if (cross2(quad[(i + 1) % 4] - quad[i], p - quad[i]) <= 0) return false;
    return true;
  };
  pts.erase(std::remove_if(pts.begin(), pts.end(), strictlyInside), pts.end());
}

}  // namespace

Polygon2 convexHull(std::vector<Eigen::Vector2d> pts) {
  dropInteriorPoints(pts);
  std::sort(pts.begin(), pts.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (pts.size() < 3) return pts;
  Polygon2 hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {  // lower hull
    while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross2(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

void clipBelow(const std::vector<Eigen::Vector3d>& in, const Eigen::Vector3d& normal, double offset,
               std::vector<Eigen::Vector3d>& out) {
  out.clear();
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector3d& x = in[i];
    const Eigen::Vector3d& y = in[(i + 1) % in.size()];
    const double sx = normal.dot(x) - offset, sy = normal.dot(y) - offset;
    if (sx <= 0) out.push_back(x);
    if ((sx <= 0) != (sy <= 0)) out.push_back(x + (sx / (sx - sy)) * (y - x));
  }
}

}  // namespace polysim::collision
