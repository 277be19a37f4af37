#pragma once
// A floor plan drawn as it will be imported: occluder segments dark and thick, the others light (fainter
// still on layers that are off in the file), a scale bar in metres so a wrong unit shows at once, and the
// envelope of a marked point filled. The wheel zooms about the cursor, a drag pans, a double click fits the
// plan again, and a click (press and release without moving) marks a point and emits point_clicked().
// It computes nothing: the dialog hands it the envelope.
#include <Eigen/Core>
#include <QString>
#include <QWidget>
#include <optional>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath::widgets {

class PlanPreview : public QWidget {
  Q_OBJECT
 public:
  explicit PlanPreview(QWidget* parent = nullptr);
  // The plan to draw (not owned; null = none). A different plan or new extents fit the view again.
  void set_plan(const FloorPlan* plan);
  // The plan's occluder flags changed: repaint, keep the view.
  void plan_changed() { update(); }
  void fit();  // the whole plan in view

  void set_marked_point(const std::optional<Eigen::Vector2d>& point);
  const std::optional<Eigen::Vector2d>& marked_point() const { return marked_; }
  // The envelope of the marked point (counter-clockwise, metres); empty = none shown.
  void set_envelope(std::vector<Eigen::Vector2d> polygon);
  const std::vector<Eigen::Vector2d>& envelope() const { return envelope_; }
  // A line drawn in the preview's top-left corner (what the envelope says, the plan's size).
  void set_note(const QString& note);
  const QString& note() const { return note_; }

  // View transform: plan metres <-> widget pixels.
  QPointF widget_from_plan(const Eigen::Vector2d& p) const;
  Eigen::Vector2d plan_from_widget(const QPointF& q) const;
  double pixels_per_metre() const { return scale_; }
  // The scale bar's length in metres and in pixels, as drawn.
  double scale_bar_metres() const;

  QSize sizeHint() const override { return {460, 360}; }
  QSize minimumSizeHint() const override { return {260, 200}; }

 signals:
  void point_clicked(const Eigen::Vector2d& plan_point);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;

 private:
  void draw_scale_bar(class QPainter& painter) const;

  const FloorPlan* plan_ = nullptr;
  PlanExtents fitted_extents_;  // the extents the view was last fitted to
  bool fitted_ = false;
  bool user_moved_ = false;                           // zoomed or panned since the last fit
  double scale_ = 1.0;                                // pixels per metre
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();  // plan point at the widget's centre
  std::optional<Eigen::Vector2d> marked_;
  std::vector<Eigen::Vector2d> envelope_;
  QString note_;
  // Mouse gesture: where the button went down, and whether it moved far enough to be a drag.
  QPoint press_pos_;
  QPoint last_pos_;
  bool pressed_ = false;
  bool dragging_ = false;
};

}  // namespace plenopath::widgets
