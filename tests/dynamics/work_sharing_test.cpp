// forEachPiece() calls every piece once, on one thread or two, and returns once all are
// done.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "dynamics/work_sharing.h"

namespace polysim::dynamics::solver {
namespace {

std::vector<int> callsPerPiece(int count, bool shared) {
  std::vector<std::atomic<int>> calls(count);
  forEachPiece(count, shared, [&](int i) {
    if (i % 7 == 0) std::this_thread::sleep_for(std::chrono::microseconds(50));  // pieces of uneven length
    ++calls[i];
  });
  std::vector<int> counted;
  for (const std::atomic<int>& c : calls) counted.push_back(c.load());
  return counted;
}

TEST(WorkSharing, EveryPieceIsDoneOnceSharedOrNot) {
  for (bool shared : {false, true})
    for (int count : {0, 1, 2, 3, 64, 1000}) {
      const std::vector<int> calls = callsPerPiece(count, shared);
      ASSERT_EQ(static_cast<int>(calls.size()), count);
      for (int i = 0; i < count; ++i) EXPECT_EQ(calls[i], 1) << "piece " << i << " of " << count << (shared ? ", shared" : "");
    }
}

TEST(WorkSharing, UnsharedPiecesRunOnTheCallingThreadInOrder) {
  std::vector<int> order;
  const std::thread::id caller = std::this_thread::get_id();
  forEachPiece(5, false, [&](int i) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace polysim::dynamics::solver
