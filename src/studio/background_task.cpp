#include "background_task.hpp"

#include <QMetaObject>

namespace fissure::studio {

BackgroundTask::BackgroundTask(QObject* parent) : QObject(parent) {}

BackgroundTask::~BackgroundTask() {
  cancel();
  join();
}

void BackgroundTask::join() {
  if (m_thread.joinable()) m_thread.join();
}

bool BackgroundTask::start(Work work) {
  if (m_running.load()) return false;
  join();  // the previous worker has finished its work; reap its thread
  m_cancel = std::make_shared<CancelToken>();
  m_running = true;
  m_thread = std::thread([this, work = std::move(work), cancel = m_cancel] {
    std::function<void()> then = work(*cancel);
    // Queued: runs on the UI thread once it returns to its event loop. The destructor joins
    // this thread before the object goes, and a call queued to a destroyed object is dropped.
    QMetaObject::invokeMethod(
        this,
        [this, then = std::move(then)] {
          m_running = false;
          if (then) then();
          emit finished();
        },
        Qt::QueuedConnection);
  });
  return true;
}

void BackgroundTask::cancel() {
  if (m_cancel) m_cancel->cancel();
}

void BackgroundTask::post(std::function<void()> f) { QMetaObject::invokeMethod(this, std::move(f), Qt::QueuedConnection); }

}  // namespace fissure::studio
