#include "dynamics/work_sharing.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>

namespace polysim::dynamics::solver {
namespace {

// One helper thread for the life of the process, waiting between solves. Started afresh
// for each shared solve, a thread took 50 to 85 us to create in this virtual machine:
// 7% of a pile of 125's run (624 shared solves in 10 s), 3% of a pile of 1000's.
class Helper {
 public:
  // The process's helper, started at the first call; null when no thread can be had (a
  // process at its limit: the caller then takes every piece).
  static Helper* instance() {
    static Helper helper;
    return helper.thread_.joinable() ? &helper : nullptr;
  }

  ~Helper() {
    if (!thread_.joinable()) return;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    posted_.notify_one();
    thread_.join();
  }

  // Runs `job` on the helper, and returns at once; finish() waits for it. False when
  // another thread is using the helper (two worlds stepped at once): the caller then
  // works alone. A caller that gets true must call finish() before it calls run() again.
  bool run(const std::function<void()>& job) {
    if (!user_.try_lock()) return false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
    }
    posted_.notify_one();
    return true;
  }

  // Waits for the job run() gave the helper, unless the helper has not taken it up yet:
  // then it is withdrawn, as the caller has done every piece by now (half the jobs of a
  // pile's run: the system is slow to wake the helper's core).
  void finish() {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!taken_) job_ = nullptr;
      done_.wait(lock, [this] { return job_ == nullptr; });
    }
    user_.unlock();
  }

 private:
  Helper() {
    try {
      thread_ = std::thread([this] { serve(); });
    } catch (const std::system_error&) {
      // No thread to be had: instance() reports none.
    }
  }

  void serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      posted_.wait(lock, [this] { return job_ != nullptr || stopping_; });  // a withdrawn job is never seen
      if (stopping_) return;
      const std::function<void()>* job = job_;
      taken_ = true;
      lock.unlock();
      (*job)();
      lock.lock();
      job_ = nullptr, taken_ = false;
      done_.notify_one();
    }
  }

  std::mutex user_;   // held by the caller whose job the helper has
  std::mutex mutex_;  // guards job_, taken_ and stopping_
  std::condition_variable posted_, done_;
  const std::function<void()>* job_ = nullptr;  // the job to run, null once it is done
  bool taken_ = false;                          // the helper is running job_
  bool stopping_ = false;
  std::thread thread_;  // last: started once the members it reads are made
};

}  // namespace

void forEachPiece(int count, bool shared, const std::function<void(int)>& work) {
  std::atomic<int> next{0};
  const std::function<void()> takePieces = [&] {
    for (int i = next++; i < count; i = next++) work(i);
  };
  static const bool twoCores = std::thread::hardware_concurrency() > 1;  // read once: glibc reads /sys each time
  Helper* helper = shared && count > 1 && twoCores ? Helper::instance() : nullptr;
  // The helper's job refers to this frame: it is waited for however the caller leaves.
  struct Finish {
    Helper* helper;
    ~Finish() {
      if (helper) helper->finish();
    }
  } const finish{helper && helper->run(takePieces) ? helper : nullptr};
  takePieces();
}

}  // namespace polysim::dynamics::solver
