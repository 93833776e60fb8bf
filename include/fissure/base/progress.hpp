#pragma once
/// Progress and cancellation for long jobs (meshing, modal analysis, simulation, fitting). Plain
/// C++: the studio adapts a ProgressSink to queued Qt signals; the CLI prints or ignores it.

#include <atomic>
#include <string_view>

namespace fissure {

/// Set from any thread; checked by the job at loop boundaries.
class CancelToken {
public:
  void cancel() { m_cancelled.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return m_cancelled.load(std::memory_order_relaxed); }
  /// Throws Cancelled when cancel() has been called.
  void throw_if_cancelled() const;

private:
  std::atomic<bool> m_cancelled{false};
};

/// Receives progress from a job. Implementations must be thread-safe if a job reports from
/// several workers; jobs report a few times per second at most.
class ProgressSink {
public:
  virtual ~ProgressSink() = default;
  /// `fraction` in [0, 1] of the current `stage` ("tetrahedralize", "eigensolve", …).
  virtual void report(std::string_view stage, double fraction) = 0;
};

/// A sink that discards everything: the default when the caller does not care.
class NullProgress final : public ProgressSink {
public:
  void report(std::string_view, double) override {}
};

}  // namespace fissure
