#pragma once
// The studio's background work over a document: fracturing bodies (the scene module's
// fracture_scene(), the very call `fissure scene fracture` makes) and meshing a fractured body's
// fragments at the age the slider shows (mesh_fragments() over its kept tet mesh, no new
// simulation). Results reach the document as undoable commands on the UI thread.
#include "background_task.hpp"
#include "studio_document.hpp"

#include <QObject>
#include <QString>

#include <filesystem>
#include <set>
#include <utility>
#include <vector>

namespace fissure::studio {

class StudioJobs : public QObject {
  Q_OBJECT
 public:
  explicit StudioJobs(StudioDocument* document, QObject* parent = nullptr);

  /// Fractures `bodies` (those with a material; the others are ignored) in the background.
  /// False, with fracture_refused(), when none has a material or a fracture is already running.
  bool fracture(const std::vector<int>& bodies, const QString& text);
  void cancel_fracture();
  bool fracture_running() const { return m_fracture.running(); }
  bool age_running() const { return m_age.running(); }
  /// Where tet meshes and stress fields are cached (empty: no cache).
  void set_cache_directory(const std::filesystem::path& directory) { m_cache = directory; }
  void set_threads(int threads) { m_threads = threads; }

 signals:
  void fracture_started(int bodies);
  void fracture_progress(int done, int total, const QString& path);
  /// After the result was pushed as one undo step; `summary` says what broke and what did not.
  void fracture_finished(const QString& summary);
  void fracture_failed(const QString& message);
  /// A fracture not started (nothing assigned, one already running): the running one, if any, goes on.
  void fracture_refused(const QString& message);
  void fracture_cancelled();
  void age_meshed(int body, int cracks);
  void age_failed(const QString& message);

 private:
  void mesh_next_age();
  StudioDocument* m_document;
  BackgroundTask m_fracture, m_age;
  std::filesystem::path m_cache;
  int m_threads = 1;
};

}  // namespace fissure::studio
