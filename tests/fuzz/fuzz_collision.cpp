// libFuzzer target: test4Intersection() and collisionDetect() on two meshes drawn from the
// bytes (fuzz_meshes.h) at any poses. Asserted, on every input:
// - nothing is NaN in what the test reports;
// - the verdict is the same with the pair given the other way round;
// - moved apart beyond their reach, they are separate;
// - moving from apart to the drawn pose, collisionDetect() returns a time in [0, 1] whose
//   state does not interpenetrate, tested again by test4Intersection().

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "collision/intersection.h"
#include "collision/time_of_contact.h"
#include "tests/fuzz/fuzz_meshes.h"

namespace {

using namespace polysim::collision;

void require(bool holds, const char* what) {
  if (holds) return;
  std::fprintf(stderr, "invariant broken: %s\n", what);
  std::abort();
}

bool finite(const IntersectionResult& r) {
  for (const PairResult& pair : r.pairs) {
    if (!std::isfinite(pair.depth)) return false;
    for (const Contact& c : pair.contacts) {
      if (!c.normal.allFinite() || !std::isfinite(c.separation)) return false;
      for (const Eigen::Vector3d& p : c.points)
        if (!p.allFinite()) return false;
    }
  }
  return true;
}

double reach(const PolygonMesh& mesh) {
  double r = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices()) r = std::max(r, v.norm());
  return r;
}

// The moving object slides in a straight line from `start` to `end` (no turn).
struct Slide {
  Eigen::Isometry3d start, end;
};
void slide(double t, const void* info, Eigen::Isometry3d& X) {
  const Slide& s = *static_cast<const Slide*>(info);
  X = s.end;
  X.translation() = (1 - t) * s.start.translation() + t * s.end.translation();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider bytes(data, size);
  const std::optional<MeshData> a = polysim::fuzz::anyMesh(bytes), b = polysim::fuzz::anyMesh(bytes);
  if (!a || !b) return 0;
  const auto meshA = std::make_shared<const PolygonMesh>(*a), meshB = std::make_shared<const PolygonMesh>(*b);
  const Eigen::Isometry3d poseA = polysim::fuzz::anyPose(bytes), poseB = polysim::fuzz::anyPose(bytes);

  ObjectDatabase forward, backward;
  forward.add("a", meshA, poseA, false);
  forward.add("b", meshB, poseB, false);
  backward.add("b", meshB, poseB, false);
  backward.add("a", meshA, poseA, false);
  const IntersectionResult there = test4Intersection(forward), swapped = test4Intersection(backward);
  require(finite(there) && finite(swapped), "a NaN or infinity in the reported contacts");
  require(there.status == swapped.status, "the verdict changes with the pair swapped");

  // Apart along a drawn direction, farther than both reaches and the tolerance.
  Eigen::Vector3d away(polysim::fuzz::unitRange(bytes, -1, 1), polysim::fuzz::unitRange(bytes, -1, 1), 1.0);
  away.normalize();
  const double clear = reach(*meshA) + reach(*meshB) + 10 * forward.tolerance;
  Eigen::Isometry3d apart = poseB;
  apart.translation() = poseA.translation() + clear * away;
  forward.objects[1].X_WO = apart;
  require(test4Intersection(forward).status == Status::Separate, "moved apart, still not separate");

  // From apart to the drawn pose: just contact, never a state inside.
  const Slide path{apart, poseB};
  ObjNode& moving = forward.objects[1];
  moving.ctrans = slide;
  moving.info = &path;
  moving.motionBound = (poseB.translation() - apart.translation()).norm();
  forward.setTime(1.0);
  const TocResult toc = collisionDetect(forward);
  require(toc.time >= 0.0 && toc.time <= 1.0, "a time of contact outside [0, 1]");
  require(toc.status != Status::Interpenetrating, "collisionDetect() returned an interpenetrating state");
  const IntersectionResult atContact = test4Intersection(forward);
  require(finite(atContact), "a NaN or infinity at the time of contact");
  require(atContact.status != Status::Interpenetrating, "the state at the returned time interpenetrates");
  return 0;
}
