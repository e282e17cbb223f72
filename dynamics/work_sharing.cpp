#include "dynamics/work_sharing.h"

#include <atomic>
#include <system_error>
#include <thread>

namespace polysim::dynamics::solver {

void forEachPiece(int count, bool shared, const std::function<void(int)>& work) {
  std::atomic<int> next{0};
  const auto takePieces = [&] {
    for (int i = next++; i < count; i = next++) work(i);
  };
  static const bool twoCores = std::thread::hardware_concurrency() > 1;  // read once: glibc reads /sys each time
  std::thread helper;
  if (shared && count > 1 && twoCores) {
    try {
      helper = std::thread(takePieces);
    } catch (const std::system_error&) {
      // No thread to be had (a process at its limit): the caller takes every piece.
    }
  }
  takePieces();
  if (helper.joinable()) helper.join();
}

}  // namespace polysim::dynamics::solver
