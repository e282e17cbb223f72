#include "sim/analytic_reference.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace polysim::sim {
namespace {

const BodySpec& find(const Scene& scene, const std::string& name) {
  for (const BodySpec& b : scene.bodies)
    if (b.name == name) return b;
  throw std::invalid_argument(scene.file + ": no body \"" + name + "\" for the analytic reference");
}

void requireAtRest(const Scene& scene, const BodySpec& body) {
  if (body.isStatic || !body.velocity.isZero() || !body.angularVelocity.isZero())
    throw std::invalid_argument(scene.file + ": body \"" + body.name +
                                "\": the analytic reference needs a dynamic body starting at rest");
}

}  // namespace

DropReference dropReference(const Scene& scene, const std::string& name) {
  const BodySpec& body = find(scene, name);
  requireAtRest(scene, body);
  const double g = scene.gravity.norm();
  const Eigen::Vector3d up = scene.up();
  double lowest = std::numeric_limits<double>::infinity(), top = -std::numeric_limits<double>::infinity();
  double e = body.restitution.value_or(scene.contact.restitution);  // polysim and ODE take the pair's larger
  for (const Eigen::Vector3d& v : body.mesh.vertices) lowest = std::min(lowest, (body.pose() * v).dot(up));
  for (const BodySpec& b : scene.bodies) {
    if (!b.isStatic && b.name != name)
      throw std::invalid_argument(scene.file + ": body \"" + name + "\": not dropped alone (\"" + b.name + "\" moves too)");
    if (!b.isStatic) continue;
    for (const Eigen::Vector3d& v : b.mesh.vertices) top = std::max(top, (b.pose() * v).dot(up));
    e = std::max(e, b.restitution.value_or(scene.contact.restitution));
  }
  if (!(lowest > top))
    throw std::invalid_argument(scene.file + ": body \"" + name + "\": not above every static body, not a drop");
  DropReference r;
  r.gap = lowest - top;
  r.firstContactTime = std::sqrt(2.0 * r.gap / g);
  r.restHeight = body.position.dot(up) - r.gap;
  r.bounceApex = r.restHeight + e * e * r.gap;
  return r;
}

double inclineSlideDistance(const Scene& scene, const std::string& name, const std::string& rampName, double duration) {
  const BodySpec& body = find(scene, name);
  const BodySpec& ramp = find(scene, rampName);
  requireAtRest(scene, body);
  const double g = scene.gravity.norm();
  const Eigen::Vector3d up = scene.up();
  const double theta = std::acos(std::clamp((ramp.orientation * Eigen::Vector3d::UnitZ()).dot(up), -1.0, 1.0));
  const double mu = std::sqrt(body.friction.value_or(scene.contact.friction) * ramp.friction.value_or(scene.contact.friction));
  const double acceleration = g * (std::sin(theta) - mu * std::cos(theta));
  return acceleration > 0 ? 0.5 * acceleration * duration * duration : 0.0;
}

}  // namespace polysim::sim
