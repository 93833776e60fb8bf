#pragma once
// The 3-D view: an OpenGL 3.3 core QOpenGLWidget drawing the document's bodies (shaded in their
// scene colours, crack faces in the crack colour, crack lines over them, the selection lit),
// a grid on the ground plane and the axes. Geometry is uploaded when a body changes, never per
// frame; a frame is uniforms and draw calls. Mouse and keys follow Blender: middle drag orbits,
// Shift + middle drag pans, wheel or Ctrl + middle drag zooms (Alt + left drag orbits without a
// middle button), left click selects (Shift adds), Home frames all, '.' frames the selection.
#include "body_geometry.hpp"
#include "orbit_camera.hpp"
#include "selection.hpp"
#include "studio_document.hpp"

#include <QOpenGLBuffer>
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QOpenGLWidget>
#include <QPoint>

#include <memory>
#include <vector>

namespace fissure::studio {

/// Makes every OpenGL context 3.3 core with a depth buffer; call before the QApplication exists.
void use_gl33_core_by_default(int samples = 4);

class Viewport : public QOpenGLWidget, protected QOpenGLFunctions_3_3_Core {
  Q_OBJECT
 public:
  Viewport(StudioDocument* document, Selection* selection, QWidget* parent = nullptr);
  ~Viewport() override;

  OrbitCamera& camera() { return m_camera; }
  /// Frames every body (or the selection) in the view.
  void frame_all();
  void frame_selection();
  /// What is under pixel (x, y): a body (fragment −1 when it is whole) or nothing (body −1).
  FragmentRef pick(int x, int y) const;
  /// The CPU time the last frame took to prepare (uniforms and draw calls), ms.
  double last_frame_ms() const { return m_last_frame_ms; }
  /// Ready to draw: the shaders compiled (false, with gl_error(), when the context refused them).
  bool gl_ready() const { return m_gl_ready; }
  const QString& gl_error() const { return m_gl_error; }

 signals:
  void gl_failed(const QString& message);

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;

 private:
  struct BodyBuffers {
    BodyGeometry geometry;
    std::unique_ptr<QOpenGLVertexArrayObject> surface_vao, line_vao;
    std::unique_ptr<QOpenGLBuffer> surface_vbo, line_vbo;
    bool uploaded = false;
    int cracks = 0;                // the crack count its fragments are of
  };
  void rebuild_all();
  void rebuild_body(int body);
  void upload(BodyBuffers& b);
  void build_grid();
  Eigen::AlignedBox3d scene_bounds(bool selection_only) const;
  FragmentRef ref_of(int body, const BodyBuffers& b, const BodyGeometry::Range& r) const;
  bool drawn(const FragmentRef& r) const;
  /// Where fragment r is drawn from its place, in scene units.
  Eigen::Vector3d drawn_offset(const FragmentRef& r) const;

  StudioDocument* m_document;
  Selection* m_selection;
  OrbitCamera m_camera;
  std::vector<BodyBuffers> m_bodies;
  std::unique_ptr<QOpenGLShaderProgram> m_surface_program, m_line_program;
  QOpenGLVertexArrayObject m_grid_vao;
  QOpenGLBuffer m_grid_vbo;
  int m_grid_vertices = 0;
  bool m_gl_ready = false;
  QString m_gl_error;
  QPoint m_last_mouse, m_press_mouse;
  Qt::MouseButtons m_drag_buttons;
  double m_last_frame_ms = 0.0;
};

}  // namespace fissure::studio
