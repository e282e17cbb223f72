#pragma once
// What the run summary, the comparison and the sweep need from a simulator, so that
// polysim and ODE are driven and measured by the same code.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace polysim::sim {

/// One dynamic body's state, as both engines report it (world frame).
struct BodyState {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, the body frame's origin (the scene's position)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();         // m/s, centre of mass
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  // rad/s
  bool atRest = false;                                        // dynamics::atRest
};

class Engine {
 public:
  virtual ~Engine() = default;
  /// Advances the simulation by dt (s).
  virtual void step(double dt) = 0;
  /// The dynamic bodies, in scene order.
  virtual std::vector<BodyState> bodyStates() const = 0;
  /// Kinetic plus gravitational potential energy of the dynamic bodies (J).
  virtual double energy() const = 0;
  /// The deepest overlap (m) between bodies during the last step, as the engine sees it.
  virtual double stepPenetration() const = 0;
  /// When bodies first touched (s), if they have.
  virtual std::optional<double> firstContactTime() const = 0;
  /// How many dynamic bodies are asleep (the scene's "sleep"; ODE: auto-disabled).
  virtual int sleepingBodies() const = 0;
};

}  // namespace polysim::sim
