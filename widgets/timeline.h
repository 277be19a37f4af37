#pragma once
// The timeline: a frame scrubber with keyframe ticks, the visibility cells as coloured bands, a plot of
// the envelope area along the path and amber marks over the frames the tracker flagged (the line above
// says why for the current one); a play button that plays at the capture's frame rate.
#include <QVector>
#include <QWidget>

class QLabel;
class QSpinBox;
class QTimer;
class QToolButton;

namespace plenopath::widgets {

class ProjectDocument;

// The strip itself: click or drag to move the current frame.
class TimelineStrip : public QWidget {
  Q_OBJECT
 public:
  explicit TimelineStrip(ProjectDocument& document, QWidget* parent = nullptr);
  QSize sizeHint() const override { return {800, 96}; }
  // Position under widget x, and x of a position.
  int position_at(double x) const;
  double x_of(int position) const;
  // Per-position series plotted along the path (empty = not shown): envelope area (m^2) and depth volume
  // (m^3), each scaled to its own maximum. Computed elsewhere (processing/), shown here.
  void set_profiles(QVector<double> envelope_area, QVector<double> depth_volume);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;

 private:
  QRectF plot_rect() const;
  ProjectDocument& document_;
  QVector<double> envelope_area_;
  QVector<double> depth_volume_;
};

class TimelinePanel : public QWidget {
  Q_OBJECT
 public:
  explicit TimelinePanel(ProjectDocument& document, QWidget* parent = nullptr);
  void set_playing(bool playing);
  bool playing() const;
  int play_interval_ms() const;  // the timer's period while playing: one frame at the capture's rate
  TimelineStrip* strip() const { return strip_; }
  QString info_text() const;  // the line beside the frame box (for tests)

 private:
  void update_controls();
  ProjectDocument& document_;
  TimelineStrip* strip_;
  QToolButton* play_;
  QSpinBox* frame_box_;
  QLabel* info_;
  QTimer* play_timer_;
};

}  // namespace plenopath::widgets
