#pragma once
// Walk mode: the exported tour's experience inside the studio. The viewer walks between keyframes along
// the path (W/S, arrows, wheel, or a click on the map window) with a cross-fade, looks around by dragging,
// and sees the map window with the plan, the path, the keyframes and a view cone. The walking logic is
// processing/walk/walk_navigator.h; this widget only draws and takes input.
#include <QElapsedTimer>
#include <QHash>
#include <QImage>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <QTimer>
#include <memory>

#include "processing/walk/walk_navigator.h"

class QOpenGLShaderProgram;
class QOpenGLVertexArrayObject;
class QOpenGLBuffer;

namespace plenopath::widgets {

class FrameProvider;
class ProjectDocument;

class WalkView : public QOpenGLWidget, protected QOpenGLFunctions {
  Q_OBJECT
 public:
  // Throws plenopath::Error when the project cannot be walked (no path or no keyframes).
  WalkView(ProjectDocument& document, FrameProvider& frames, QWidget* parent = nullptr);
  ~WalkView() override;

  const WalkNavigator& navigator() const { return navigator_; }
  WalkNavigator& navigator() { return navigator_; }
  // Measured frames per second over the last second of animation (0 before any).
  double frames_per_second() const { return fps_; }
  // Where a plan point is drawn in the map window (widget coordinates).
  QPointF map_point(const Eigen::Vector2d& p) const;

 signals:
  void keyframe_changed(int frame);

 protected:
  void initializeGL() override;
  void paintGL() override;
  void keyPressEvent(QKeyEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  void tick();
  void request_images();
  unsigned texture_for(int keyframe);
  void draw_map(class QPainter& painter);
  QRectF map_rect() const;
  Eigen::Vector2d plan_point(const QPointF& p) const;
  void release_gl();

  ProjectDocument& document_;
  FrameProvider& frames_;
  WalkNavigator navigator_;
  std::vector<int> position_of_keyframe_;  // path position of each navigator keyframe
  QHash<int, QImage> images_;              // keyframe -> decoded image awaiting upload or kept
  QHash<int, unsigned> textures_;          // keyframe -> GL texture
  QList<int> texture_order_;               // least recently used first
  std::unique_ptr<QOpenGLShaderProgram> program_;
  std::unique_ptr<QOpenGLVertexArrayObject> vao_;
  std::unique_ptr<QOpenGLBuffer> quad_;
  QTimer timer_;
  QElapsedTimer clock_;
  double pitch_ = 0.0;
  double fov_ = 1.4;  // vertical field of view, radians
  QPoint last_mouse_;
  QPoint press_mouse_;
  bool map_drag_ = false;
  int frames_drawn_ = 0;
  QElapsedTimer fps_clock_;
  double fps_ = 0.0;
  int last_emitted_keyframe_ = -1;
};

}  // namespace plenopath::widgets
