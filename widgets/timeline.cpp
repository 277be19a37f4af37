#include "widgets/timeline.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QStyle>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "widgets/map_pieces.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

TimelineStrip::TimelineStrip(ProjectDocument& document, QWidget* parent)
    : QWidget(parent), document_(document) {
  setMinimumHeight(80);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Preferred);
  connect(&document_, &ProjectDocument::changed, this, [this] { update(); });
  connect(&document_, &ProjectDocument::current_position_changed, this, [this] { update(); });
}

QRectF TimelineStrip::plot_rect() const { return QRectF(8, 6, width() - 16, height() - 22); }

int TimelineStrip::position_at(double x) const {
  const int n = document_.frame_count();
  if (n <= 1) return 0;
  const QRectF r = plot_rect();
  return std::clamp(static_cast<int>(std::lround((x - r.left()) / r.width() * (n - 1))), 0, n - 1);
}

double TimelineStrip::x_of(int position) const {
  const int n = document_.frame_count();
  const QRectF r = plot_rect();
  return n <= 1 ? r.left() : r.left() + r.width() * position / (n - 1.0);
}

void TimelineStrip::set_profiles(QVector<double> envelope_area, QVector<double> depth_volume) {
  envelope_area_ = std::move(envelope_area);
  depth_volume_ = std::move(depth_volume);
  update();
}

void TimelineStrip::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.fillRect(rect(), palette().base());
  const QRectF r = plot_rect();
  const Project& p = document_.project();
  const int n = document_.frame_count();
  if (n == 0) {
    painter.setPen(palette().color(QPalette::PlaceholderText));
    painter.drawText(rect(), Qt::AlignCenter, tr("No frames yet"));
    return;
  }
  // Cell bands: a light band per cell across the plot, a saturated strip along the bottom.
  double max_area = 0.0;
  for (const VisibilityCell& c : p.visibility.cells) max_area = std::max(max_area, c.area_mean);
  for (std::size_t k = 0; k < p.visibility.cells.size(); ++k) {
    const VisibilityCell& c = p.visibility.cells[k];
    const int a = document_.position_of_frame_index(c.first_frame);
    const int b = document_.position_of_frame_index(c.last_frame);
    if (a < 0 || b < 0) continue;
    const auto rgb = cell_colour(static_cast<int>(k));
    const QColor colour(rgb[0], rgb[1], rgb[2]);
    const double x0 = x_of(a), x1 = std::max(x_of(b), x0 + 1.0);
    QColor light = colour;
    light.setAlpha(40);
    painter.fillRect(QRectF(x0, r.top(), x1 - x0, r.height()), light);
    painter.fillRect(QRectF(x0, r.bottom() - 6, x1 - x0, 6), colour);
    // Envelope area of the cell as a step of the plot.
    if (max_area > 0) {
      const double y = r.bottom() - 8 - (r.height() - 12) * c.area_mean / max_area;
      painter.setPen(QPen(colour.darker(130), 2));
      painter.drawLine(QPointF(x0, y), QPointF(x1, y));
    }
  }
  // A path in pieces: each piece's span in its colour along the very bottom, a break as a red tick with the
  // piece's number (an unplaced piece's band hatched).
  if (p.path.piece_count() > 1 && p.path.size() == static_cast<std::size_t>(n)) {
    for (int i = 0; i < n;) {
      const int piece = p.path.frames[static_cast<std::size_t>(i)].piece;
      int j = i;
      while (j + 1 < n && p.path.frames[static_cast<std::size_t>(j + 1)].piece == piece) ++j;
      const auto rgb = piece_colour(piece);
      const QColor colour(rgb[0], rgb[1], rgb[2]);
      const double x0 = x_of(i), x1 = std::max(x_of(j), x0 + 2.0);
      const QRectF band(x0, r.bottom() - 3, x1 - x0, 3);
      painter.fillRect(band, p.path.piece_placed(piece) ? QBrush(colour) : QBrush(colour, Qt::BDiagPattern));
      if (i > 0) {
        painter.setPen(QPen(QColor(200, 0, 0), 2));
        painter.drawLine(QPointF(x0, r.top()), QPointF(x0, r.bottom()));
        painter.drawText(QPointF(x0 + 3, r.bottom() - 6), tr("piece %1").arg(piece));
      }
      i = j + 1;
    }
  }
  // Frames the tracker flagged (bridged, moving objects, stopped, ...): amber marks along the top, one run
  // of consecutive flagged frames as one bar.
  if (p.path.size() == static_cast<std::size_t>(n)) {
    const QColor amber(240, 150, 0);
    for (int i = 0; i < n;) {
      if (p.path.frames[static_cast<std::size_t>(i)].flags == kFrameOk) {
        ++i;
        continue;
      }
      int j = i;
      while (j + 1 < n && p.path.frames[static_cast<std::size_t>(j + 1)].flags != kFrameOk) ++j;
      const double x0 = x_of(i) - 1.0, x1 = std::max(x_of(j) + 1.0, x0 + 3.0);
      painter.fillRect(QRectF(x0, r.top(), x1 - x0, 5), amber);
      i = j + 1;
    }
  }
  // Per-frame curves, each scaled to its maximum.
  QVector<QPair<QString, QColor>> legend;
  auto plot = [&](const QVector<double>& series, const QColor& colour, const QString& name,
                  const QString& unit) {
    if (series.size() != n) return;
    const double top = *std::max_element(series.begin(), series.end());
    if (!(top > 0)) return;
    QPainterPath curve;
    auto y_of = [&](double v) { return r.bottom() - 8 - (r.height() - 14) * v / top; };
    auto add = [&curve](const QPointF& q) {
      if (curve.elementCount() == 0)
        curve.moveTo(q);
      else
        curve.lineTo(q);
    };
    const int columns = std::max(1, static_cast<int>(r.width()));
    if (n <= 2 * columns) {
      for (int i = 0; i < n; ++i) add(QPointF(x_of(i), y_of(series[i])));
    } else {
      // More frames than pixels (20 000 frames: stroking every vertex took ~60 ms of the GUI thread): per
      // pixel column its lowest and highest value, in the order they come, which draws the same picture.
      for (int i = 0; i < n;) {
        const int column = static_cast<int>(x_of(i) - r.left());
        int j = i, low = i, high = i;
        while (j + 1 < n && static_cast<int>(x_of(j + 1) - r.left()) == column) {
          ++j;
          if (series[j] < series[low]) low = j;
          if (series[j] > series[high]) high = j;
        }
        const double x = r.left() + column + 0.5;
        add(QPointF(x, y_of(series[std::min(low, high)])));
        if (low != high) add(QPointF(x, y_of(series[std::max(low, high)])));
        i = j + 1;
      }
    }
    painter.setPen(QPen(colour, 1.6));
    painter.setBrush(Qt::NoBrush);
    painter.drawPath(curve);
    legend.append({QString("%1 (max %2 %3)").arg(name).arg(top, 0, 'f', 0).arg(unit), colour});
  };
  plot(envelope_area_, QColor(40, 110, 200), tr("envelope area"), tr("m²"));
  plot(depth_volume_, QColor(30, 150, 80), tr("depth volume"), tr("m³"));
  if (!legend.isEmpty()) {
    double x = r.left() + 4;
    for (const auto& [text, colour] : legend) {
      painter.setPen(colour);
      painter.drawText(QPointF(x, r.top() + painter.fontMetrics().ascent() + 2), "― " + text);
      x += painter.fontMetrics().horizontalAdvance("― " + text) + 18;
    }
  } else if (max_area > 0) {
    painter.setPen(palette().color(QPalette::Text));
    painter.drawText(r.adjusted(4, 2, 0, 0), Qt::AlignLeft | Qt::AlignTop,
                     tr("cell envelope area (max %1 m²)").arg(max_area, 0, 'f', 0));
  } else if (p.visibility.cells.empty()) {
    painter.setPen(palette().color(QPalette::PlaceholderText));
    painter.drawText(r.adjusted(4, 2, 0, 0), Qt::AlignLeft | Qt::AlignTop,
                     tr("no visibility cells yet (Process ▸ Compute visibility)"));
  }
  // Keyframe ticks.
  painter.setPen(QPen(QColor(210, 30, 40), 1.5));
  for (int index : p.keyframes.indices) {
    const int position = document_.position_of_frame_index(index);
    if (position < 0) continue;
    const double x = x_of(position);
    painter.drawLine(QPointF(x, r.bottom() + 1), QPointF(x, r.bottom() + 12));
  }
  // Frame axis.
  painter.setPen(palette().color(QPalette::Mid));
  painter.drawLine(QPointF(r.left(), r.bottom()), QPointF(r.right(), r.bottom()));
  // Play head.
  const double x = x_of(document_.current_position());
  painter.setPen(QPen(palette().color(QPalette::Highlight), 2));
  painter.drawLine(QPointF(x, 0), QPointF(x, height()));
}

void TimelineStrip::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) document_.set_current_position(position_at(event->pos().x()));
}

void TimelineStrip::mouseMoveEvent(QMouseEvent* event) {
  if (event->buttons() & Qt::LeftButton) document_.set_current_position(position_at(event->pos().x()));
}

TimelinePanel::TimelinePanel(ProjectDocument& document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      strip_(new TimelineStrip(document, this)),
      play_(new QToolButton(this)),
      frame_box_(new QSpinBox(this)),
      info_(new QLabel(this)),
      play_timer_(new QTimer(this)) {
  play_->setCheckable(true);
  play_->setIcon(style()->standardIcon(QStyle::SP_MediaPlay));
  play_->setToolTip(tr("Play at the capture's frame rate (Space)"));
  play_->setShortcut(Qt::Key_Space);
  frame_box_->setToolTip(tr("Current frame (position along the path)"));
  auto* controls = new QHBoxLayout;
  controls->addWidget(play_);
  controls->addWidget(frame_box_);
  controls->addWidget(info_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  layout->addLayout(controls);
  layout->addWidget(strip_, 1);

  connect(play_, &QToolButton::toggled, this, &TimelinePanel::set_playing);
  connect(frame_box_, qOverload<int>(&QSpinBox::valueChanged), this,
          [this](int value) { document_.set_current_position(value); });
  connect(play_timer_, &QTimer::timeout, this, [this] {
    if (document_.current_position() + 1 >= document_.frame_count()) {
      set_playing(false);
      return;
    }
    document_.step(1);
  });
  connect(&document_, &ProjectDocument::changed, this, [this] { update_controls(); });
  connect(&document_, &ProjectDocument::current_position_changed, this, [this] { update_controls(); });
  update_controls();
}

void TimelinePanel::set_playing(bool playing) {
  if (playing) {
    if (document_.current_position() + 1 >= document_.frame_count()) document_.set_current_position(0);
    const double rate =
        document_.project().capture.frame_rate > 0 ? document_.project().capture.frame_rate : 30.0;
    play_timer_->start(static_cast<int>(std::lround(1000.0 / rate)));
  } else {
    play_timer_->stop();
  }
  const QSignalBlocker block(play_);
  play_->setChecked(playing);
  play_->setIcon(style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
}

bool TimelinePanel::playing() const { return play_timer_->isActive(); }

int TimelinePanel::play_interval_ms() const { return play_timer_->interval(); }

QString TimelinePanel::info_text() const { return info_->text(); }

void TimelinePanel::update_controls() {
  const int n = document_.frame_count();
  const int position = document_.current_position();
  {
    const QSignalBlocker block(frame_box_);
    frame_box_->setRange(0, std::max(0, n - 1));
    frame_box_->setValue(position);
  }
  const Project& p = document_.project();
  const double rate = p.capture.frame_rate > 0 ? p.capture.frame_rate : 30.0;
  // The frame's own time: variable-rate video is not evenly spaced at the rate.
  const double time_s = p.capture.frame_times_s.empty()
                            ? position / rate
                            : p.capture.frame_time_s(position) - p.capture.frame_time_s(0);
  QString text = tr("of %1 · %2 s").arg(n).arg(time_s, 0, 'f', 2);
  if (!p.path.empty() && position < static_cast<int>(p.path.size())) {
    const std::vector<double> s = p.path.arc_lengths();
    text += tr(" · %1 m of %2 m").arg(s[position], 0, 'f', 1).arg(s.back(), 0, 'f', 1);
  }
  text += tr(" · %1 keyframes").arg(p.keyframes.indices.size());
  int flagged = 0;
  for (const PathFrame& f : p.path.frames) flagged += f.flags != kFrameOk;
  if (flagged > 0) text += tr(" · %1 flagged").arg(flagged);
  if (p.path.piece_count() > 1) {
    int unplaced = 0;
    for (int k = 0; k < p.path.piece_count(); ++k) unplaced += !p.path.piece_placed(k);
    text += tr(" · %1 pieces (%2 unplaced)").arg(p.path.piece_count()).arg(unplaced);
  }
  QString reason;
  if (position >= 0 && position < static_cast<int>(p.path.size())) {
    const PathFrame& f = p.path.frames[static_cast<std::size_t>(position)];
    if (f.flags != kFrameOk)
      reason = f.reason.empty() ? tr("flagged by the tracker") : QString::fromStdString(f.reason);
  }
  if (!reason.isEmpty()) text += tr(" · this frame: %1").arg(reason);
  info_->setText(text);
  info_->setToolTip(reason.isEmpty()
                        ? QString()
                        : tr("The tracker flagged this frame: %1. Its pose may be interpolated or "
                             "less certain; an anchor (Ctrl+drag on the map) can pin it.")
                              .arg(reason));
}

}  // namespace plenopath::widgets
