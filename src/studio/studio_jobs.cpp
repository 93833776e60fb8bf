#include "studio_jobs.hpp"

#include "studio_commands.hpp"

#include "fissure/base/error.hpp"

#include <QThread>

#include <algorithm>

namespace fissure::studio {

StudioJobs::StudioJobs(StudioDocument* document, QObject* parent)
    : QObject(parent), m_document(document), m_threads(std::max(1, QThread::idealThreadCount())) {
  connect(document, &StudioDocument::age_changed, this, &StudioJobs::mesh_next_age);
  connect(document, &StudioDocument::body_changed, this, &StudioJobs::mesh_next_age);
  connect(&m_age, &BackgroundTask::finished, this, &StudioJobs::mesh_next_age);
}

bool StudioJobs::fracture(const std::vector<int>& bodies, const QString& text) {
  if (m_fracture.running()) {
    emit fracture_refused("A fracture is already running: wait for it or cancel it (Esc).");
    return false;
  }
  std::vector<int> assigned;
  for (int b : bodies)
    if (!m_document->material_of(b).empty()) assigned.push_back(b);
  if (assigned.empty()) {
    emit fracture_refused(bodies.empty() ? "Nothing is selected to fracture."
                                         : "No fracture material is assigned to the selection: assign one from the library first.");
    return false;
  }
  SceneFractureOptions options;
  try {
    options = m_document->fracture_options(assigned);
  } catch (const Error& e) {
    emit fracture_refused(QString::fromStdString(e.what()));
    return false;
  }
  options.threads = m_threads;
  options.cache_dir = m_cache;
  const auto scene = m_document->scene_ptr();
  StudioDocument* document = m_document;
  const auto total = static_cast<int>(assigned.size());
  m_fracture.start([this, scene, options, document, text](const CancelToken& cancel) mutable -> std::function<void()> {
    options.cancel = &cancel;
    options.on_body_done = [this](int done, int all, const std::string& path) {
      m_fracture.post([this, done, all, p = QString::fromStdString(path)] { emit fracture_progress(done, all, p); });
    };
    try {
      auto result = std::make_shared<SceneFracture>(fracture_scene(*scene, options));
      return [this, result, document, text, scene] {
        if (document->scene_ptr() != scene) {  // another scene was opened meanwhile
          emit fracture_cancelled();
          return;
        }
        QStringList skipped;
        int broken = 0;
        for (const SceneBodyReport& r : result->reports) {
          if (r.status == SceneBodyReport::Status::Fractured) ++broken;
          if (r.status == SceneBodyReport::Status::Skipped)
            skipped << QString::fromStdString(r.path + ": " + r.reason);
        }
        auto states = StudioDocument::fracture_states(std::move(*result));
        if (!states.empty()) document->undo_stack()->push(new ApplyFractureCommand(document, std::move(states), text));
        QString summary = QString("%1 %2 fractured").arg(broken).arg(broken == 1 ? "body" : "bodies");
        if (!skipped.isEmpty()) summary += QString("; %1 skipped:\n").arg(skipped.size()) + skipped.join("\n");
        emit fracture_finished(summary);
      };
    } catch (const Cancelled&) {
      return [this] { emit fracture_cancelled(); };
    } catch (const std::exception& e) {
      return [this, message = QString::fromStdString(e.what())] { emit fracture_failed(message); };
    }
  });
  emit fracture_started(total);
  return true;
}

void StudioJobs::cancel_fracture() { m_fracture.cancel(); }

// One body at a time, the first in body order whose shown age has no fragments yet; each
// finished job calls this again, so a slider dragged across many ages meshes only where it rests.
void StudioJobs::mesh_next_age() {
  if (m_age.running()) return;
  for (int b = 0; b < static_cast<int>(m_document->bodies().size()); ++b) {
    const auto state = m_document->fracture_of(b);
    if (!state) continue;
    const int want = m_document->shown_cracks(b);
    if (state->fragments_at.count(want) || state->failed_counts.count(want) || !state->fractured.fracture.mesh) continue;
    StudioDocument* document = m_document;
    m_age.start([this, state, want, b, document](const CancelToken&) -> std::function<void()> {
      try {
        const auto& f = state->fractured.fracture;
        auto fragments = std::make_shared<const std::vector<FragmentMesh>>(mesh_fragments(*f.mesh, f.result.cracks, want, 1));
        return [this, document, b, state, want, fragments] {
          document->add_fragments(b, state.get(), want, fragments);
          emit age_meshed(b, want);
        };
      } catch (const std::exception& e) {
        // Not retried (the slider would loop on it); the nearest meshed age stays shown.
        return [this, document, b, state, want, message = QString::fromStdString(e.what())] {
          document->mark_failed(b, state.get(), want);
          emit age_failed(message);
        };
      }
    });
    return;
  }
}

}  // namespace fissure::studio
