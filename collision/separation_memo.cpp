#include "collision/separation_memo.h"

#include <cstdint>

#include "collision/convex_separation.h"

namespace polysim::collision {

void SeparationMemo::enable(bool on) {
  slots_.assign(on ? kSlots : 0, Entry{});
  hits_ = 0;
}

std::optional<double> SeparationMemo::measure(const ObjNode& a, const ObjNode& b) {
  if (slots_.empty() || a.id < 0 || b.id < 0) return convexSeparation(a, b);
  const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a.id)) << 32) | static_cast<std::uint32_t>(b.id);
  Entry& e = slots_[((key * 0x9E3779B97F4A7C15ull) >> 40) % kSlots];  // Fibonacci hashing spreads neighbouring ids
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
