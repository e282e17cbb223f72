#pragma once
// SPEC.md's JSON for contacts and pairs.

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "collision/intersection.h"

namespace polysim::sim {

/// A number as printed: rounded to 1e-12 so that round-off (0.49999999999999994, -0.0)
/// does not reach users; 1e-12 m is far below any contact tolerance.
double forOutput(double x);
nlohmann::ordered_json toJson(const Eigen::Vector3d& v);

/// A body's state as the summary and the step log print it: {"name", "position" (frame
/// origin, m), "orientation" [w, x, y, z], "velocity" (m/s), "angular_velocity" (rad/s)}.
nlohmann::ordered_json bodyStateToJson(const std::string& name, const Eigen::Vector3d& position,
                                       const Eigen::Quaterniond& orientation, const Eigen::Vector3d& velocity,
                                       const Eigen::Vector3d& angularVelocity);

/// One contact: {"type", "normal", "points", "separation"}.
nlohmann::ordered_json toJson(const collision::Contact& c);

/// {"status", "pairs": [{"a", "b", "status", "contacts", ...}]} as `polysim contacts`
/// prints it; `names` are the database's object names.
nlohmann::ordered_json intersectionToJson(const collision::IntersectionResult& r, const std::vector<std::string>& names);
nlohmann::ordered_json pairsToJson(const std::vector<collision::PairResult>& pairs, const std::vector<std::string>& names);
/// [["a", "b"], ...]: the pairs collisionDetect() found interpenetrating just past its
/// returned time (TocResult::crossing), by name.
nlohmann::ordered_json crossingToJson(const std::vector<std::pair<int, int>>& crossing, const std::vector<std::string>& names);

}  // namespace polysim::sim
