#pragma once
// The panorama: a perspective view of the current frame's equirectangular image, drawn by a fragment
// shader that turns each screen pixel into a bearing and looks it up per rig/spherical.h's convention.
// Drag to look around, wheel to change the field of view, Left/Right (or PageUp/PageDown) to step frames,
// E to toggle the whole equirectangular image with the hotspots outlined. A comparison (the clean plate of
// the shown frame) splits the view: left of a vertical line the frame as captured, right of it the other
// image, the line dragged with the mouse; Esc or another frame ends it. Ctrl+drag paints the clean plate
// away (take what other frames saw), Ctrl+Shift+drag paints it back (keep as captured): each stroke arrives
// as stroke_painted, a mask of the frame's size. Hotspot authoring (new quads,
// handles, Delete, Esc) and the hotspot overlay live in HotspotEditor (widgets/hotspot_editor.h).
#include <QImage>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <memory>
#include <optional>
#include <vector>

#include "rig/spherical.h"

class QOpenGLShaderProgram;
class QOpenGLVertexArrayObject;
class QOpenGLBuffer;

namespace plenopath::widgets {

class FrameProvider;
class HotspotEditor;
class ProjectDocument;

class PanoramaView : public QOpenGLWidget, protected QOpenGLFunctions {
  Q_OBJECT
 public:
  PanoramaView(ProjectDocument& document, FrameProvider& frames, QWidget* parent = nullptr);
  ~PanoramaView() override;

  // Look direction (radians): azimuth grows to the right, elevation up; horizontal field of view.
  void set_look(double azimuth, double elevation, double fov);
  double azimuth() const { return azimuth_; }
  double elevation() const { return elevation_; }
  double fov() const { return fov_; }

  void set_equirect_mode(bool whole_image);
  bool equirect_mode() const { return equirect_mode_; }

  // Position whose image is on screen (-1 while none).
  int shown_position() const { return shown_position_; }

  // Direction (azimuth, elevation in the frame's camera) under a widget point; none outside the image.
  std::optional<SphericalAngles> direction_at(const QPointF& widget_point) const;
  // Widget point of a direction in the frame's camera; none when behind the viewer.
  std::optional<QPointF> widget_point_of(const SphericalAngles& direction) const;
  // The letterboxed image's rectangle in whole-image mode (widget pixels).
  QRectF image_box() const;
  // Before/after: `after` (the same size as the frame, equirectangular) shown right of the split while
  // `position` is on screen; `label` names it on the view. Another frame, Esc or clear_comparison() end it.
  void set_comparison(int position, const QImage& after, const QString& label);
  void clear_comparison();
  bool comparing() const { return comparison_position_ >= 0; }
  double comparison_split() const { return split_; }  // share of the width left of the line
  void set_comparison_split(double split);
  // Hotspot authoring and overlay in this view.
  HotspotEditor& hotspot_editor() const { return *hotspots_; }

 signals:
  void image_shown(int position);
  void equirect_mode_changed(bool whole_image);
  void comparison_changed(bool comparing);
  // A finished stroke on the comparison: `mask` (Grayscale8, the frame's size) is 255 where painted;
  // `value` is what those pixels mean (kCleanPlateRemove or kCleanPlateKeep, model/tour_settings.h).
  void stroke_painted(int position, const QImage& mask, int value);

 protected:
  void initializeGL() override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  void show_current();
  void upload_pending_image();
  void draw_overlay();
  void release_gl();

  ProjectDocument& document_;
  FrameProvider& frames_;
  std::unique_ptr<QOpenGLShaderProgram> program_;
  std::unique_ptr<QOpenGLVertexArrayObject> vao_;
  std::unique_ptr<QOpenGLBuffer> quad_;
  unsigned texture_ = 0;
  unsigned after_texture_ = 0;
  QImage pending_after_;  // uploaded at the next paint
  int comparison_position_ = -1;
  QString comparison_label_;
  double split_ = 0.5;
  bool dragging_split_ = false;
  int paint_value_ = 0;                         // the stroke being painted (0: none)
  QImage stroke_;                               // its mask, the frame's size
  QSize comparison_size_;                       // the frame's size
  std::vector<QPointF> stroke_points_;          // widget points, drawn while painting
  void paint_at(const QPointF& widget_point);   // the stroke on to here
  void paint_dab(const QPointF& widget_point);  // one brush mark
  QImage pending_image_;                        // uploaded at the next paint
  QSize texture_size_;
  int pending_position_ = -1;
  int shown_position_ = -1;
  QString message_;
  double azimuth_ = 0.0;
  double elevation_ = 0.0;
  double fov_ = 1.5707963267948966;
  bool equirect_mode_ = false;
  QPoint last_mouse_;
  HotspotEditor* hotspots_;
};

}  // namespace plenopath::widgets
