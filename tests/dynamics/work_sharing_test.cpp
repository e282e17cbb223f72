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

// The helper thread is kept from call to call: each call's pieces are its own, and the
// caller returns only once the helper is done with them, however short they are.
TEST(WorkSharing, TheHelperTakesPiecesAndFinishesThemBeforeTheCallReturns) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: every piece is the caller's";
  const std::thread::id caller = std::this_thread::get_id();
  int helpedCalls = 0;
  for (int call = 0; call < 50; ++call) {
    std::vector<std::atomic<int>> calls(8);
    std::atomic<bool> helped{false};
    forEachPiece(8, true, [&](int i) {
      if (std::this_thread::get_id() != caller) helped = true;
      std::this_thread::sleep_for(std::chrono::microseconds(call % 2 == 0 ? 500 : 0));  // long, then instant pieces
      ++calls[i];
    });
    for (int i = 0; i < 8; ++i) ASSERT_EQ(calls[i].load(), 1) << "piece " << i << " of call " << call;
    helpedCalls += helped;
  }
  // 25 calls of 4 ms of pieces each: the helper has the time to wake for some, even on a
  // loaded machine.
  EXPECT_GT(helpedCalls, 0);
}

// Two threads sharing at once (two worlds stepped side by side): one of them has the
// helper, the other works alone; every piece of each is done once.
TEST(WorkSharing, TwoCallersAtOnceEachGetEveryPieceDone) {
  std::atomic<int> wrong{0};
  const auto caller = [&wrong] {
    for (int call = 0; call < 200; ++call) {
      const std::vector<int> calls = callsPerPiece(1 + call % 17, true);
      for (int c : calls) wrong += c != 1;
    }
  };
  std::thread other(caller);
  caller();
  other.join();
  EXPECT_EQ(wrong.load(), 0);
}

}  // namespace
}  // namespace polysim::dynamics::solver
