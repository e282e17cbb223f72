// The run summary's figures against runs worked by hand: an engine that plays back a
// scripted sequence of energies, overlaps and positions, so every figure of SPEC.md's
// summary has one right value.

#include "sim/run_record.h"

#include <gtest/gtest.h>

#include <cmath>

namespace polysim::sim {
namespace {

// Plays back one scripted state per step; the state before the first step is index 0.
class ScriptedEngine : public Engine {
 public:
  struct State {
    double energy, penetration, height;
    bool touched;
    bool atRest = false;
  };
  explicit ScriptedEngine(std::vector<State> script) : script_(std::move(script)) {}

  void step(double dt) override {
    ++k_;
    time_ += dt;
    if (script_[k_].touched && !firstContact_) firstContact_ = time_;
  }
  std::vector<BodyState> bodyStates() const override {
    BodyState b;
    b.name = "box";
    b.position = Eigen::Vector3d(0.25 * k_, 0, script_[k_].height);
    b.atRest = script_[k_].atRest;
    return {b};
  }
  double energy() const override { return script_[k_].energy; }
  double stepPenetration() const override { return script_[k_].penetration; }
  std::optional<double> firstContactTime() const override { return firstContact_; }
  int sleepingBodies() const override { return 0; }

 private:
  std::vector<State> script_;
  size_t k_ = 0;
  double time_ = 0.0;
  std::optional<double> firstContact_;
};

TEST(RunRecord, EnergyIncreaseIsTheLargestRiseOverTheInitialEnergy) {
  // Rises by 1 J in each of two steps, then falls below the start: the largest rise over
  // the initial 10 J is 2 J (a rise over the previous step would be 1 J).
  ScriptedEngine engine({{10, 0, 2, false}, {11, 0, 2, false}, {12, 0, 2, false}, {9, 0, 2, false}, {9.5, 0, 2, false}});
  const RunRecord r = recordRun(engine, 4, 0.5, Eigen::Vector3d::UnitZ());
  EXPECT_DOUBLE_EQ(r.initialEnergy, 10.0);
  EXPECT_DOUBLE_EQ(r.finalEnergy, 9.5);
  EXPECT_DOUBLE_EQ(r.maxEnergyIncrease, 2.0);

  const nlohmann::ordered_json s = summaryToJson("scripted", r);
  EXPECT_DOUBLE_EQ(s["energy"]["initial"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(s["energy"]["final"].get<double>(), 9.5);
  EXPECT_DOUBLE_EQ(s["energy"]["max_increase"].get<double>(), 2.0);
}

TEST(RunRecord, EnergyThatNeverRisesHasNoIncrease) {
  // Falls, recovers part of the way, never passes the start: SPEC says 0.
  ScriptedEngine engine({{10, 0, 2, false}, {8, 0, 2, false}, {9.9, 0, 2, false}, {7, 0, 2, false}});
  const RunRecord r = recordRun(engine, 3, 0.5, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(r.maxEnergyIncrease, 0.0);
}

// The time to rest is the end of the last step that ended with a body moving, once the
// run ends at rest: a body that stops, moves again and stops counts from its last stop.
TEST(RunRecord, TimeToRestIsTheEndOfTheLastStepThatEndedMoving) {
  auto run = [](const std::vector<bool>& rest) {
    std::vector<ScriptedEngine::State> script;
    for (bool r : rest) script.push_back({10, 0, 1, true, r});
    ScriptedEngine engine(script);
    return recordRun(engine, static_cast<long>(rest.size()) - 1, 0.5, Eigen::Vector3d::UnitZ());
  };
  const RunRecord stops = run({false, false, true, false, true, true});
  ASSERT_TRUE(stops.timeToRest);
  EXPECT_DOUBLE_EQ(*stops.timeToRest, 1.5);  // step 3 ended moving
  EXPECT_DOUBLE_EQ(summaryToJson("scripted", stops)["time_to_rest"].get<double>(), 1.5);

  const RunRecord moving = run({false, true, true, false});
  EXPECT_FALSE(moving.timeToRest);
  EXPECT_TRUE(summaryToJson("scripted", moving)["time_to_rest"].is_null());

  const RunRecord still = run({true, true, true});
  ASSERT_TRUE(still.timeToRest);
  EXPECT_EQ(*still.timeToRest, 0.0);
}

TEST(RunRecord, SummaryFiguresOfAHandWorkedRun) {
  // Four steps of 0.25 s: first contact in step 2, overlaps 0, 3 mm, 1 mm, 0; the box
  // rises again to 1.5 m after touching at 1 m, and moves 0.25 m along x per step.
  ScriptedEngine engine({{20, 0, 2.0, false},
                         {15, 0, 1.5, false},
                         {10, 0.003, 1.0, true},
                         {12, 0.001, 1.5, true},
                         {11, 0, 1.25, true}});
  const RunRecord r = recordRun(engine, 4, 0.25, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(r.steps, 4);
  EXPECT_DOUBLE_EQ(r.simTime, 1.0);
  ASSERT_TRUE(r.firstContactTime);
  EXPECT_DOUBLE_EQ(*r.firstContactTime, 0.5);
  EXPECT_DOUBLE_EQ(r.maxPenetration, 0.003);
  EXPECT_EQ(r.maxEnergyIncrease, 0.0);  // 12 J after the 10 J low is still below the initial 20 J
  ASSERT_EQ(r.apexAfterFirstContact.size(), 1u);
  EXPECT_DOUBLE_EQ(r.apexAfterFirstContact[0], 1.5);  // highest after the first contact, not the 2 m start
  EXPECT_DOUBLE_EQ(r.drift(0), 1.0);                  // 4 steps of 0.25 m across `up`
  EXPECT_DOUBLE_EQ(r.heightChange(0), -0.75);

  const nlohmann::ordered_json s = summaryToJson("scripted", r);
  EXPECT_EQ(s["scene"], "scripted");
  EXPECT_EQ(s["steps"].get<long>(), 4);
  EXPECT_DOUBLE_EQ(s["sim_time"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(s["first_contact_time"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(s["max_penetration"].get<double>(), 0.003);
  ASSERT_EQ(s["bodies"].size(), 1u);
  EXPECT_EQ(s["bodies"][0]["name"], "box");
  EXPECT_DOUBLE_EQ(s["bodies"][0]["position"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(s["bodies"][0]["position"][2].get<double>(), 1.25);
}

TEST(RunRecord, NoContactGivesANullFirstContactTime) {
  ScriptedEngine engine({{5, 0, 3, false}, {5, 0, 2, false}});
  const RunRecord r = recordRun(engine, 1, 0.1, Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(r.firstContactTime);
  EXPECT_TRUE(std::isnan(r.apexAfterFirstContact[0]));
  EXPECT_TRUE(summaryToJson("scripted", r)["first_contact_time"].is_null());
}

}  // namespace
}  // namespace polysim::sim
