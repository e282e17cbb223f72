#include "sim/json_output.h"

#include <cmath>

namespace polysim::sim {

double forOutput(double x) {
  constexpr double kOutputResolution = 1e12;  // 1 / 1e-12
  return std::round(x * kOutputResolution) / kOutputResolution + 0.0;  // + 0.0 turns -0 into 0
}

nlohmann::ordered_json toJson(const Eigen::Vector3d& v) {
  return nlohmann::ordered_json::array({forOutput(v.x()), forOutput(v.y()), forOutput(v.z())});
}

nlohmann::ordered_json bodyStateToJson(const std::string& name, const Eigen::Vector3d& position,
                                       const Eigen::Quaterniond& q, const Eigen::Vector3d& velocity,
                                       const Eigen::Vector3d& angularVelocity) {
  return {{"name", name},
          {"position", toJson(position)},
          {"orientation", {forOutput(q.w()), forOutput(q.x()), forOutput(q.y()), forOutput(q.z())}},
          {"velocity", toJson(velocity)},
          {"angular_velocity", toJson(angularVelocity)}};
}

nlohmann::ordered_json toJson(const collision::Contact& c) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array(), gaps = nlohmann::ordered_json::array();
  for (size_t i = 0; i < c.points.size(); ++i) {
    points.push_back(toJson(c.points[i]));
    gaps.push_back(forOutput(c.gapAt(i)));
  }
  return {{"type", collision::toString(c.type)},
          {"normal", toJson(c.normal)},
          {"points", points},
          {"separation", forOutput(c.separation)},
          {"gaps", gaps}};
}

nlohmann::ordered_json crossingToJson(const std::vector<std::pair<int, int>>& crossing, const std::vector<std::string>& names) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& [a, b] : crossing) list.push_back({names[a], names[b]});
  return list;
}

nlohmann::ordered_json pairsToJson(const std::vector<collision::PairResult>& pairs, const std::vector<std::string>& names) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const collision::PairResult& p : pairs) {
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (const collision::Contact& c : p.contacts) contacts.push_back(toJson(c));
    nlohmann::ordered_json pair = {{"a", names[p.a]}, {"b", names[p.b]}, {"status", collision::toString(p.status)},
                           {"contacts", contacts}};
    if (p.status == collision::Status::Interpenetrating) pair["depth"] = forOutput(p.depth);
    out.push_back(pair);
  }
  return out;
}

nlohmann::ordered_json intersectionToJson(const collision::IntersectionResult& r, const std::vector<std::string>& names) {
  return {{"status", collision::toString(r.status)}, {"pairs", pairsToJson(r.pairs, names)}};
}

}  // namespace polysim::sim
