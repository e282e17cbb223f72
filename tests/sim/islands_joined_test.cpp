// Islands joined (World::stepIslands, joinIslandsReached): an event's impulse can turn a
// body towards another island's. The islands take their events in time order, so the
// other island's clock stands at or before the event; it is moved to the event and the
// two go on as one, so the pair meets at its own event.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sim/scene.h"
#include "sim/world.h"
#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

constexpr double kEps = 1e-4;  // the scene's contact tolerance (m)

// Three unit boxes in a row along x with no gravity, no friction and restitution 1
// (a Newton's cradle in space): A flies at `speed` m/s into B, `gapAB` m ahead of it;
// B, struck, flies into C, `gapBC` m further, which drifts away at `drift` m/s (slower)
// past D, resting beside it within the band. A's path over a step of `dt` stops short of
// C, so at the step's start A and B are one island and C and D another; B's impact sends
// it into C's bounds. The islands are the same size, so they step in the order of their
// first bodies: `cFirst` lists C and D first, so that their island steps before A and
// B's and is taken back when they reach it.
struct Cradle {
  double speed, drift, gapAB, gapBC, dt;
  bool cFirst;
};

std::string cradleScene(const Cradle& s) {
  const double xB = 1.0 + s.gapAB, xC = xB + 1.0 + s.gapBC;
  const auto box = [](const std::string& name, double x, double v) {
    std::ostringstream text;
    text << std::setprecision(17) << R"({"name": ")" << name
         << R"(", "mass": 1, "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)" << x
         << R"(, 0, 0], "velocity": [)" << v << ", 0, 0]}";
    return text.str();
  };
  const std::string a = box("A", 0.0, s.speed), b = box("B", xB, 0.0), c = box("C", xC, s.drift);
  const std::string d = R"({"name": "D", "mass": 1, "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)" +
                        std::to_string(xC) + ", " + std::to_string(1.0 + 0.5 * kEps) + ", 0]}";
  const std::string path = ::polysim::test::tempPath("islands_joined_cradle.json");
  std::ofstream(path) << std::setprecision(17) << R"({"dt": )" << s.dt << R"(, "duration": 1, "gravity": [0, 0, 0],)"
                      << R"( "contact": {"tolerance": )" << kEps << R"(, "restitution": 1, "friction": 0},)"
                      << R"( "sleep": {"enabled": false}, "bodies": [)"
                      << (s.cFirst ? c + ", " + d + ", " + a + ", " + b : a + ", " + b + ", " + c + ", " + d) << "]}\n";
  return path;
}

// Elastic impacts of equal masses swap velocities: A stops at B's start, B takes A's
// speed until it meets C and C's drift after, C flies on at A's speed. Each impact is at
// just contact (within the band), so each body ends within a few eps of where it would.
// D, frictionless, is left where it was (to round-off).
void expectCradleStep(const Cradle& s) {
  World w(loadScene(cradleScene(s)));
  const int a = test::bodyIndex(w, "A"), b = test::bodyIndex(w, "B"), c = test::bodyIndex(w, "C");
  const int d = test::bodyIndex(w, "D");
  const Eigen::Vector3d dAt = w.bodies()[d].position;
  const double xB = 1.0 + s.gapAB, xC = xB + 1.0 + s.gapBC;
  const double strikesB = s.gapAB / s.speed, strikesC = (s.gapAB + s.gapBC) / (s.speed - s.drift);
  const StepReport& r = w.step(s.dt);
  EXPECT_EQ(r.islandsJoined, 1);
  EXPECT_EQ(r.events.size(), 2u);
  ASSERT_EQ(r.islands.size(), 1u);  // the two islands ended as one
  EXPECT_EQ(r.islands.front().bodies, 4);
  EXPECT_EQ(r.islands.front().events, 2);
  const auto expectAt = [&](double t, double bAt, double cAt) {
    EXPECT_NEAR(w.bodies()[a].position.x(), s.gapAB, 2 * kEps);
    EXPECT_NEAR(w.bodies()[b].position.x(), bAt, 3 * kEps);
    EXPECT_NEAR(w.bodies()[c].position.x(), cAt, 4 * kEps);
    EXPECT_NEAR(w.bodies()[a].velocity.x(), 0.0, 1e-9 * s.speed);
    EXPECT_NEAR(w.bodies()[b].velocity.x(), s.drift, 1e-9 * s.speed);
    EXPECT_NEAR(w.bodies()[c].velocity.x(), s.speed, 1e-9 * s.speed);
    EXPECT_LT((w.bodies()[d].position - dAt).norm(), 1e-9);
    EXPECT_LT(w.bodies()[d].velocity.norm(), 1e-9 * s.speed);
    const double energy = 0.5 * (s.speed * s.speed + s.drift * s.drift);
    EXPECT_NEAR(w.energy(), energy, 1e-9 * energy);
    EXPECT_LE(r.penetration, kEps);
    test::FreshVerdict fresh(w.scene());
    EXPECT_FALSE(fresh.interpenetrating(w)) << "at " << t << " s";
  };
  const double bEnd = xB + s.speed * (strikesC - strikesB) + s.drift * (s.dt - strikesC);
  const double cEnd = xC + s.drift * strikesC + s.speed * (s.dt - strikesC);
  expectAt(s.dt, bEnd, cEnd);
  w.step(s.dt);  // each flies on alone
  expectAt(2 * s.dt, bEnd + s.drift * s.dt, cEnd + s.speed * s.dt);
}

TEST(IslandsJoined, AStruckBodyMeetsABodyOfAnotherIslandAtItsOwnEvent) {
  for (bool cFirst : {false, true}) {
    SCOPED_TRACE(cFirst ? "C's island steps first" : "C's island steps last");
    expectCradleStep({10.0, 0.0, 0.1, 0.5, 0.1, cFirst});
    expectCradleStep({10.0, 2.0, 0.1, 0.5, 0.1, cFirst});  // C moves before it joins
  }
}

// Seeded speeds, drifts, gaps and steps: C is always out of A's and B's reach at the
// step's start (swept bounds grow by a body's motion every way, so B and C are further
// apart than C drifts in a step) and always struck within it.
TEST(IslandsJoined, SeededCradles) {
  constexpr double margin = 0.01;  // m, between bounds that must not overlap
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 12; ++k) {
    Cradle s{2.0 + 13.0 * unit(rng), 0.0, 0.0, 0.0, 0.05 + 0.1 * unit(rng), k % 2 == 1};
    s.drift = 0.2 * unit(rng) * s.speed;
    const double reach = s.speed * s.dt, drifted = s.drift * s.dt;
    // gapAB + gapBC inside (reach + drifted - 1, (speed - drift) dt): A short of C, C struck within the step.
    const double least = std::max(reach + drifted - 1.0, drifted + 2 * margin) + margin;
    const double total = least + (0.1 + 0.8 * unit(rng)) * ((s.speed - s.drift) * s.dt - least);
    s.gapBC = drifted + margin + unit(rng) * (total - drifted - 2 * margin);
    s.gapAB = total - s.gapBC;
    SCOPED_TRACE("speed " + std::to_string(s.speed) + " drift " + std::to_string(s.drift) + " dt " +
                 std::to_string(s.dt) + " gaps " + std::to_string(s.gapAB) + ", " + std::to_string(s.gapBC));
    expectCradleStep(s);
  }
}

// A row of unit boxes along x, no gravity, no friction, restitution 1: equal masses
// colliding elastically swap velocities, so with each box's width taken out of its
// position (box k at x - k) the boxes move as free points passing through each other, and
// box k is always the k-th of them from the left. Seeded gaps and speeds (distinct by at
// least 1 m/s: every impact bounces, kBounceThreshold), and no two crossings within a
// millisecond (impacts one at a time, as the analytic answer has them). With steps of 0.1 s
// and speeds up to 10 m/s the row splits into several islands, and struck boxes outgrow
// them: every step must match the free points within a few eps a collision.
struct Row {
  std::vector<double> x, v;  // m, m/s
};

Row seededRow(std::mt19937_64& rng, int boxes, double duration) {
  std::uniform_real_distribution<double> gap(0.05, 1.2), speed(-10.0, 10.0);
  for (;;) {
    Row row;
    for (int k = 0; k < boxes; ++k) {
      row.x.push_back(k == 0 ? 0.0 : row.x.back() + 1.0 + gap(rng));
      row.v.push_back(speed(rng));
    }
    bool apart = true;  // speeds distinct, crossings of the free points apart in time
    std::vector<double> crossings;
    for (int i = 0; i < boxes; ++i)
      for (int j = i + 1; j < boxes; ++j) {
        const double dv = row.v[i] - row.v[j];
        apart = apart && std::abs(dv) >= 1.0;
        const double t = ((row.x[j] - j) - (row.x[i] - i)) / dv;  // free point i meets j
        if (dv > 0 && t <= duration) crossings.push_back(t);
      }
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 1; k < crossings.size(); ++k) apart = apart && crossings[k] - crossings[k - 1] > 1e-3;
    if (apart) return row;
  }
}

std::string rowScene(const Row& row, double dt) {
  std::ostringstream text;
  text << std::setprecision(17) << R"({"dt": )" << dt << R"(, "duration": 1, "gravity": [0, 0, 0],)"
       << R"( "contact": {"tolerance": )" << kEps << R"(, "restitution": 1, "friction": 0},)"
       << R"( "sleep": {"enabled": false}, "bodies": [)";
  for (size_t k = 0; k < row.x.size(); ++k)
    text << (k ? ", " : "") << R"({"name": "box)" << k << R"(", "mass": 1, "shape": {"type": "box", "size": [1, 1, 1]},)"
         << R"( "position": [)" << row.x[k] << R"(, 0, 0], "velocity": [)" << row.v[k] << ", 0, 0]}";
  text << "]}\n";
  const std::string path = ::polysim::test::tempPath("islands_joined_row.json");
  std::ofstream(path) << text.str();
  return path;
}

// Steps the row `steps` times, checking each step against the free points; adds the
// step reports' islands redone to `redone`.
void expectRowMovesAsFreePoints(const Row& row, double dt, int steps, int& redone) {
  const int boxes = static_cast<int>(row.x.size());
  World w(loadScene(rowScene(row, dt)));
  test::FreshVerdict fresh(w.scene());
  double energy = 0.0;
  for (double v : row.v) energy += 0.5 * v * v;
  for (int step = 1; step <= steps; ++step) {
    const StepReport& r = w.step(dt);
    redone += r.islandsJoined;
    const double t = step * dt;
    std::vector<std::pair<double, double>> points;  // free points at t: position, speed
    for (int k = 0; k < boxes; ++k) points.emplace_back(row.x[k] - k + row.v[k] * t, row.v[k]);
    std::sort(points.begin(), points.end());
    for (int k = 0; k < boxes; ++k) {
      const dynamics::RigidBody& b = w.bodies()[k];
      EXPECT_NEAR(b.position.x(), points[k].first + k, 2 * boxes * kEps) << "box" << k << " at " << t << " s";
      EXPECT_NEAR(b.velocity.x(), points[k].second, 1e-6) << "box" << k << " at " << t << " s";
    }
    EXPECT_NEAR(w.energy(), energy, 1e-9 * energy);
    EXPECT_LE(r.penetration, kEps);
    EXPECT_FALSE(fresh.interpenetrating(w)) << "at " << t << " s";
  }
}

TEST(IslandsJoined, SeededElasticRowsMoveAsFreePointsPassingThrough) {
  std::mt19937_64 rng(11);
  int redone = 0;
  for (int seed = 0; seed < 24; ++seed) {
    SCOPED_TRACE("row " + std::to_string(seed));
    expectRowMovesAsFreePoints(seededRow(rng, 7, 0.4), 0.1, 4, redone);
  }
  EXPECT_GT(redone, 0);  // the rows exercise what they are for
}

// A strikes B at 0.03 s, and B can then reach C, of the other island; but C is struck by
// E at 0.0018 s and in fact strikes B at 0.02 s, before A does. Joined as one island
// from the first event that turns a body towards the other, the row meets each of these
// at its own time.
TEST(IslandsJoined, AnIslandReachingIntoOneWhoseOwnEventComesFirst) {
  int redone = 0;
  expectRowMovesAsFreePoints({{0.0, 1.3, 2.5, 3.52}, {10.0, 0.0, 0.0, -11.0}}, 0.1, 3, redone);
  EXPECT_GE(redone, 1);
}

}  // namespace
}  // namespace polysim::sim
