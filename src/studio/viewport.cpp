#include "viewport.hpp"

#include <QElapsedTimer>
#include <QFile>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

namespace fissure::studio {
namespace {

// The crack faces' colour: fragment_scene()'s crack material, a pale broken-stone grey.
const Eigen::Vector3f kCrackColour(0.86f, 0.84f, 0.80f);
const Eigen::Vector3d kCrackLineColour(0.08, 0.07, 0.06);
const Eigen::Vector3f kHighlight(0.30f, 0.15f, 0.0f);  // Blender's orange selection, added

QString shader_source(const QString& name) {
  QFile f(":/shaders/" + name);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QString::fromUtf8(f.readAll());
}

}  // namespace

void use_gl33_core_by_default(int samples) {
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setSamples(samples);
  QSurfaceFormat::setDefaultFormat(format);
}

Viewport::Viewport(StudioDocument* document, Selection* selection, QWidget* parent)
    : QOpenGLWidget(parent), m_document(document), m_selection(selection), m_grid_vbo(QOpenGLBuffer::VertexBuffer) {
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(320, 240);
  connect(document, &StudioDocument::scene_reset, this, [this] {
    m_camera.set_up(m_document->up());
    rebuild_all();
    frame_all();
  });
  connect(document, &StudioDocument::body_changed, this, [this](int b) {
    rebuild_body(b);
    update();
  });
  connect(document, &StudioDocument::age_changed, this, [this] {
    // Only bodies whose shown crack count moved: a slider tick within one crack's interval rebuilds nothing.
    for (int b = 0; b < static_cast<int>(m_bodies.size()); ++b) {
      int cracks = 0;
      if (m_document->shown_fragments(b, &cracks) && cracks != m_bodies[static_cast<std::size_t>(b)].cracks) rebuild_body(b);
    }
    update();
  });
  connect(document, &StudioDocument::explode_changed, this, qOverload<>(&QWidget::update));
  // Moves, hides and deletes are uniforms and skipped ranges: nothing to rebuild.
  connect(document, &StudioDocument::edits_changed, this, qOverload<>(&QWidget::update));
  connect(selection, &Selection::changed, this, qOverload<>(&QWidget::update));
}

Viewport::~Viewport() {
  makeCurrent();
  m_bodies.clear();
  m_surface_program.reset();
  m_line_program.reset();
  if (m_grid_vao.isCreated()) m_grid_vao.destroy();
  if (m_grid_vbo.isCreated()) m_grid_vbo.destroy();
  doneCurrent();
}

void Viewport::initializeGL() {
  if (!initializeOpenGLFunctions()) {
    m_gl_error = "this display offers no OpenGL 3.3 core context";
    emit gl_failed(m_gl_error);
    return;
  }
  auto program = [this](const char* vert, const char* frag) {
    auto p = std::make_unique<QOpenGLShaderProgram>();
    if (!p->addShaderFromSourceCode(QOpenGLShader::Vertex, shader_source(vert)) ||
        !p->addShaderFromSourceCode(QOpenGLShader::Fragment, shader_source(frag)) || !p->link()) {
      m_gl_error = QString("shader %1/%2: %3").arg(vert, frag, p->log());
      return std::unique_ptr<QOpenGLShaderProgram>();
    }
    return p;
  };
  m_surface_program = program("surface.vert", "surface.frag");
  m_line_program = program("lines.vert", "lines.frag");
  if (!m_surface_program || !m_line_program) {
    emit gl_failed(m_gl_error);
    return;
  }
  m_gl_ready = true;
  glEnable(GL_DEPTH_TEST);
  build_grid();
  for (BodyBuffers& b : m_bodies) b.uploaded = false;
}

void Viewport::resizeGL(int, int) {}

void Viewport::build_grid() {
  // A grid of 1-unit cells on the ground plane (orthogonal to up, through the origin), 20 × 20,
  // and the two horizontal axes in Blender's red and green.
  const Eigen::Vector3d up = m_document->is_open() ? m_document->up() : Eigen::Vector3d::UnitY();
  Eigen::Index least = 0;
  up.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d a = (Eigen::Vector3d::Unit(least) - up * up(least)).normalized();
  const Eigen::Vector3d b = up.cross(a);
  std::vector<float> v;
  auto line = [&v](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& c) {
    for (const Eigen::Vector3d* x : {&p, &q}) {
      for (int k = 0; k < 3; ++k) v.push_back(static_cast<float>((*x)(k)));
      for (int k = 0; k < 3; ++k) v.push_back(static_cast<float>(c(k)));
    }
  };
  const int n = 10;
  const Eigen::Vector3d grey(0.32, 0.32, 0.32);
  for (int i = -n; i <= n; ++i) {
    if (i == 0) continue;
    line(a * i - b * n, a * i + b * n, grey);
    line(b * i - a * n, b * i + a * n, grey);
  }
  line(-a * n, a * n, Eigen::Vector3d(0.75, 0.2, 0.2));
  line(-b * n, b * n, Eigen::Vector3d(0.3, 0.65, 0.2));
  line(Eigen::Vector3d::Zero(), up, Eigen::Vector3d(0.2, 0.4, 0.8));
  m_grid_vertices = static_cast<int>(v.size() / 6);
  if (!m_grid_vao.isCreated()) m_grid_vao.create();
  if (!m_grid_vbo.isCreated()) m_grid_vbo.create();
  m_grid_vao.bind();
  m_grid_vbo.bind();
  m_grid_vbo.allocate(v.data(), static_cast<int>(v.size() * sizeof(float)));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  m_grid_vao.release();
}

void Viewport::rebuild_all() {
  makeCurrent();
  m_bodies.clear();
  m_bodies.resize(m_document->bodies().size());
  for (int b = 0; b < static_cast<int>(m_bodies.size()); ++b) rebuild_body(b);
  if (m_gl_ready) build_grid();
  doneCurrent();
  update();
}

void Viewport::rebuild_body(int body) {
  if (body < 0 || body >= static_cast<int>(m_bodies.size())) return;
  BodyBuffers& b = m_bodies[static_cast<std::size_t>(body)];
  const SceneBody& scene_body = m_document->bodies()[static_cast<std::size_t>(body)];
  int cracks = 0;
  if (const auto fragments = m_document->shown_fragments(body, &cracks)) {
    b.geometry = fragment_geometry(*fragments, body_colour(m_document->scene(), scene_body), kCrackLineColour,
                                   1.0 / m_document->unit());
    b.cracks = cracks;
  } else {
    b.geometry = whole_body_geometry(m_document->scene(), scene_body);
    b.cracks = 0;
  }
  b.uploaded = false;
}

void Viewport::upload(BodyBuffers& b) {
  auto fill = [this](std::unique_ptr<QOpenGLVertexArrayObject>& vao, std::unique_ptr<QOpenGLBuffer>& vbo,
                     const std::vector<float>& data, bool surface) {
    // Created anew when missing or when the context they were made in is gone (a QOpenGLWidget
    // gets a new one when it is re-parented).
    if (!vao || !vao->isCreated()) {
      vao = std::make_unique<QOpenGLVertexArrayObject>();
      vao->create();
      vbo = std::make_unique<QOpenGLBuffer>(QOpenGLBuffer::VertexBuffer);
      vbo->create();
    }
    vao->bind();
    vbo->bind();
    vbo->allocate(data.data(), static_cast<int>(data.size() * sizeof(float)));
    const int stride = (surface ? BodyGeometry::kSurfaceFloats : BodyGeometry::kLineFloats) * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(3 * sizeof(float)));
    if (surface) {
      glEnableVertexAttribArray(2);
      glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(6 * sizeof(float)));
      glEnableVertexAttribArray(3);
      glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(9 * sizeof(float)));
    }
    vao->release();
  };
  fill(b.surface_vao, b.surface_vbo, b.geometry.surface, true);
  fill(b.line_vao, b.line_vbo, b.geometry.lines, false);
  b.uploaded = true;
}

FragmentRef Viewport::ref_of(int body, const BodyBuffers& b, const BodyGeometry::Range& r) const {
  return {body, r.fragment < 0 ? 0 : b.cracks, r.fragment};
}

Eigen::Vector3d Viewport::drawn_offset(const FragmentRef& r) const {
  return r.fragment < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(m_document->drawn_offset(r) / m_document->unit());
}

bool Viewport::drawn(const FragmentRef& r) const {
  if (r.fragment < 0) return true;
  const FragmentEdit e = m_document->edit_of(r);
  return !e.hidden && !e.deleted;
}

void Viewport::paintGL() {
  QElapsedTimer timer;
  timer.start();
  glClearColor(0.23f, 0.23f, 0.24f, 1.0f);  // Blender's viewport grey
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!m_gl_ready) return;
  const double aspect = height() > 0 ? double(width()) / height() : 1.0;
  const Eigen::Matrix4f vp = m_camera.projection(aspect) * m_camera.view();
  QMatrix4x4 mvp;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) mvp(r, c) = vp(r, c);

  m_line_program->bind();
  m_line_program->setUniformValue("u_view_projection", mvp);
  m_line_program->setUniformValue("u_offset", QVector3D(0, 0, 0));
  m_grid_vao.bind();
  glDrawArrays(GL_LINES, 0, m_grid_vertices);
  m_grid_vao.release();

  // Light from over the viewer's shoulder, so what faces the camera reads brightest.
  const Eigen::Vector3d light = (-m_camera.forward() + 0.6 * m_document->up()).normalized();
  m_surface_program->bind();
  m_surface_program->setUniformValue("u_view_projection", mvp);
  m_surface_program->setUniformValue("u_light", QVector3D(light.x(), light.y(), light.z()));
  m_surface_program->setUniformValue("u_crack_colour", QVector3D(kCrackColour.x(), kCrackColour.y(), kCrackColour.z()));
  // Faces pushed back a little, so the crack lines drawn after them on their edges stay visible.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  for (int body = 0; body < static_cast<int>(m_bodies.size()); ++body) {
    BodyBuffers& b = m_bodies[static_cast<std::size_t>(body)];
    if (!b.uploaded) upload(b);
    const bool body_selected = m_selection->contains({body, 0, -1});
    b.surface_vao->bind();
    for (const BodyGeometry::Range& r : b.geometry.ranges) {
      const FragmentRef ref = ref_of(body, b, r);
      if (!drawn(ref)) continue;
      const Eigen::Vector3d offset = drawn_offset(ref);
      m_surface_program->setUniformValue("u_offset", QVector3D(offset.x(), offset.y(), offset.z()));
      const bool lit = body_selected || m_selection->contains(ref);
      m_surface_program->setUniformValue("u_highlight", lit ? QVector3D(kHighlight.x(), kHighlight.y(), kHighlight.z()) : QVector3D());
      glDrawArrays(GL_TRIANGLES, r.first, r.count);
    }
    b.surface_vao->release();
  }
  glDisable(GL_POLYGON_OFFSET_FILL);

  m_line_program->bind();
  for (int body = 0; body < static_cast<int>(m_bodies.size()); ++body) {
    BodyBuffers& b = m_bodies[static_cast<std::size_t>(body)];
    if (b.geometry.lines.empty()) continue;
    b.line_vao->bind();
    for (const BodyGeometry::Range& r : b.geometry.ranges) {
      const FragmentRef ref = ref_of(body, b, r);
      if (r.line_count == 0 || !drawn(ref)) continue;
      const Eigen::Vector3d offset = drawn_offset(ref);
      m_line_program->setUniformValue("u_offset", QVector3D(offset.x(), offset.y(), offset.z()));
      glDrawArrays(GL_LINES, r.first_line, r.line_count);
    }
    b.line_vao->release();
  }
  m_last_frame_ms = timer.nsecsElapsed() * 1e-6;
}

Eigen::AlignedBox3d Viewport::scene_bounds(bool selection_only) const {
  Eigen::AlignedBox3d box;
  for (int body = 0; body < static_cast<int>(m_bodies.size()); ++body) {
    const BodyBuffers& b = m_bodies[static_cast<std::size_t>(body)];
    if (!selection_only || m_selection->contains({body, 0, -1})) {
      box.extend(b.geometry.bounds);
      continue;
    }
    for (const BodyGeometry::Range& r : b.geometry.ranges) {
      const FragmentRef ref = ref_of(body, b, r);
      if (!m_selection->contains(ref)) continue;
      const Eigen::Vector3d offset = drawn_offset(ref);
      for (int v = r.first; v < r.first + r.count; ++v) {
        const float* q = &b.geometry.surface[static_cast<std::size_t>(v * BodyGeometry::kSurfaceFloats)];
        box.extend(Eigen::Vector3d(q[0], q[1], q[2]) + offset);
      }
    }
  }
  return box;
}

void Viewport::frame_all() {
  const Eigen::AlignedBox3d box = scene_bounds(false);
  if (!box.isEmpty()) m_camera.frame(box.min(), box.max(), height() > 0 ? double(width()) / height() : 1.0);
  update();
}

void Viewport::frame_selection() {
  const Eigen::AlignedBox3d box = scene_bounds(true);
  if (box.isEmpty()) return frame_all();
  m_camera.frame(box.min(), box.max(), height() > 0 ? double(width()) / height() : 1.0);
  update();
}

FragmentRef Viewport::pick(int x, int y) const {
  Eigen::Vector3d origin, direction;
  m_camera.ray(x, y, width(), height(), origin, direction);
  FragmentRef best;
  double nearest = -1.0;
  for (int body = 0; body < static_cast<int>(m_bodies.size()); ++body) {
    const BodyBuffers& b = m_bodies[static_cast<std::size_t>(body)];
    for (const BodyGeometry::Range& r : b.geometry.ranges) {
      const FragmentRef ref = ref_of(body, b, r);
      if (!drawn(ref)) continue;
      const Eigen::Vector3d offset = drawn_offset(ref);
      const double t = ray_hit(b.geometry, r, offset, origin, direction);
      if (t > 0.0 && (nearest < 0.0 || t < nearest)) {
        nearest = t;
        best = ref;
      }
    }
  }
  return best;
}

void Viewport::mousePressEvent(QMouseEvent* e) {
  m_last_mouse = m_press_mouse = e->pos();
  m_drag_buttons = e->buttons();
}

void Viewport::mouseMoveEvent(QMouseEvent* e) {
  const QPoint d = e->pos() - m_last_mouse;
  m_last_mouse = e->pos();
  const bool middle = e->buttons() & Qt::MiddleButton;
  const bool alt_left = (e->buttons() & Qt::LeftButton) && (e->modifiers() & Qt::AltModifier);
  if (!middle && !alt_left) return;
  if (e->modifiers() & Qt::ShiftModifier) m_camera.pan(d.x(), d.y(), height());
  else if (e->modifiers() & Qt::ControlModifier) m_camera.zoom(-d.y() / 40.0);
  else m_camera.orbit(-d.x() * 0.008, d.y() * 0.008);
  update();
}

void Viewport::mouseReleaseEvent(QMouseEvent* e) {
  // A left click that did not drag (a few pixels of hand shake allowed) selects.
  if (e->button() != Qt::LeftButton || (e->modifiers() & Qt::AltModifier)) return;
  if ((e->pos() - m_press_mouse).manhattanLength() > 4) return;
  const FragmentRef hit = pick(e->pos().x(), e->pos().y());
  if (e->modifiers() & Qt::ShiftModifier) {
    if (hit.body >= 0) m_selection->toggle(hit);
  } else {
    m_selection->set(hit.body >= 0 ? std::set<FragmentRef>{hit} : std::set<FragmentRef>{});
  }
}

void Viewport::wheelEvent(QWheelEvent* e) {
  m_camera.zoom(e->angleDelta().y() / 120.0);
  update();
}

void Viewport::keyPressEvent(QKeyEvent* e) {
  switch (e->key()) {
    case Qt::Key_Home: frame_all(); return;
    case Qt::Key_Period: frame_selection(); return;
    default: QOpenGLWidget::keyPressEvent(e);
  }
}

}  // namespace fissure::studio
