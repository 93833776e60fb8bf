#pragma once
// One piece of core work on a worker thread, so the UI thread never waits on the core: the work
// runs there with a cancel token, and what it hands back runs on the UI thread afterwards (a
// queued call), where it may touch the document. Destroying the task cancels the work and waits
// for it, so no worker outlives what it reads.
#include "fissure/base/progress.hpp"

#include <QObject>

#include <atomic>
#include <functional>
#include <memory>
#include <thread>

namespace fissure::studio {

class BackgroundTask : public QObject {
  Q_OBJECT
 public:
  /// Runs on the worker; returns what to run on the UI thread when it is done (may be empty).
  /// It must catch its own exceptions (and turn them into a continuation that reports them).
  using Work = std::function<std::function<void()>(const CancelToken&)>;

  explicit BackgroundTask(QObject* parent = nullptr);
  ~BackgroundTask() override;

  /// Starts `work` unless a previous one is still running (then false).
  bool start(Work work);
  void cancel();
  bool running() const { return m_running.load(); }
  /// From the worker: runs `f` on this object's thread.
  void post(std::function<void()> f);

 signals:
  /// On the UI thread, after the work's continuation ran.
  void finished();

 private:
  void join();
  std::thread m_thread;
  std::shared_ptr<CancelToken> m_cancel;
  std::atomic<bool> m_running{false};
};

}  // namespace fissure::studio
