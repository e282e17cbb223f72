#pragma once
// polysim's step loop (World) behind the Engine interface.

#include "sim/engine.h"
#include "sim/world.h"

namespace polysim::sim {

class PolysimEngine : public Engine {
 public:
  PolysimEngine(const Scene& scene, collision::TocMethod method) : world_(scene, method) {}

  void step(double dt) override { report_ = &world_.step(dt); }
  std::vector<BodyState> bodyStates() const override;
  double energy() const override { return world_.energy(); }
  double stepPenetration() const override { return report_ ? report_->penetration : 0.0; }
  std::optional<double> firstContactTime() const override;
  int sleepingBodies() const override;

  const World& world() const { return world_; }
  /// The last step's report (valid after the first step).
  const StepReport& lastReport() const { return *report_; }

 private:
  World world_;
  const StepReport* report_ = nullptr;
};

}  // namespace polysim::sim
