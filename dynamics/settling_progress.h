#pragma once
// Whether a settling group's sweeps still gain on its error (kSettlingStallWindow,
// settings.h). Internal to the solver (contact_sweeps.cpp).

#include <algorithm>
#include <limits>

#include "dynamics/settings.h"

namespace polysim::dynamics::solver {

/// Watches the largest impulse change of each sweep (m/s, as ContactSweeps measures it)
/// of a group swept past kMaxSolverIterations. Symmetric sweeps alternate in how much they
/// change, so the smallest change so far is watched, not the last.
class SettlingProgress {
 public:
  /// After each sweep: its largest impulse change (m/s).
  void note(double largestChange) { smallest_ = std::min(smallest_, largestChange); }

  /// Before the sweep after `done` sweeps: true when `done` ends a window of
  /// kSettlingStallWindow sweeps counted from kMaxSolverIterations and the smallest change
  /// is not below (1 - kSettlingLeastGain) times what it was when the window began. The
  /// window at kMaxSolverIterations itself only begins one.
  bool stalled(int done) {
    if (done < kMaxSolverIterations || (done - kMaxSolverIterations) % kSettlingStallWindow != 0) return false;
    const bool stalls = smallest_ > (1.0 - kSettlingLeastGain) * smallestAtWindow_;
    smallestAtWindow_ = smallest_;
    return stalls;
  }

 private:
  double smallest_ = std::numeric_limits<double>::infinity();
  double smallestAtWindow_ = std::numeric_limits<double>::infinity();
};

}  // namespace polysim::dynamics::solver
