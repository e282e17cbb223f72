#include "collision/separation_memo.h"

#include <cstdint>

#include "collision/convex_separation.h"

namespace polysim::collision {

void SeparationMemo::enable(bool on) {
  slots_.assign(on ? kSlots : 0, Entry{});
  hits_ = 0;
}

namespace {

// How far any point of the mesh moves (m) from pose `before` (the top rows of X_WO) to
// pose `now`: at most the move of its bounds' centre plus the rotation's change (its
// Frobenius norm, above the spectral) times the bounds' half diagonal.
double pointMotionBound(const PolygonMesh& mesh, const Eigen::Matrix<double, 3, 4>& before,
                        const Eigen::Matrix<double, 3, 4>& now) {
  const Eigen::Matrix3d turn = now.leftCols<3>() - before.leftCols<3>();
  const Eigen::Vector3d centre = mesh.bounds().center();
  const double centreMove = (turn * centre + now.col(3) - before.col(3)).norm();
  return centreMove + turn.norm() * 0.5 * mesh.bounds().diagonal().norm();
}

std::uint64_t keyOf(const ObjNode& a, const ObjNode& b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a.id)) << 32) | static_cast<std::uint32_t>(b.id);
}

}  // namespace

SeparationMemo::Entry& SeparationMemo::slotOf(const ObjNode& a, const ObjNode& b) {
  return slots_[((keyOf(a, b) * 0x9E3779B97F4A7C15ull) >> 40) % kSlots];  // Fibonacci hashing spreads neighbouring ids
}

const SeparationMemo::Entry* SeparationMemo::entryOf(const ObjNode& a, const ObjNode& b) const {
  if (slots_.empty() || a.id < 0 || b.id < 0) return nullptr;
  const Entry& e = slots_[((keyOf(a, b) * 0x9E3779B97F4A7C15ull) >> 40) % kSlots];
  if (e.a != a.id || e.b != b.id || e.meshA != a.mesh.get() || e.meshB != b.mesh.get()) return nullptr;
  return &e;
}

std::optional<double> SeparationMemo::lowerBound(const ObjNode& a, const ObjNode& b) const {
  const Entry* e = entryOf(a, b);
  if (!e || !e->separation) return std::nullopt;
  const double moved = pointMotionBound(*a.mesh, e->poseA, a.X_WO.matrix().topRows<3>()) +
                       pointMotionBound(*b.mesh, e->poseB, b.X_WO.matrix().topRows<3>());
  return *e->separation - moved;
}

std::optional<double> SeparationMemo::measure(const ObjNode& a, const ObjNode& b) {
  if (slots_.empty() || a.id < 0 || b.id < 0) return convexSeparation(a, b);
  Entry& e = slotOf(a, b);
  const auto poseA = a.X_WO.matrix().topRows<3>(), poseB = b.X_WO.matrix().topRows<3>();
  if (e.a == a.id && e.b == b.id && e.meshA == a.mesh.get() && e.meshB == b.mesh.get() && e.poseA == poseA &&
      e.poseB == poseB) {
    ++hits_;
    return e.separation;
  }
  e = {a.id, b.id, a.mesh.get(), b.mesh.get(), poseA, poseB, convexSeparation(a, b)};
  return e.separation;
}

}  // namespace polysim::collision
