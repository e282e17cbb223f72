// `polysim make` (scene_generators.h): every kind, at several sizes and seeds, is a valid
// scene file that starts without interpenetration, holds what its options say, and comes
// out byte for byte the same for the same options.

#include "sim/scene_generators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "sim/commands.h"
#include "sim/scene.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

// Loads a generated scene through the scene reader (every SPEC.md check) and the
// start-state check (no interpenetration).
Scene loaded(const MakeOptions& options) {
  const std::string path = ::polysim::test::tempPath("polysim_generated_" + options.kind + ".json");
  std::ofstream(path) << makeScene(options).dump(1) << "\n";
  Scene scene = loadScene(path);
  checkInitialState(scene);
  return scene;
}

int dynamicBodies(const Scene& s) {
  int n = 0;
  for (const BodySpec& b : s.bodies) n += !b.isStatic;
  return n;
}

MakeOptions options(const std::string& kind, int count, unsigned long long seed = 1) {
  MakeOptions o;
  o.kind = kind;
  o.count = count;
  o.seed = seed;
  return o;
}

TEST(SceneGenerators, EveryKindIsAValidSceneThatStartsApart) {
  for (const std::string& kind : sceneKinds())
    for (int count : {1, 4, 9})
      for (unsigned long long seed : {1ull, 7ull, 12345ull}) {
        SCOPED_TRACE(kind + " x" + std::to_string(count) + " seed " + std::to_string(seed));
        const Scene s = loaded(options(kind, count, seed));
        EXPECT_EQ(dynamicBodies(s), kind == "pyramid" ? count * (count + 1) / 2 : count);
        EXPECT_NEAR(s.dt, 1.0 / 60, 1e-15);
      }
}

TEST(SceneGenerators, SameOptionsGiveTheSameBytesAndTheSeedChangesThem) {
  for (const std::string& kind : sceneKinds()) {
    MakeOptions o = options(kind, 6, 3);
    if (kind == "pile" || kind == "cups") o.tilt = 0.3;
    EXPECT_EQ(makeScene(o).dump(), makeScene(o).dump()) << kind;
    MakeOptions other = o;
    other.seed = 4;
    const bool random = kind == "pile" || kind == "cups" || kind == "dominoes";
    EXPECT_EQ(makeScene(o).dump() != makeScene(other).dump(), random) << kind;
  }
}

// A tilted pile of 64 boxes: inside the 16 m pen, above the ground, each turned by at most
// the tilt asked for, and not all turned alike.
TEST(SceneGenerators, PileBoxesAreTiltedWithinTheLimitInsideThePen) {
  for (unsigned long long seed : {1ull, 2ull, 99ull}) {
    MakeOptions o = options("pile", 64, seed);
    o.tilt = 0.25;
    const Scene s = loaded(o);
    double largest = 0.0, smallest = 1.0;
    for (const BodySpec& b : s.bodies) {
      if (b.isStatic) continue;
      EXPECT_LT(b.position.head<2>().cwiseAbs().maxCoeff() + 0.7, 8.0) << b.name << " outside the pen";
      EXPECT_GT(b.position.z(), 0.7) << b.name;
      const double angle = 2 * std::acos(std::min(1.0, std::abs(b.orientation.w())));
      largest = std::max(largest, angle);
      smallest = std::min(smallest, angle);
    }
    EXPECT_LE(largest, 0.25 + 1e-12);
    EXPECT_GT(largest - smallest, 0.1);
    int walls = 0;
    for (const BodySpec& b : s.bodies) walls += b.isStatic && b.name.rfind("wall", 0) == 0;
    EXPECT_EQ(walls, 4);
  }
}

TEST(SceneGenerators, StackAndPyramidRestExactlyOnEachOther) {
  const Scene stack = loaded(options("stack", 12));
  for (int k = 0; k < 12; ++k) EXPECT_DOUBLE_EQ(stack.bodies[k + 1].position.z(), 0.5 + k);
  const Scene pyramid = loaded(options("pyramid", 6));
  double top = 0.0;
  for (const BodySpec& b : pyramid.bodies) top = std::max(top, b.position.z());
  EXPECT_DOUBLE_EQ(top, 0.5 + 5);  // six rows
}

TEST(SceneGenerators, BadOptionsAreRejectedNamingTheOption) {
  auto messageFor = [](const MakeOptions& o) {
    try {
      makeScene(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  MakeOptions o = options("heap", 5);
  EXPECT_NE(messageFor(o).find("unknown kind \"heap\""), std::string::npos);
  o = options("stack", 0);
  EXPECT_NE(messageFor(o).find("--count"), std::string::npos);
  o = options("stack", 5);
  o.tilt = 0.1;
  EXPECT_NE(messageFor(o).find("--tilt"), std::string::npos);
  o = options("pile", 5);
  o.tilt = 0.5;
  EXPECT_NE(messageFor(o).find("--tilt"), std::string::npos);
  o = options("cups", 5);
  o.dt = -1.0;
  EXPECT_NE(messageFor(o).find("--dt"), std::string::npos);
}

// `polysim make --out`: the file holds the scene whole; an unwritable path is an error
// naming it, and leaves no partial file behind.
TEST(SceneGenerators, MakeCommandWritesTheFileWholeOrNotAtAll) {
  const MakeOptions o = options("cups", 3, 5);
  const std::string path = ::polysim::test::tempPath("polysim_make_cups.json");
  std::ostringstream unused;
  ASSERT_EQ(makeCommand(o, path, unused), 0);
  std::ifstream in(path);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, makeScene(o).dump(1) + "\n");
  EXPECT_TRUE(unused.str().empty());

  const std::string bad = ::polysim::test::tempPath("no_such_directory/scene.json");
  try {
    makeCommand(o, bad, unused);
    FAIL() << "an unwritable path must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::ifstream(bad + ".partial").good());
}

}  // namespace
}  // namespace polysim::sim
