#include "collision/segment_distance.h"

#include <algorithm>
#include <limits>

namespace polysim::collision {

SegmentClosestPoints closestPointsOnSegments(const Eigen::Vector3d& p0, const Eigen::Vector3d& u,
                                             const Eigen::Vector3d& q0, const Eigen::Vector3d& v) {
  // Minimise |p0 + s u - q0 - t v|^2: solve for s with t eliminated, clamp, then solve
  // for t and clamp, re-solving s when t was clamped.
  const Eigen::Vector3d r = p0 - q0;
  const double a = u.squaredNorm(), e = v.squaredNorm(), f = v.dot(r);
  const double tiny = std::numeric_limits<double>::min();
  double s = 0.0, t = 0.0;
  if (a <= tiny && e <= tiny) {
    s = t = 0.0;
  } else if (a <= tiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = u.dot(r);
    if (e <= tiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = u.dot(v), denom = a * e - b * b;
      s = denom > tiny ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) t = 0.0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1.0) t = 1.0, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  SegmentClosestPoints out;
  out.onFirst = p0 + s * u;
  out.onSecond = q0 + t * v;
  out.distance = (out.onFirst - out.onSecond).norm();
  out.s = s;
  out.t = t;
  return out;
}

}  // namespace polysim::collision
