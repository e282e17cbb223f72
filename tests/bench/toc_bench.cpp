// collisionDetect() per query and its error against the reference, for each method
// (issue 3): a cube falling onto a slab, the same while turning 30 degrees, and an
// icosphere pair approaching along their centre line. Run:
//   build/tests/bench/toc_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "collision/shapes.h"
#include "collision/time_of_contact.h"

namespace polysim::bench {
namespace {

using V3 = Eigen::Vector3d;
using namespace collision;

struct Motion {
  Eigen::Isometry3d start;
  V3 v, w;
};

void movePose(double t, const void* info, Eigen::Isometry3d& X) {
  const Motion& m = *static_cast<const Motion*>(info);
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  if (m.w.norm() > 0) turn = Eigen::AngleAxisd(m.w.norm() * t, m.w.normalized()).toRotationMatrix();
  X.linear() = turn * m.start.linear();
  X.translation() = m.start.translation() + t * m.v;
}

Eigen::Isometry3d at(const V3& p, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

// A scenario: one static object and one moving, and the reference time of contact.
struct Scenario {
  ObjectDatabase db;
  Motion motion;
  double reference = 0.0;
};

void addMover(Scenario& s, std::shared_ptr<PolygonMesh> mesh) {
  const int id = s.db.add("mover", mesh, s.motion.start, false);
  ObjNode& node = s.db.objects[id];
  node.ctrans = movePose;
  node.info = &s.motion;
  double radius = 0.0;
  for (const V3& p : mesh->vertices()) radius = std::max(radius, p.norm());
  node.motionBound = s.motion.v.norm() + s.motion.w.norm() * radius;
}

// Cube above a 10x10x1 slab whose top is at z = 0; its bottom face from z = 1.5 at t = 0
// to z = -0.5 at t = 1, optionally turning 30 degrees about x.
std::unique_ptr<Scenario> cubeOntoSlab(bool turning) {
  auto s = std::make_unique<Scenario>();
  s->db.add("slab", std::make_shared<PolygonMesh>(makeBox(V3(10, 10, 1))), at(V3(0, 0, -0.5)), true);
  s->motion = {at(V3(0, 0, 2.0)), V3(0, 0, -2.0), turning ? V3(M_PI / 6, 0, 0) : V3::Zero()};
  addMover(*s, std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))));
  s->reference = turning ? 0.678641277913399 : 0.75;
  return s;
}

// Two level-3 icospheres of radius 1; B from 3.0 to 1.5 apart along (1,1,1)/sqrt(3).
std::unique_ptr<Scenario> icospheres() {
  auto s = std::make_unique<Scenario>();
  auto mesh = std::make_shared<PolygonMesh>(makeIcosphere(1.0, 3));
  const V3 axis = V3(1, 1, 1).normalized();
  s->db.add("A", mesh, at(V3::Zero()), true);
  s->motion = {at(3.0 * axis), -1.5 * axis, V3::Zero()};
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
  for (auto _ : state) {
    s.db.setTime(1.0);
    r = collisionDetect(s.db, options);
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(toString(options.method));
  state.counters["time"] = r.time;
  state.counters["error"] = std::abs(r.time - s.reference);
  state.counters["tests"] = r.iterations;
  state.counters["subintervals"] = r.subintervals;
}

void BM_Toc_CubeOntoSlab(benchmark::State& state) { runQueries(state, *cubeOntoSlab(false)); }
void BM_Toc_TurningCubeOntoSlab(benchmark::State& state) { runQueries(state, *cubeOntoSlab(true)); }
void BM_Toc_Icospheres(benchmark::State& state) { runQueries(state, *icospheres()); }

BENCHMARK(BM_Toc_CubeOntoSlab)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Toc_TurningCubeOntoSlab)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Toc_Icospheres)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace polysim::bench

BENCHMARK_MAIN();
