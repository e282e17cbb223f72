// test4Intersection() beside ODE's dCollide on the same geometry and the same question
// (issue 2): an icosphere pair, separate or interpenetrating; a box on a triangulated
// floor, full contact set; a box resting on a box; and the voxel-grid build. Run:
//   build/tests/bench/intersection_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <ode/ode.h>

#include <memory>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "sim/ode_geometry.h"
#include "tests/poses.h"

namespace polysim::bench {
namespace {

using V3 = Eigen::Vector3d;
using collision::ObjectDatabase;
using collision::PolygonMesh;
using test::pose;

// Sphere B turned so that one of its vertices faces sphere A along the centre line.
struct SpherePair {
  collision::MeshData mesh;
  Eigen::Isometry3d X_A, X_B;
  SpherePair(int level, double distance) : mesh(collision::makeIcosphere(1.0, level)) {
    const V3 axis = V3(1, 1, 1).normalized();
    const V3 vertex = mesh.vertices[0].normalized();
    X_A = pose(V3::Zero());
    X_B = pose(distance * axis, Eigen::Quaterniond::FromTwoVectors(vertex, -axis).toRotationMatrix());
  }
};

// Arguments: icosphere level, centre distance in hundredths, voxel halvings (-1: auto).
void BM_Polysim_Icospheres(benchmark::State& state) {
  const SpherePair pair(static_cast<int>(state.range(0)), state.range(1) / 100.0);
  ObjectDatabase db;
  auto mesh = std::make_shared<PolygonMesh>(pair.mesh);
  db.add("A", mesh, pair.X_A, false, static_cast<int>(state.range(2)));
  db.add("B", mesh, pair.X_B, false, static_cast<int>(state.range(2)));
  collision::IntersectionWorkspace ws;
  collision::IntersectionOptions verdictOnly;
  verdictOnly.contacts = false;
  verdictOnly.stopAtInterpenetration = true;
  collision::IntersectionResult r;
  for (auto _ : state) {
    r = collision::test4Intersection(db, ws, verdictOnly);
    benchmark::DoNotOptimize(r);
  }
  state.counters["triangles"] = mesh->faceCount();
  state.counters["M"] = db.objects[0].grid->halvings();
  state.counters["interpenetrating"] = r.status == collision::Status::Interpenetrating;
  state.counters["polygon_pairs"] = static_cast<double>(r.polygonPairsTested);
}

void BM_Ode_Icospheres(benchmark::State& state) {
  const SpherePair pair(static_cast<int>(state.range(0)), state.range(1) / 100.0);
  const sim::OdeGeom a = sim::OdeGeom::triMesh(pair.mesh), b = sim::OdeGeom::triMesh(pair.mesh);
  sim::setPose(a.geom(), pair.X_A);
  sim::setPose(b.geom(), pair.X_B);
  dContactGeom contact[1];
  int n = 0;
  for (auto _ : state) {
    n = dCollide(a.geom(), b.geom(), 1, contact, sizeof(dContactGeom));
    benchmark::DoNotOptimize(n);
  }
  state.counters["triangles"] = static_cast<double>(pair.mesh.faces.size());
  state.counters["interpenetrating"] = n > 0;
}

void icosphereArgs(benchmark::internal::Benchmark* b, bool withM) {
  for (int distance : {210, 190})
    for (int level = 0; level <= 5; ++level) b->Args({level, distance, -1});
  if (withM)
    for (int distance : {210, 190})
      for (int m : {6, 8, 9, 10, 12, 14, 16, 18}) b->Args({5, distance, m});
}
BENCHMARK(BM_Polysim_Icospheres)->Apply([](auto* b) { icosphereArgs(b, true); })->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ode_Icospheres)->Apply([](auto* b) { icosphereArgs(b, false); })->Unit(benchmark::kMicrosecond);

// A unit box resting on a 10 x 10 floor of 2 k^2 triangles, half a tolerance deep so that
// ODE (which reports touching only when penetrating) sees the contact too.
constexpr double kSink = 0.5 * collision::kDefaultContactTolerance;

void BM_Polysim_BoxOnFloor(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  ObjectDatabase db;
  db.add("floor", std::make_shared<PolygonMesh>(collision::makeTriangulatedFloor(10, 10, k)), pose(V3::Zero()), true,
         static_cast<int>(state.range(1)));
  db.add("box", std::make_shared<PolygonMesh>(collision::makeBox(V3(1, 1, 1))), pose(V3(0.05, 0.05, 0.5 - kSink)), false);
  collision::IntersectionWorkspace ws;
  collision::IntersectionResult r;
  for (auto _ : state) {
    r = collision::test4Intersection(db, ws);
    benchmark::DoNotOptimize(r);
  }
  state.counters["triangles"] = 2.0 * k * k;
  state.counters["M"] = db.objects[0].grid->halvings();
  state.counters["contacts"] = r.pairs.empty() ? 0.0 : static_cast<double>(r.pairs[0].contacts.size());
  state.counters["polygon_pairs"] = static_cast<double>(r.polygonPairsTested);
}

void BM_Ode_BoxOnFloor(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const sim::OdeGeom floor = sim::OdeGeom::triMesh(collision::makeTriangulatedFloor(10, 10, k));
  const sim::OdeGeom box = sim::OdeGeom::box(V3(1, 1, 1));
  sim::setPose(box.geom(), pose(V3(0.05, 0.05, 0.5 - kSink)));
  std::vector<dContactGeom> contacts(1000);
  int n = 0;
  for (auto _ : state) {
    n = dCollide(box.geom(), floor.geom(), 1000, contacts.data(), sizeof(dContactGeom));
    benchmark::DoNotOptimize(n);
  }
  state.counters["triangles"] = 2.0 * k * k;
  state.counters["contacts"] = n;
}

void floorArgs(benchmark::internal::Benchmark* b, bool withM) {
  for (int k : {10, 25, 50, 100}) b->Args({k, -1});
  if (withM)
    for (int m : {6, 8, 9, 10, 12, 14, 16}) b->Args({100, m});
}
BENCHMARK(BM_Polysim_BoxOnFloor)->Apply([](auto* b) { floorArgs(b, true); })->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ode_BoxOnFloor)->Apply([](auto* b) { floorArgs(b, false); })->Unit(benchmark::kMicrosecond);

// A unit box resting on another, as a pile's boxes rest: turned about the vertical (a
// face on a face, an area), tipped about x (an edge on a face, a line), or tipped about
// x and y (a vertex on a face, a point); its lowest point half a tolerance into the one
// below. What one pair's full contact set costs each engine: the unit a busy pile's
// collision work is made of. No contact reuse or kept separation (the workspace has them off).
struct RestingBox {
  Eigen::Isometry3d below, above;
  collision::ContactType contact;  // what polysim must report for it
  explicit RestingBox(int kind) : below(pose(V3(0, 0, -0.5))) {
    const Eigen::Matrix3d R = kind == 0   ? test::rot(0.3, V3::UnitZ())
                              : kind == 1 ? test::rot(0.3, V3::UnitX())
                                          : test::rot(0.3, V3::UnitX()) * test::rot(0.2, V3::UnitY());
    const double halfHeight = 0.5 * R.row(2).cwiseAbs().sum();  // the box's lowest point below its centre
    above = pose(V3(0.1, 0.05, halfHeight - kSink), R);
    contact = kind == 0 ? collision::ContactType::Area : kind == 1 ? collision::ContactType::Line : collision::ContactType::Point;
  }
};

void BM_Polysim_BoxOnBox(benchmark::State& state) {
  const RestingBox boxes(static_cast<int>(state.range(0)));
  ObjectDatabase db;
  db.add("below", std::make_shared<PolygonMesh>(collision::makeBox(V3(1, 1, 1))), boxes.below, false);
  db.add("above", std::make_shared<PolygonMesh>(collision::makeBox(V3(1, 1, 1))), boxes.above, false);
  collision::IntersectionWorkspace ws;
  collision::IntersectionResult r;
  for (auto _ : state) {
    r = collision::test4Intersection(db, ws);
    benchmark::DoNotOptimize(r);
  }
  if (r.pairs.size() != 1 || r.pairs[0].status != collision::Status::Contact || r.pairs[0].contacts.size() != 1 ||
      r.pairs[0].contacts[0].type != boxes.contact)
    state.SkipWithError("not the one contact the pose is made for");
  state.counters["contacts"] = r.pairs.empty() ? 0.0 : static_cast<double>(r.pairs[0].contacts.size());
  state.counters["polygon_pairs"] = static_cast<double>(r.polygonPairsTested);
}

void BM_Ode_BoxOnBox(benchmark::State& state) {
  const sim::OdeGeom below = sim::OdeGeom::box(V3(1, 1, 1));
  const sim::OdeGeom above = sim::OdeGeom::box(V3(1, 1, 1));
  const RestingBox boxes(static_cast<int>(state.range(0)));
  sim::setPose(below.geom(), boxes.below);
  sim::setPose(above.geom(), boxes.above);
  std::vector<dContactGeom> contacts(16);
  int n = 0;
  for (auto _ : state) {
    n = dCollide(above.geom(), below.geom(), 16, contacts.data(), sizeof(dContactGeom));
    benchmark::DoNotOptimize(n);
  }
  if (n == 0) state.SkipWithError("the boxes do not touch");
  state.counters["contacts"] = n;
}

// 0: face on face, 1: edge on face, 2: vertex on face.
BENCHMARK(BM_Polysim_BoxOnBox)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ode_BoxOnBox)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// Building the voxel grid of a 20480-triangle icosphere (target: under 2 ms).
void BM_VoxelGridBuild(benchmark::State& state) {
  const PolygonMesh mesh(collision::makeIcosphere(1.0, 5));
  const int m = state.range(0) < 0 ? collision::VoxelGrid::chooseHalvings(mesh) : static_cast<int>(state.range(0));
  for (auto _ : state) {
    collision::VoxelGrid grid(mesh, m, collision::kDefaultContactTolerance);
    benchmark::DoNotOptimize(grid);
  }
  state.counters["M"] = m;
  state.counters["triangles"] = mesh.faceCount();
}
BENCHMARK(BM_VoxelGridBuild)->Arg(-1)->Arg(8)->Arg(12)->Arg(16)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace polysim::bench
