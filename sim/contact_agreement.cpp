#include "sim/contact_agreement.h"

#include <cmath>
#include <limits>

#include "collision/clip.h"
#include "sim/json_output.h"

namespace polysim::sim {

Eigen::Vector3d pressDirection(const collision::PairResult& pair) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const collision::Contact& c : pair.contacts) sum += c.normal;
  return sum.norm() > 0 ? Eigen::Vector3d(sum.normalized()) : Eigen::Vector3d::UnitZ();
}

double lateralDistanceToContact(const collision::Contact& c, const Eigen::Vector3d& pOffPlane) {
  using collision::ContactType;
  const Eigen::Vector3d p = pOffPlane - c.normal * c.normal.dot(pOffPlane - c.points[0]);
  if (c.type == ContactType::Point) return (p - c.points[0]).norm();
  if (c.type == ContactType::Line) {
    const Eigen::Vector3d d = c.points[1] - c.points[0];
    const double s = d.squaredNorm() > 0 ? std::clamp((p - c.points[0]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - (c.points[0] + s * d)).norm();
  }
  const collision::PlaneFrame frame(c.points[0], c.normal);
  collision::Polygon2 polygon;
  for (const Eigen::Vector3d& q : c.points) polygon.push_back(frame.to2d(q));
  return collision::distanceToConvex(polygon, frame.to2d(p));
}

PairDisagreement comparePairContacts(const collision::PairResult& pair, const std::vector<dContactGeom>& ode,
                                     double press, double tolerance) {
  PairDisagreement d;
  for (const dContactGeom& g : ode) {
    if (g.depth < press - tolerance) continue;
    ++d.odeContacts;
    const Eigen::Vector3d p(g.pos[0], g.pos[1], g.pos[2]), n(g.normal[0], g.normal[1], g.normal[2]);
    const collision::Contact* nearest = nullptr;
    double distance = std::numeric_limits<double>::infinity();
    for (const collision::Contact& c : pair.contacts) {
      const double dc = lateralDistanceToContact(c, p);
      if (dc < distance) distance = dc, nearest = &c;
    }
    if (!nearest) continue;
    d.pointDistance = std::max(d.pointDistance, distance);
    d.normalAngle = std::max(d.normalAngle, std::acos(std::clamp(n.dot(nearest->normal), -1.0, 1.0)));
    d.depthError = std::max(d.depthError, std::abs(g.depth - (press - nearest->separation)));
  }
  return d;
}

namespace {

nlohmann::ordered_json odeContactsToJson(const std::vector<dContactGeom>& ode) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const dContactGeom& g : ode)
    out.push_back({{"point", toJson(Eigen::Vector3d(g.pos[0], g.pos[1], g.pos[2]))},
                   {"normal", toJson(Eigen::Vector3d(g.normal[0], g.normal[1], g.normal[2]))},
                   {"depth", forOutput(g.depth)}});
  return out;
}

nlohmann::ordered_json polysimContactsToJson(const collision::PairResult& pair) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const collision::Contact& c : pair.contacts) out.push_back(toJson(c));
  return out;
}

}  // namespace

bool ContactAgreement::Worst::offer(double v, double t, const std::string& p) {
  if (!pair.empty() && v <= value) return false;
  value = v, time = t, pair = p;
  return true;
}

nlohmann::ordered_json ContactAgreement::Worst::toJson() const {
  if (pair.empty()) return nullptr;
  return {{"max", forOutput(value)}, {"time", forOutput(time)}, {"pair", pair}, {"polysim", polysim}, {"ode", ode}};
}

void ContactAgreement::add(double time, const std::string& a, const std::string& b, const collision::PairResult& pair,
                           const std::vector<dContactGeom>& ode, const PairDisagreement& d) {
  ++pairs_;
  const std::string names = a + "/" + b;
  if (d.odeContacts == 0) {
    if (missed_++ == 0) firstMissed_.offer(0.0, time, names);
    return;
  }
  for (auto [worst, value] : {std::pair{&normal_, d.normalAngle}, {&point_, d.pointDistance}, {&depth_, d.depthError}})
    if (worst->offer(value, time, names)) {
      worst->polysim = polysimContactsToJson(pair);
      worst->ode = odeContactsToJson(ode);
    }
}

nlohmann::ordered_json ContactAgreement::toJson() const {
  nlohmann::ordered_json j;
  j["states"] = states_;
  j["pairs"] = pairs_;
  j["ode_missed"] = {{"count", missed_},
                     {"first_time", firstMissed_.pair.empty() ? nlohmann::ordered_json(nullptr)
                                                              : nlohmann::ordered_json(forOutput(firstMissed_.time))},
                     {"first_pair", firstMissed_.pair.empty() ? nlohmann::ordered_json(nullptr)
                                                              : nlohmann::ordered_json(firstMissed_.pair)}};
  j["normal_angle_rad"] = normal_.toJson();
  j["point_distance"] = point_.toJson();
  j["depth_error"] = depth_.toJson();
  return j;
}

}  // namespace polysim::sim
