#pragma once
// How ODE's contacts compare with polysim's at the same configuration: normals, where
// ODE's points lie relative to polysim's points, lines and areas, and ODE's depth against
// polysim's separation.

#include <ode/ode.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "collision/contact.h"

namespace polysim::sim {

/// polysim's contacts sit in a band around zero separation (|separation| <= tolerance),
/// where ODE, which reports overlaps only, may see nothing. So ODE is handed the same
/// poses with body a pressed into b along polysim's normal by kOdePressFactor times the
/// tolerance; ODE's depth should then be that press minus polysim's separation.
inline constexpr double kOdePressFactor = 2.0;

/// The disagreement for one pair at one configuration; the worst over ODE's contacts.
struct PairDisagreement {
  int odeContacts = 0;
  double normalAngle = 0.0;    // rad, ODE's normal against the nearest polysim contact's
  double pointDistance = 0.0;  // m, across the normal: ODE's point to the nearest polysim point, line or area
  double depthError = 0.0;     // m, |ODE depth - (press - polysim separation)|
};

/// The direction to press a into b: the mean of the pair's contact normals (unit).
Eigen::Vector3d pressDirection(const collision::PairResult& pair);

/// Compares ODE's contacts (normals from b towards a) with polysim's contacts of the same
/// pair, ODE having been given the poses pressed by `press` (m) along pressDirection.
/// ODE contacts shallower than press - tolerance are left out: pressing brought them in
/// from gaps wider than the tolerance, where polysim rightly reports nothing (a tipping
/// box's far corner).
PairDisagreement comparePairContacts(const collision::PairResult& pair, const std::vector<dContactGeom>& ode,
                                     double press, double tolerance);

/// Distance (m) from p to a contact's point, segment or polygon, measured across the
/// contact normal (p is first projected onto the contact's plane): whether p lies on the
/// contact as seen along the normal. Offsets along the normal are depths, compared apart.
double lateralDistanceToContact(const collision::Contact& contact, const Eigen::Vector3d& p);

/// The disagreements over a run: counts, and each measure's largest value with where
/// (time, pair) it happened.
class ContactAgreement {
 public:
  /// Adds one pair's comparison; `pair` and `ode` are kept as the example when this is the
  /// worst yet of a measure.
  void add(double time, const std::string& a, const std::string& b, const collision::PairResult& pair,
           const std::vector<dContactGeom>& ode, const PairDisagreement& d);
  /// {"states", "pairs", "ode_missed", "normal_angle_rad", "point_distance", "depth_error"};
  /// each of the last three {"max", "time", "pair", "polysim", "ode"} with both engines'
  /// contacts at that state; "ode_missed" {"count", "first_time", "first_pair"}.
  nlohmann::ordered_json toJson() const;

  long pairsCompared() const { return pairs_; }
  long pairsOdeMissed() const { return missed_; }
  double maxNormalAngle() const { return normal_.value; }
  double maxPointDistance() const { return point_.value; }
  double maxDepthError() const { return depth_.value; }

  void countState() { ++states_; }

 private:
  struct Worst {
    double value = 0.0, time = 0.0;
    std::string pair;
    nlohmann::ordered_json polysim, ode;  // the contacts at that state
    bool offer(double v, double t, const std::string& p);
    nlohmann::ordered_json toJson() const;
  };
  long states_ = 0, pairs_ = 0, missed_ = 0;
  Worst normal_, point_, depth_, firstMissed_;
};

}  // namespace polysim::sim
