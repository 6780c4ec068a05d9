// Threads for one evaluation's stages (solver.threads): a fixed set of threads that each run the
// same stage function on their own share of the work and meet at barriers, the calling thread
// being thread 0. The threads start with the pool and join when it is destroyed; between runs they
// spin for a while (a rig's next frame comes within microseconds), then sleep until the next run.
// A run allocates nothing. Stage functions must not throw: a thread that left a run early would
// leave the others waiting at the next barrier.
#pragma once

#include <memory>
#include <vector>

namespace chaindrive {

/// Whether this build runs threads (false: a build without std::thread, or one built with
/// CHAINDRIVE_NO_THREADS, such as a source FMU for a target without threads).
bool threadsAvailable();

class StagePool {
 public:
  using Task = void (*)(void* context, int thread) noexcept;
  static constexpr int kMaxThreads = 16;  // (solver.threads' range: 1 to this)

  /// A pool of `threads` threads (the caller and threads - 1 more). Throws std::invalid_argument,
  /// naming solver.threads, for threads < 1, and for threads > 1 in a build without threads or
  /// where they cannot start.
  explicit StagePool(int threads);
  ~StagePool();
  StagePool(const StagePool&) = delete;
  StagePool& operator=(const StagePool&) = delete;

  int size() const { return threads_; }

  /// task(context, t) on every thread t (the caller's is 0); returns when all have returned.
  void run(Task task, void* context) noexcept;
  template <class F>
  void run(F& f) noexcept {
    run([](void* c, int t) noexcept { (*static_cast<F*>(c))(t); }, &f);
  }

  /// Within a run, on thread `thread`: returns once every thread has called it.
  void barrier(int thread) noexcept;

  /// Barriers crossed since the pool started (runs' ends included): the cost's measure.
  long long barriers() const;

 private:
  struct Shared;
  void work(int thread) noexcept;
  void arrive(int thread) noexcept;
  void stopWorkers() noexcept;

  int threads_;
  std::unique_ptr<Shared> shared_;
};

}  // namespace chaindrive
