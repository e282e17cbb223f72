// A settling group's sweeps stop once they stall (kSettlingStallWindow): a change that
// repeats, or shrinks by less than kSettlingLeastGain over a window, stops them; one that
// still shrinks, however it alternates from sweep to sweep, does not.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "dynamics/settings.h"
#include "dynamics/settling_progress.h"

namespace polysim::dynamics::solver {
namespace {

// Sweeps a group as sweepGroup does, each sweep's largest change given by `change` (of
// the sweep's number, from 1), up to kSettlingSolverSweeps; returns the sweeps made
// before it stalled, or the limit.
int sweepsUntilStalled(const std::function<double(int)>& change) {
  SettlingProgress progress;
  for (int done = 0; done < kSettlingSolverSweeps; ++done) {
    if (done >= kMaxSolverIterations && progress.stalled(done)) return done;
    progress.note(change(done + 1));
  }
  return kSettlingSolverSweeps;
}

const int kFirstWindowEnd = kMaxSolverIterations + kSettlingStallWindow;

TEST(SettlingProgress, ARepeatedChangeStallsAtTheFirstWindowsEnd) {
  EXPECT_EQ(sweepsUntilStalled([](int) { return 1.2e-8; }), kFirstWindowEnd);
}

TEST(SettlingProgress, AChangeShrinkingByAPercentASweepNeverStalls) {
  EXPECT_EQ(sweepsUntilStalled([](int k) { return 1e-3 * std::pow(0.99, k); }), kSettlingSolverSweeps);
}

// 0.05% a sweep is 5% a window of 100: less than kSettlingLeastGain.
TEST(SettlingProgress, AChangeShrinkingTooSlowlyStalls) {
  static_assert(kSettlingStallWindow == 100 && kSettlingLeastGain > 0.05, "the rate below assumes these");
  EXPECT_EQ(sweepsUntilStalled([](int k) { return 1e-3 * std::pow(0.9995, k); }), kFirstWindowEnd);
}

// Shrinks until sweep 400, then repeats: the window that ends at 400 gained, the next did not.
TEST(SettlingProgress, AChangeThatStopsShrinkingStallsOneWindowLater) {
  const int flatFrom = kMaxSolverIterations + 3 * kSettlingStallWindow;
  EXPECT_EQ(sweepsUntilStalled([flatFrom](int k) { return 1e-3 * std::pow(0.99, std::min(k, flatFrom)); }),
            flatFrom + kSettlingStallWindow);
}

// Symmetric sweeps: the forward ones (odd) change ever less, the backward ones as much
// each time, and every window ends on a backward one. The smallest change still
// shrinks, so the sweeps go on.
TEST(SettlingProgress, AlternatingSweepsAreJudgedByTheSmallestChange) {
  static_assert(kMaxSolverIterations % 2 == 0 && kSettlingStallWindow % 2 == 0, "windows end on backward sweeps");
  EXPECT_EQ(sweepsUntilStalled([](int k) { return k % 2 ? 1e-3 * std::pow(0.99, k) : 1e-2; }), kSettlingSolverSweeps);
}

TEST(SettlingProgress, NothingStallsBeforeTheSettlingSweepsBegin) {
  SettlingProgress progress;
  for (int done = 0; done < kMaxSolverIterations; ++done) {
    EXPECT_FALSE(progress.stalled(done));
    progress.note(1.0);
  }
}

}  // namespace
}  // namespace polysim::dynamics::solver
