#pragma once
// The separating axis test's last measure of each pair, kept with the poses it was made
// at. One state is often measured more than once: collisionDetect() gathers every pair's
// contacts at the time it found, and the step loop's speculative test follows at the
// same poses; that time is the next search's start, where the pairs that can
// interpenetrate are told apart by the same measure. In the first second of a landing
// pile of 1000 boxes, 35% of 800,000 measures were of poses measured just before.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "collision/object.h"

namespace polysim::collision {

class SeparationMemo {
 public:
  /// Off until enabled, as contact reuse: a pair is known again by its objects' ids
  /// (ObjNode::id) and meshes, which only one database's owner can vouch for.
  void enable(bool on = true);

  /// convexSeparation(a, b), bit for bit: measured, or the value kept for the same
  /// objects, meshes and poses (compared exactly, so nothing is approximated).
  std::optional<double> measure(const ObjNode& a, const ObjNode& b);

  /// A lower bound (m) on the signed distance of a and b at their current poses (their
  /// distance apart; overlapping, minus their penetration depth), from the measure kept
  /// for the pair at whatever poses it was made: that measure, less how far any point of
  /// either has moved since. The measure never exceeds the signed distance (apart, the
  /// widest gap along the axes is at most the distance; overlapping, it is minus the
  /// depth), and the signed distance changes by no more than the points move. Empty when
  /// nothing is kept for the pair or it was not measured by axes. Lets a caller that only
  /// needs the pair far enough apart skip measuring it: in a landing pile most pairs an
  /// event's search looks at are a few millimetres apart or more, and their bodies have
  /// moved a fraction of that since the last event measured them.
  std::optional<double> lowerBound(const ObjNode& a, const ObjNode& b) const;

  /// How many measures were answered from the memo since it was enabled.
  long hits() const { return hits_; }

 private:
  struct Entry {
    int a = -1, b = -1;
    const PolygonMesh* meshA = nullptr;
    const PolygonMesh* meshB = nullptr;
    Eigen::Matrix<double, 3, 4> poseA, poseB;  // the rows of X_WO that are not (0 0 0 1)
    std::optional<double> separation;
  };
  // Direct-mapped by the pair's ids: a pair's newer measure replaces whatever held its
  // slot, so memory stays fixed (kSlots entries) however many pairs a scene has.
  static constexpr size_t kSlots = 16384;
  const Entry* entryOf(const ObjNode& a, const ObjNode& b) const;
  Entry& slotOf(const ObjNode& a, const ObjNode& b);
  std::vector<Entry> slots_;
  long hits_ = 0;
};

}  // namespace polysim::collision
