// collisionDetect() per query and its error against the reference, for each method
// (issue 3): a cube falling onto a slab, the same while turning 30 degrees, and an
// icosphere pair approaching along their centre line. Run:
//   build/tests/bench/toc_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "collision/convex_separation.h"
#include "collision/shapes.h"
#include "collision/time_of_contact.h"
#include "sim/kinematic_motion.h"
#include "tests/poses.h"

namespace polysim::bench {
namespace {

using V3 = Eigen::Vector3d;
using namespace collision;

using sim::KinematicMotion;
using test::pose;

// A scenario: one static object and one moving, and the reference time of contact.
struct Scenario {
  ObjectDatabase db;
  KinematicMotion motion;
  double reference = 0.0;
};

void addMover(Scenario& s, std::shared_ptr<PolygonMesh> mesh) {
  const int id = s.db.add("mover", mesh, s.motion.start, false);
  ObjNode& node = s.db.objects[id];
  node.ctrans = sim::kinematicPose;
  node.info = &s.motion;
  node.motionBound = sim::kinematicMotionBound(s.motion, *mesh);
}

// Cube above a 10x10x1 slab whose top is at z = 0; its bottom face from z = 1.5 at t = 0
// to z = -0.5 at t = 1, optionally turning 30 degrees about x.
std::unique_ptr<Scenario> cubeOntoSlab(bool turning) {
  auto s = std::make_unique<Scenario>();
  s->db.add("slab", std::make_shared<PolygonMesh>(makeBox(V3(10, 10, 1))), pose(V3(0, 0, -0.5)), true);
  s->motion = {pose(V3(0, 0, 2.0)), V3(0, 0, -2.0), turning ? V3(M_PI / 6, 0, 0) : V3::Zero(), 1.0};
  addMover(*s, std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))));
  s->reference = turning ? 0.678641277913399 : 0.75;
  return s;
}

// Two level-3 icospheres of radius 1; B from 3.0 to 1.5 apart along (1,1,1)/sqrt(3).
std::unique_ptr<Scenario> icospheres() {
  auto s = std::make_unique<Scenario>();
  auto mesh = std::make_shared<PolygonMesh>(makeIcosphere(1.0, 3));
  const V3 axis = V3(1, 1, 1).normalized();
  s->db.add("A", mesh, pose(V3::Zero()), true);
  s->motion = {pose(3.0 * axis), -1.5 * axis, V3::Zero(), 1.0};
  addMover(*s, mesh);
  // Reference: the signed-separation root found with a tolerance a thousand times finer.
  ObjectDatabase fine = s->db;
  fine.tolerance = 1e-3 * s->db.tolerance;
  fine.objects[1].info = &s->motion;
  fine.setTime(1.0);
  TocOptions exact;
  exact.method = TocMethod::RegulaFalsi;
  s->reference = collisionDetect(fine, exact).time;
  return s;
}

void runQueries(benchmark::State& state, Scenario& s) {
  TocOptions options;
  options.method = state.range(0) == 0 ? TocMethod::Bisection : TocMethod::RegulaFalsi;
  TocResult r;
  IntersectionWorkspace workspace;
  for (auto _ : state) {
    s.db.setTime(1.0);
    r = collisionDetect(s.db, workspace, options);
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(toString(options.method));
  state.counters["time"] = r.time;
  state.counters["error"] = std::abs(r.time - s.reference);
  state.counters["tests"] = r.iterations;
  state.counters["separations"] = r.separations;
  state.counters["subintervals"] = r.subintervals;
}

void BM_Toc_CubeOntoSlab(benchmark::State& state) { runQueries(state, *cubeOntoSlab(false)); }
void BM_Toc_TurningCubeOntoSlab(benchmark::State& state) { runQueries(state, *cubeOntoSlab(true)); }
void BM_Toc_Icospheres(benchmark::State& state) { runQueries(state, *icospheres()); }

// One signed-separation measure (the root finder's function) of the turning cube and the
// slab, near their contact: the cost of one regula-falsi iteration on convex objects.
void BM_ConvexSeparation_CubeAndSlab(benchmark::State& state) {
  std::unique_ptr<Scenario> s = cubeOntoSlab(true);
  s->db.setTime(0.68);
  for (auto _ : state) benchmark::DoNotOptimize(convexSeparation(s->db.objects[0], s->db.objects[1]));
}

BENCHMARK(BM_ConvexSeparation_CubeAndSlab);

// The test every query ends with: test4Intersection() with contacts at the turning
// cube's time of contact (an edge on the slab: a line contact).
void BM_ContactTest_TurningCubeAtContact(benchmark::State& state) {
  std::unique_ptr<Scenario> s = cubeOntoSlab(true);
  s->db.setTime(s->reference);
  IntersectionWorkspace workspace;
  IntersectionOptions options;
  options.contacts = true;
  IntersectionResult r;
  for (auto _ : state) {
    r = test4Intersection(s->db, workspace, options);
    benchmark::DoNotOptimize(r);
  }
  state.counters["polygonPairs"] = static_cast<double>(r.polygonPairsTested);
  state.counters["contacts"] = r.pairs.empty() ? 0.0 : static_cast<double>(r.pairs[0].contacts.size());
  state.counters["raw"] = static_cast<double>(workspace.raw.size());
}

BENCHMARK(BM_ContactTest_TurningCubeAtContact);

BENCHMARK(BM_Toc_CubeOntoSlab)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Toc_TurningCubeOntoSlab)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Toc_Icospheres)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace polysim::bench
