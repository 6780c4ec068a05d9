#include "threads.h"

#include <stdexcept>
#include <string>

#if defined(__GLIBCXX__) && !defined(_GLIBCXX_HAS_GTHREADS) && !defined(CHAINDRIVE_NO_THREADS)
#define CHAINDRIVE_NO_THREADS 1  // (libstdc++ without a thread model: no std::thread)
#endif

#ifndef CHAINDRIVE_NO_THREADS
#include <atomic>
#include <chrono>
#include <cstdint>
#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <immintrin.h>
#endif
#endif

namespace chaindrive {

#ifdef CHAINDRIVE_NO_THREADS

bool threadsAvailable() { return false; }

struct StagePool::Shared {};

StagePool::StagePool(int threads) : threads_(threads) {
  if (threads != 1)
    throw std::invalid_argument("solver.threads = " + std::to_string(threads) +
                                ": this build has no threads (a source build without std::thread); allowed: 1");
}
StagePool::~StagePool() = default;
void StagePool::run(Task task, void* context) noexcept { task(context, 0); }
void StagePool::barrier(int) noexcept {}
long long StagePool::barriers() const { return 0; }
void StagePool::work(int) noexcept {}
void StagePool::arrive(int) noexcept {}
void StagePool::stopWorkers() noexcept {}

#else

namespace {

inline void pause() noexcept {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
  _mm_pause();
#endif
}

// How long a thread spins for the next run before it sleeps: a rig's frames and a master's steps
// come sooner; a master that stops for longer pays one wake-up (some 30 us) at its next step.
constexpr auto kSpinBeforeSleep = std::chrono::milliseconds(2);
// How long a thread spins at a barrier before it yields its core at every look: a barrier on free
// cores takes well under a microsecond; yielding sooner would hand the core to another process.
constexpr auto kSpinBeforeYield = std::chrono::microseconds(50);

}  // namespace

bool threadsAvailable() { return true; }

// A thread's count of the barriers it reached (a run's end included: the same for every thread
// once all are through), on a cache line of its own: each thread writes its own and reads the
// others', so that a barrier of two threads costs one exchange of lines each way, at once.
struct alignas(64) Arrivals {
  std::atomic<std::uint64_t> count{0};
};

struct StagePool::Shared {
  alignas(64) std::atomic<std::uint64_t> generation{0};  // runs started (and one more to stop)
  alignas(64) std::atomic<int> sleepers{0};
  std::vector<Arrivals> arrivals;  // (threads)
  std::atomic<bool> stop{false};
  Task task = nullptr;
  void* context = nullptr;
  std::mutex mutex;
  std::condition_variable wake;
  std::vector<std::thread> workers;
};

StagePool::StagePool(int threads) : threads_(threads), shared_(std::make_unique<Shared>()) {
  if (threads < 1) throw std::invalid_argument("solver.threads = " + std::to_string(threads) + ": at least 1");
  shared_->arrivals = std::vector<Arrivals>(static_cast<std::size_t>(threads));
  shared_->workers.reserve(static_cast<std::size_t>(threads - 1));
  try {
    for (int t = 1; t < threads; ++t) shared_->workers.emplace_back([this, t] { work(t); });
  } catch (const std::system_error& e) {  // (a C library without threads linked in, a process at its limit)
    stopWorkers();
    throw std::invalid_argument("solver.threads = " + std::to_string(threads) + ": the threads could not start (" +
                                e.what() + "); allowed here: 1");
  }
}

StagePool::~StagePool() { stopWorkers(); }

void StagePool::stopWorkers() noexcept {
  Shared& s = *shared_;
  s.stop.store(true);
  s.generation.fetch_add(1);
  {
    std::lock_guard<std::mutex> lock(s.mutex);
  }
  s.wake.notify_all();
  for (std::thread& w : s.workers) w.join();
}

void StagePool::run(Task task, void* context) noexcept {
  Shared& s = *shared_;
  if (threads_ == 1) return task(context, 0);
  s.task = task;
  s.context = context;
  s.generation.fetch_add(1);  // (sequentially consistent: a sleeper counted after it sees the run)
  if (s.sleepers.load() > 0) {
    { std::lock_guard<std::mutex> lock(s.mutex); }
    s.wake.notify_all();
  }
  task(context, 0);
  barrier(0);
}

void StagePool::barrier(int thread) noexcept {
  if (threads_ == 1) return;
  arrive(thread);
  const std::uint64_t count = shared_->arrivals[static_cast<std::size_t>(thread)].count.load(std::memory_order_relaxed);
  for (const Arrivals& other : shared_->arrivals) {
    if (other.count.load(std::memory_order_acquire) >= count) continue;
    const auto since = std::chrono::steady_clock::now();
    bool yielding = false;
    for (int spins = 1; other.count.load(std::memory_order_acquire) < count; ++spins) {
      if (yielding) std::this_thread::yield();  // (more threads than free cores: let the one awaited run)
      else pause();
      if (spins % 256 == 0 && !yielding) yielding = std::chrono::steady_clock::now() - since > kSpinBeforeYield;
    }
  }
}

void StagePool::arrive(int thread) noexcept {
  std::atomic<std::uint64_t>& mine = shared_->arrivals[static_cast<std::size_t>(thread)].count;
  mine.store(mine.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

long long StagePool::barriers() const {
  return threads_ == 1 ? 0 : static_cast<long long>(shared_->arrivals[0].count.load());
}

void StagePool::work(int thread) noexcept {
  Shared& s = *shared_;
  std::uint64_t seen = 0;
  for (;;) {
    // spin, then sleep, until the next run
    const auto since = std::chrono::steady_clock::now();
    for (int spins = 0; s.generation.load(std::memory_order_acquire) == seen; ++spins) {
      pause();
      if (spins % 1024 != 1023 || std::chrono::steady_clock::now() - since < kSpinBeforeSleep) continue;
      std::unique_lock<std::mutex> lock(s.mutex);
      s.sleepers.fetch_add(1);
      s.wake.wait(lock, [&] { return s.generation.load() != seen; });
      s.sleepers.fetch_sub(1);
    }
    seen = s.generation.load(std::memory_order_acquire);
    if (s.stop.load()) return;
    s.task(s.context, thread);
    arrive(thread);  // (the run's end: the calling thread waits for it, this one goes on)
  }
}

#endif

}  // namespace chaindrive
