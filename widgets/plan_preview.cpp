#include "widgets/plan_preview.h"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <set>

namespace plenopath::widgets {
namespace {

constexpr int kMargin = 16;        // pixels left and right of the fitted plan
constexpr int kTopMargin = 30;     // room for the note
constexpr int kBottomMargin = 44;  // room for the scale bar
constexpr int kDragThreshold = 4;  // pixels a press must move before it pans instead of marking a point

bool same_extents(const PlanExtents& a, const PlanExtents& b) {
  return a.valid == b.valid && a.min == b.min && a.max == b.max;
}

// "0.5 m", "10 m", "2000 m": the bar stays in metres so a plan read in the wrong unit is obvious.
QString metres_text(double metres) { return QStringLiteral("%1 m").arg(metres, 0, 'g', 6); }

}  // namespace

PlanPreview::PlanPreview(QWidget* parent) : QWidget(parent) {
  setMouseTracking(false);
  setFocusPolicy(Qt::ClickFocus);
  setCursor(Qt::CrossCursor);
  setToolTip(tr("Click: what is seen from there · wheel: zoom · drag: pan · double click: fit"));
}

void PlanPreview::set_plan(const FloorPlan* plan) {
  plan_ = plan;
  const PlanExtents e = plan_ ? plan_->extents() : PlanExtents{};
  if (!fitted_ || !same_extents(e, fitted_extents_)) fit();
  update();
}

void PlanPreview::fit() {
  fitted_ = true;
  user_moved_ = false;
  fitted_extents_ = plan_ ? plan_->extents() : PlanExtents{};
  if (!fitted_extents_.valid) {
    scale_ = 1.0;
    centre_.setZero();
    update();
    return;
  }
  // Fit into the area the note (top) and the scale bar (bottom) leave free.
  const QRectF free(kMargin, kTopMargin, std::max(1, width() - 2 * kMargin),
                    std::max(1, height() - kTopMargin - kBottomMargin));
  const Eigen::Vector2d size = fitted_extents_.size().cwiseMax(1e-9);
  scale_ = std::min(free.width() / size.x(), free.height() / size.y());
  const Eigen::Vector2d middle = 0.5 * (fitted_extents_.min + fitted_extents_.max);
  centre_ = {middle.x() - (free.center().x() - width() / 2.0) / scale_,
             middle.y() + (free.center().y() - height() / 2.0) / scale_};
  update();
}

void PlanPreview::set_marked_point(const std::optional<Eigen::Vector2d>& point) {
  marked_ = point;
  update();
}

void PlanPreview::set_envelope(std::vector<Eigen::Vector2d> polygon) {
  envelope_ = std::move(polygon);
  update();
}

void PlanPreview::set_note(const QString& note) {
  note_ = note;
  update();
}

QPointF PlanPreview::widget_from_plan(const Eigen::Vector2d& p) const {
  // Plan Y up, screen y down.
  return {width() / 2.0 + (p.x() - centre_.x()) * scale_, height() / 2.0 - (p.y() - centre_.y()) * scale_};
}

Eigen::Vector2d PlanPreview::plan_from_widget(const QPointF& q) const {
  return {centre_.x() + (q.x() - width() / 2.0) / scale_, centre_.y() - (q.y() - height() / 2.0) / scale_};
}

double PlanPreview::scale_bar_metres() const {
  // The largest of 1, 2, 5 x 10^k metres that is at most a quarter of the width (and at least 40 px).
  const double max_px = std::max(40.0, width() / 4.0);
  const double max_m = max_px / scale_;
  const double decade = std::pow(10.0, std::floor(std::log10(max_m)));
  for (double step : {5.0, 2.0, 1.0})
    if (step * decade <= max_m) return step * decade;
  return decade;
}

void PlanPreview::resizeEvent(QResizeEvent*) {
  // A view the author has not moved keeps showing the whole plan.
  if (fitted_ && !user_moved_) fit();
}

void PlanPreview::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(250, 249, 245));
  if (!plan_ || plan_->empty()) {
    painter.setPen(QColor(120, 120, 120));
    painter.drawText(rect(), Qt::AlignCenter, tr("No plan"));
    return;
  }
  painter.setRenderHint(QPainter::Antialiasing);

  // Envelope under the lines.
  if (envelope_.size() >= 3) {
    QPolygonF polygon;
    for (const Eigen::Vector2d& p : envelope_) polygon << widget_from_plan(p);
    painter.setPen(QPen(QColor(40, 120, 200), 1.0));
    painter.setBrush(QColor(70, 150, 230, 90));
    painter.drawPolygon(polygon);
    painter.setBrush(Qt::NoBrush);
  }

  std::set<std::string> off_layers;
  for (const PlanLayer& layer : plan_->layers)
    if (!layer.visible) off_layers.insert(layer.name);
  QVector<QLineF> off, light, dark;
  const QRectF view = QRectF(rect()).adjusted(-2, -2, 2, 2);
  for (const PlanSegment& s : plan_->segments) {
    const QLineF line(widget_from_plan(s.a), widget_from_plan(s.b));
    // Skip what lies wholly outside the view (zoomed in on a big plan).
    if (std::max(line.x1(), line.x2()) < view.left() || std::min(line.x1(), line.x2()) > view.right() ||
        std::max(line.y1(), line.y2()) < view.top() || std::min(line.y1(), line.y2()) > view.bottom())
      continue;
    if (s.occluder)
      dark.push_back(line);
    else if (off_layers.count(s.layer))
      off.push_back(line);
    else
      light.push_back(line);
  }
  painter.setPen(QPen(QColor(205, 205, 205), 1.0, Qt::DotLine));
  painter.drawLines(off);
  painter.setPen(QPen(QColor(150, 150, 150), 1.0));
  painter.drawLines(light);
  painter.setPen(QPen(QColor(25, 30, 40), 2.5, Qt::SolidLine, Qt::RoundCap));
  painter.drawLines(dark);

  if (marked_) {
    const QPointF c = widget_from_plan(*marked_);
    painter.setPen(QPen(Qt::white, 1.5));
    painter.setBrush(QColor(210, 40, 40));
    painter.drawEllipse(c, 4.5, 4.5);
    painter.setBrush(Qt::NoBrush);
  }

  draw_scale_bar(painter);
  if (!note_.isEmpty()) {
    const QRect box = painter.fontMetrics()
                          .boundingRect(QRect(8, 6, width() - 16, height() / 2), Qt::TextWordWrap, note_)
                          .adjusted(-4, -2, 4, 2);
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(255, 255, 255, 220));
    painter.drawRoundedRect(box, 3, 3);
    painter.setPen(QColor(30, 30, 30));
    painter.drawText(QRect(8, 6, width() - 16, height() / 2), Qt::TextWordWrap, note_);
  }
}

void PlanPreview::draw_scale_bar(QPainter& painter) const {
  const double metres = scale_bar_metres();
  const double px = metres * scale_;
  const QFontMetrics fm = painter.fontMetrics();
  const QString label = metres_text(metres);
  const double x0 = 12, y = height() - 12;
  const QRectF back(x0 - 6, y - fm.height() - 10, std::max(px, double(fm.horizontalAdvance(label))) + 12,
                    fm.height() + 16);
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(255, 255, 255, 220));
  painter.drawRoundedRect(back, 3, 3);
  painter.setBrush(Qt::NoBrush);
  painter.setPen(QPen(QColor(20, 20, 20), 2.0, Qt::SolidLine, Qt::FlatCap));
  painter.drawLine(QPointF(x0, y), QPointF(x0 + px, y));
  painter.drawLine(QPointF(x0, y - 5), QPointF(x0, y + 1));
  painter.drawLine(QPointF(x0 + px, y - 5), QPointF(x0 + px, y + 1));
  painter.drawText(QPointF(x0, y - 7), label);
}

void PlanPreview::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps == 0.0) return;
  // Zoom about the cursor: the plan point under it stays under it.
  const QPointF at = event->position();
  const Eigen::Vector2d before = plan_from_widget(at);
  scale_ *= std::pow(1.25, steps);
  scale_ = std::clamp(scale_, 1e-6, 1e6);
  const Eigen::Vector2d after = plan_from_widget(at);
  centre_ += before - after;
  user_moved_ = true;
  update();
  event->accept();
}

void PlanPreview::mousePressEvent(QMouseEvent* event) {
  pressed_ = true;
  dragging_ = false;
  press_pos_ = last_pos_ = event->pos();
}

void PlanPreview::mouseMoveEvent(QMouseEvent* event) {
  if (!pressed_) return;
  if (!dragging_ && (event->pos() - press_pos_).manhattanLength() > kDragThreshold) {
    dragging_ = true;
    setCursor(Qt::ClosedHandCursor);
  }
  if (dragging_) {
    const QPoint d = event->pos() - last_pos_;
    centre_ += Eigen::Vector2d(-d.x() / scale_, d.y() / scale_);
    last_pos_ = event->pos();
    user_moved_ = true;
    update();
  }
}

void PlanPreview::mouseReleaseEvent(QMouseEvent* event) {
  const bool click = pressed_ && !dragging_ && event->button() == Qt::LeftButton;
  pressed_ = dragging_ = false;
  setCursor(Qt::CrossCursor);
  if (click && plan_ && !plan_->empty()) {
    const Eigen::Vector2d p = plan_from_widget(event->pos());
    set_marked_point(p);
    emit point_clicked(p);
  }
}

void PlanPreview::mouseDoubleClickEvent(QMouseEvent*) { fit(); }

}  // namespace plenopath::widgets
