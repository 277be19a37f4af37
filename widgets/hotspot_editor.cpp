#include "widgets/hotspot_editor.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPolygonF>
#include <QTimer>
#include <QTransform>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/hotspots/hotspot_geometry.h"
#include "processing/hotspots/hotspot_placement.h"
#include "processing/hotspots/hotspot_validation.h"
#include "widgets/hotspot_commands.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

constexpr double kHandleRadius = 9.0;  // widget pixels within which a press grabs a corner handle
constexpr double kClickSlop = 5.0;     // a press and release closer than this is a click, not a look-around
constexpr int kEdgeSteps = 16;         // samples per edge when drawing re-projected outlines
constexpr int kMaxMediaSide = 1024;    // preview media is scaled down to this
constexpr int kOverlayHeight = 512;    // whole-image mode: the media is warped into a 1024 x 512 overlay

const QColor kOutline(255, 200, 40);
const QColor kSelected(40, 220, 255);
const QColor kPending(255, 70, 70);

// The media (RGB888 preview) warped onto the quad in a whole equirectangular frame, transparent elsewhere:
// processing's warp_media_into_equirect paints the media and, separately, a white mask of the covered pixels.
QImage equirect_overlay(const QImage& media, const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                        double camera_height_m) {
  const QImage rgb = media.convertToFormat(QImage::Format_RGB888);
  cv::Mat media_bgr;
  cv::cvtColor(cv::Mat(rgb.height(), rgb.width(), CV_8UC3, const_cast<uchar*>(rgb.constBits()),
                       static_cast<std::size_t>(rgb.bytesPerLine())),
               media_bgr, cv::COLOR_RGB2BGR);
  cv::Mat canvas(kOverlayHeight, 2 * kOverlayHeight, CV_8UC3, cv::Scalar::all(0));
  cv::Mat mask = canvas.clone();
  warp_media_into_equirect(canvas, media_bgr, quad, pose, camera_height_m);
  warp_media_into_equirect(mask, cv::Mat(media_bgr.size(), CV_8UC3, cv::Scalar::all(255)), quad, pose,
                           camera_height_m);
  QImage out(canvas.cols, canvas.rows, QImage::Format_ARGB32);
  out.fill(Qt::transparent);
  for (int v = 0; v < canvas.rows; ++v)
    for (int u = 0; u < canvas.cols; ++u)
      if (mask.at<cv::Vec3b>(v, u)[0] > 0) {
        const cv::Vec3b c = canvas.at<cv::Vec3b>(v, u);
        out.setPixel(u, v, qRgba(c[2], c[1], c[0], mask.at<cv::Vec3b>(v, u)[0]));
      }
  return out;
}

QImage to_qimage(const cv::Mat& bgr) {
  cv::Mat small = bgr;
  const int side = std::max(bgr.cols, bgr.rows);
  if (side > kMaxMediaSide) {
    const double s = kMaxMediaSide / static_cast<double>(side);
    cv::resize(bgr, small, cv::Size(), s, s, cv::INTER_AREA);
  }
  cv::Mat rgb;
  if (small.channels() == 1)
    cv::cvtColor(small, rgb, cv::COLOR_GRAY2RGB);
  else if (small.channels() == 4)
    cv::cvtColor(small, rgb, cv::COLOR_BGRA2RGB);
  else
    cv::cvtColor(small, rgb, cv::COLOR_BGR2RGB);
  return QImage(rgb.data, rgb.cols, rgb.rows, static_cast<int>(rgb.step), QImage::Format_RGB888).copy();
}

}  // namespace

struct HotspotEditor::Video {
  cv::VideoCapture capture;
  double frame_rate = 25.0;
};

HotspotEditor::HotspotEditor(ProjectDocument& document, PanoramaView& view)
    : QObject(&view), document_(document), view_(view), video_timer_(new QTimer(this)) {
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (!(flags & kHotspotsChanged)) return;
    // The selection goes when its hotspot does (undo of a creation, delete).
    if (!selected_.empty() && find_hotspot(document_.project().hotspots, selected_) < 0) select("");
    // Media may have been re-picked: forget previews of files no hotspot uses.
    for (auto it = media_.begin(); it != media_.end();) {
      bool used = false;
      for (const Hotspot& h : document_.project().hotspots) used = used || h.media == it->first;
      if (used) {
        ++it;
      } else {
        videos_.erase(it->first);
        it = media_.erase(it);
      }
    }
  });
  connect(&document_, &ProjectDocument::current_position_changed, this, [this] {
    if (!pending_.empty()) {
      pending_.clear();
      emit status_message(tr("The frame changed: the corners marked so far are dropped; mark them again"));
    }
  });
  connect(video_timer_, &QTimer::timeout, this, &HotspotEditor::advance_videos);
}

HotspotEditor::~HotspotEditor() = default;

void HotspotEditor::set_mode(Mode mode) {
  pending_.clear();
  if (mode == mode_) {
    view_.update();
    return;
  }
  mode_ = mode;
  emit mode_changed(mode_);
  announce_mode();
  view_.update();
}

void HotspotEditor::announce_mode() {
  switch (mode_) {
    case Mode::kNewMovieTexture:
      emit status_message(
          tr("New movie texture: click the four corners of a TV, poster or window in the panorama "
             "(drag to look around, Esc cancels)"));
      break;
    case Mode::kNewEvent:
      emit status_message(
          tr("New event hotspot: click four corners for a quad, or Shift+click three or more and "
             "press Enter for a polygon (Esc cancels)"));
      break;
    case Mode::kIdle:
      emit status_message(QString());
      break;
  }
}

void HotspotEditor::select(const std::string& id) {
  if (id == selected_) return;
  selected_ = id;
  drag_corner_ = -1;
  emit selection_changed(QString::fromStdString(id));
  view_.update();
}

void HotspotEditor::show_hotspot(const std::string& id) {
  const Project& p = document_.project();
  const int i = find_hotspot(p.hotspots, id);
  select(i < 0 ? std::string() : id);
  if (i < 0) return;
  const Hotspot& h = p.hotspots[static_cast<std::size_t>(i)];
  const double height = camera_height_or_default(p.capture.camera_height_m);
  HotspotVisibilityOptions visibility;
  visibility.camera_height_m = height;
  const int position = position_to_show_hotspot(h, p.path, p.plan, document_.current_position(), visibility);
  if (position < 0) {
    if (p.path.empty() && h.frame >= 0)
      document_.set_current_position(h.frame);
    else
      emit status_message(tr("No frame on the path sees hotspot %1").arg(QString::fromStdString(h.title)));
  } else {
    document_.set_current_position(position);
  }
  // Face the hotspot's centre.
  SphericalAngles centre;
  const int now = document_.current_position();
  if (h.world_corners.size() >= 3 && now >= 0 && now < static_cast<int>(p.path.size())) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& w : h.world_corners) c += w / static_cast<double>(h.world_corners.size());
    centre = direction_in_frame(c, p.path.frames[static_cast<std::size_t>(now)], height);
  } else if (!h.image_corners.empty()) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& a : h.image_corners) sum += angles_to_bearing({a.x(), a.y()});
    centre = bearing_to_angles(sum);
  } else {
    return;
  }
  if (!view_.equirect_mode()) view_.set_look(centre.azimuth, centre.elevation, view_.fov());
}

bool HotspotEditor::delete_selected() {
  if (selected_.empty() || find_hotspot(document_.project().hotspots, selected_) < 0) return false;
  document_.undo_stack()->push(new RemoveHotspotCommand(document_, selected_));
  select("");
  return true;
}

void HotspotEditor::finish_pending() {
  if (mode_ == Mode::kIdle) return;
  if (pending_.size() < 3) {
    emit status_message(tr("A hotspot needs at least three corners (%1 so far)").arg(pending_.size()));
    return;
  }
  create_from_pending();
}

void HotspotEditor::add_corner(const SphericalAngles& direction, bool keep_going) {
  pending_.push_back(direction);
  const bool quad_done = pending_.size() == 4 && (mode_ == Mode::kNewMovieTexture || !keep_going);
  if (quad_done) {
    create_from_pending();
    return;
  }
  if (mode_ == Mode::kNewMovieTexture || !keep_going)
    emit status_message(tr("Corner %1 of 4 marked (Esc cancels)").arg(pending_.size()));
  else
    emit status_message(
        tr("Polygon corner %1 marked: Shift+click more, Enter finishes").arg(pending_.size()));
  view_.update();
}

void HotspotEditor::create_from_pending() {
  const Project& p = document_.project();
  const int position = document_.current_position();
  Hotspot h;
  h.id = unused_hotspot_id(p.hotspots);
  h.kind = mode_ == Mode::kNewMovieTexture ? HotspotKind::kMovieTexture : HotspotKind::kEvent;
  const QString kind_name = h.kind == HotspotKind::kMovieTexture ? tr("Movie texture") : tr("Event");
  h.title = QString("%1 %2").arg(kind_name).arg(QString::fromStdString(h.id).section('-', -1)).toStdString();
  h.frame = document_.frame_index_at(position);
  for (const auto& c : pending_) h.image_corners.push_back({c.azimuth, c.elevation});
  if (h.kind == HotspotKind::kEvent) {
    h.trigger = HotspotTrigger::kClick;
    h.action = HotspotAction::kShowText;
  }

  QString placement;
  if (!p.path.empty() && position >= 0 && position < static_cast<int>(p.path.size())) {
    const PathFrame& pose = p.path.frames[static_cast<std::size_t>(position)];
    HotspotPlacementOptions options;
    options.lift.camera_height_m = camera_height_or_default(p.capture.camera_height_m);
    try {
      PlacedQuad placed = place_hotspot_quad(pending_, pose, p.plan, cv::Mat(), options);
      const bool doubtful = placed.placement != HotspotPlacement::kWall || !placed.quad.warning.empty();
      if (doubtful && !p.capture.depth_folder.empty()) {
        // Depth only when the plan does not settle it: reading a depth map costs a decode.
        try {
          const auto source = FrameSource::open_capture(p.capture);
          const int index = p.capture.kept_of_frame_index(h.frame);
          if (index < 0) throw Error("frame " + std::to_string(h.frame) + " is not a kept frame");
          placed = place_hotspot_quad(pending_, pose, p.plan, source->read_depth(index), options);
        } catch (const Error& e) {
          placed.message += " (depth map not read: " + std::string(e.what()) + ")";
        }
      }
      h.world_corners = placed.quad.corners;
      placement = QString::fromStdString(placed.message);
    } catch (const Error& e) {
      placement = tr("not placed in 3-D (%1): it is shown in frame %2 only").arg(e.what()).arg(h.frame);
    }
  } else {
    placement = tr("no camera path yet: it is shown in frame %1 only").arg(h.frame);
  }
  last_message_ = tr("%1 “%2”: %3").arg(kind_name, QString::fromStdString(h.title), placement);
  const std::string id = h.id;
  pending_.clear();
  mode_ = Mode::kIdle;
  emit mode_changed(mode_);
  document_.undo_stack()->push(new AddHotspotCommand(document_, std::move(h)));
  select(id);
  emit status_message(last_message_);
  view_.update();
}

std::optional<HotspotEditor::Shown> HotspotEditor::shown(const Hotspot& h) const {
  const Project& p = document_.project();
  const int position = document_.current_position();
  const PathFrame* pose = (!p.path.empty() && position >= 0 && position < static_cast<int>(p.path.size()))
                              ? &p.path.frames[static_cast<std::size_t>(position)]
                              : nullptr;
  Shown s;
  s.hotspot = &h;
  const double width = view_.width();
  // Pieces of a polyline: broken where a point is behind the viewer or jumps across the image's seam.
  auto add_outline = [&](const std::vector<std::optional<QPointF>>& points) {
    std::vector<QPointF> piece;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const bool jump =
          k > 0 && points[k] && points[k - 1] && std::abs(points[k]->x() - points[k - 1]->x()) > 0.5 * width;
      if (!points[k] || jump) {
        if (piece.size() >= 2) s.outline.push_back(piece);
        piece.clear();
      }
      if (points[k]) piece.push_back(*points[k]);
    }
    if (piece.size() >= 2) s.outline.push_back(piece);
  };

  if (h.world_corners.size() >= 3 && pose) {
    const double height = camera_height_or_default(p.capture.camera_height_m);
    HotspotVisibilityOptions visibility;
    visibility.camera_height_m = height;
    if (!hotspot_visible_from(h.world_corners, *pose, p.plan, visibility, p.path.find_frame(h.frame)))
      return std::nullopt;
    for (const auto& w : h.world_corners) {
      const auto q = view_.widget_point_of(direction_in_frame(w, *pose, height));
      if (!q) return std::nullopt;  // a corner behind the viewer: not drawn in this look direction
      s.corners.push_back(*q);
    }
    std::vector<std::optional<QPointF>> points;
    const std::size_t n = h.world_corners.size();
    for (std::size_t i = 0; i <= n; ++i)
      for (int k = 0; k < (i < n ? kEdgeSteps : 1); ++k) {
        const Eigen::Vector3d a = h.world_corners[i % n], b = h.world_corners[(i + 1) % n];
        const Eigen::Vector3d w = a + (b - a) * (k / static_cast<double>(kEdgeSteps));
        points.push_back(view_.widget_point_of(direction_in_frame(w, *pose, height)));
      }
    add_outline(points);
    return s;
  }
  if (h.frame != document_.frame_index_at(position) || h.image_corners.size() < 2) return std::nullopt;
  for (const auto& c : h.image_corners) {
    const auto q = view_.widget_point_of({c.x(), c.y()});
    if (!q) return std::nullopt;
    s.corners.push_back(*q);
  }
  s.outline.push_back(s.corners);
  s.outline.back().push_back(s.corners.front());
  return s;
}

std::vector<HotspotEditor::Shown> HotspotEditor::shown_hotspots() const {
  std::vector<Shown> out;
  for (const Hotspot& h : document_.project().hotspots)
    if (auto s = shown(h)) out.push_back(std::move(*s));
  return out;
}

std::optional<std::vector<QPointF>> HotspotEditor::corner_points(const std::string& id) const {
  const int i = find_hotspot(document_.project().hotspots, id);
  if (i < 0) return std::nullopt;
  const auto s = shown(document_.project().hotspots[static_cast<std::size_t>(i)]);
  if (!s) return std::nullopt;
  return s->corners;
}

const QImage& HotspotEditor::media_image(const std::string& file) {
  auto it = media_.find(file);
  if (it != media_.end()) return it->second;
  QImage image;
  if (media_type_of(file) == "video") {
    auto video = std::make_unique<Video>();
    if (video->capture.open(file, cv::CAP_FFMPEG)) {
      cv::Mat frame;
      if (video->capture.read(frame) && !frame.empty()) image = to_qimage(frame);
      const double fps = video->capture.get(cv::CAP_PROP_FPS);
      if (fps > 1 && fps < 240) video->frame_rate = fps;
      videos_[file] = std::move(video);
    }
  } else if (!file.empty()) {
    const cv::Mat bgr = cv::imread(file, cv::IMREAD_COLOR);
    if (!bgr.empty()) image = to_qimage(bgr);
  }
  return media_.emplace(file, image).first->second;
}

void HotspotEditor::set_playing(bool playing) {
  playing_ = playing;
  if (!playing) {
    video_timer_->stop();
    return;
  }
  double fps = 25.0;
  for (const auto& [file, video] : videos_) fps = std::min(fps, video->frame_rate);
  video_timer_->start(static_cast<int>(1000.0 / std::clamp(fps, 5.0, 30.0)));
}

void HotspotEditor::advance_videos() {
  bool any = false;
  for (const Shown& s : shown_hotspots()) {
    const Hotspot& h = *s.hotspot;
    if (h.kind != HotspotKind::kMovieTexture) continue;
    media_image(h.media);  // opens the video when first seen
    auto it = videos_.find(h.media);
    if (it == videos_.end()) continue;
    cv::Mat frame;
    if (!it->second->capture.read(frame) || frame.empty()) {
      it->second->capture.set(cv::CAP_PROP_POS_FRAMES, 0);  // loop
      if (!it->second->capture.read(frame) || frame.empty()) continue;
    }
    media_[h.media] = to_qimage(frame);
    any = true;
  }
  if (any) view_.update();
}

bool HotspotEditor::mouse_press(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  press_point_ = event->localPos();
  if (mode_ != Mode::kIdle) {
    pressed_in_mode_ = true;
    return false;  // the view still looks around on a drag
  }
  pressed_in_mode_ = false;
  // A handle of the selected hotspot starts a corner drag.
  if (auto corners = corner_points(selected_)) {
    for (std::size_t i = 0; i < corners->size(); ++i) {
      const QPointF d = (*corners)[i] - event->localPos();
      if (std::hypot(d.x(), d.y()) <= kHandleRadius) {
        drag_corner_ = static_cast<int>(i);
        drag_session_ = new_hotspot_merge_session();
        return true;
      }
    }
  }
  // A press inside a hotspot selects it (the topmost: the last drawn).
  const std::vector<Shown> all = shown_hotspots();
  for (auto it = all.rbegin(); it != all.rend(); ++it)
    if (QPolygonF(QVector<QPointF>(it->corners.begin(), it->corners.end()))
            .containsPoint(event->localPos(), Qt::OddEvenFill)) {
      select(it->hotspot->id);
      return false;
    }
  return false;
}

bool HotspotEditor::mouse_move(QMouseEvent* event) {
  if (drag_corner_ < 0) return false;
  drag_corner_to(event->localPos());
  return true;
}

bool HotspotEditor::mouse_release(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  if (drag_corner_ >= 0) {
    drag_corner_to(event->localPos());
    drag_corner_ = -1;
    return true;
  }
  if (pressed_in_mode_ && mode_ != Mode::kIdle) {
    pressed_in_mode_ = false;
    const QPointF d = event->localPos() - press_point_;
    if (std::hypot(d.x(), d.y()) > kClickSlop) return false;  // that was a look-around drag
    if (const auto direction = view_.direction_at(event->localPos()))
      add_corner(*direction, event->modifiers() & Qt::ShiftModifier);
    return true;
  }
  return false;
}

bool HotspotEditor::mouse_double_click(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || mode_ != Mode::kNewEvent || pending_.size() < 3) return false;
  finish_pending();
  return true;
}

bool HotspotEditor::key_press(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_Escape:
      if (mode_ == Mode::kIdle && pending_.empty()) {
        if (selected_.empty()) return false;
        select("");
        return true;
      }
      set_mode(Mode::kIdle);
      emit status_message(tr("Cancelled: no hotspot made"));
      return true;
    case Qt::Key_Delete:
    case Qt::Key_Backspace:
      return mode_ == Mode::kIdle && delete_selected();
    case Qt::Key_Return:
    case Qt::Key_Enter:
      if (mode_ == Mode::kIdle) return false;
      finish_pending();
      return true;
    default:
      return false;
  }
}

void HotspotEditor::drag_corner_to(const QPointF& widget_point) {
  const Project& p = document_.project();
  const int index = find_hotspot(p.hotspots, selected_);
  const auto direction = view_.direction_at(widget_point);
  if (index < 0 || !direction) return;
  Hotspot h = p.hotspots[static_cast<std::size_t>(index)];
  const std::size_t corner = static_cast<std::size_t>(drag_corner_);
  const int position = document_.current_position();
  const bool on_path = !p.path.empty() && position >= 0 && position < static_cast<int>(p.path.size());
  const double height = camera_height_or_default(p.capture.camera_height_m);
  if (h.world_corners.size() >= 3 && corner < h.world_corners.size() && on_path) {
    const PathFrame& pose = p.path.frames[static_cast<std::size_t>(position)];
    try {
      h.world_corners[corner] = point_on_quad_plane(h.world_corners, *direction, pose, height);
    } catch (const Error& e) {
      emit status_message(tr("The corner cannot go there: %1").arg(e.what()));
      return;
    }
    // Keep the marks in the authoring frame in step with the 3-D corner.
    if (const PathFrame* authoring = p.path.find_frame(h.frame);
        authoring && corner < h.image_corners.size()) {
      const SphericalAngles a = direction_in_frame(h.world_corners[corner], *authoring, height);
      h.image_corners[corner] = {a.azimuth, a.elevation};
    }
  } else if (h.frame == document_.frame_index_at(position) && corner < h.image_corners.size()) {
    h.image_corners[corner] = {direction->azimuth, direction->elevation};
  } else {
    return;
  }
  document_.undo_stack()->push(
      new EditHotspotCommand(document_, std::move(h), tr("Move hotspot corner"), drag_session_));
}

void HotspotEditor::paint(QPainter& painter) {
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setRenderHint(QPainter::SmoothPixmapTransform);
  for (const Shown& s : shown_hotspots()) {
    const Hotspot& h = *s.hotspot;
    const bool selected = h.id == selected_;
    const QPolygonF polygon(QVector<QPointF>(s.corners.begin(), s.corners.end()));
    bool textured = false;
    // Whole-image mode: the media warped into the equirectangular frame on the CPU (curved edges and all).
    if (h.kind == HotspotKind::kMovieTexture && h.world_corners.size() == 4 && view_.equirect_mode() &&
        !h.media.empty() && !media_image(h.media).isNull()) {
      const Project& p = document_.project();
      const int position = document_.current_position();
      if (position >= 0 && position < static_cast<int>(p.path.size())) {
        try {
          painter.drawImage(view_.image_box(),
                            equirect_overlay(media_image(h.media), h.world_corners,
                                             p.path.frames[static_cast<std::size_t>(position)],
                                             camera_height_or_default(p.capture.camera_height_m)));
          textured = true;
        } catch (const Error&) {
          // A degenerate quad: outlined only.
        }
      }
    }
    // Movie texture preview: the media mapped onto the quad by the view's homography (exact for a planar
    // quad seen through a pinhole view).
    if (h.kind == HotspotKind::kMovieTexture && s.corners.size() == 4 && !view_.equirect_mode() &&
        !h.media.empty()) {
      const QImage& image = media_image(h.media);
      QTransform transform;
      // Media corners in the order of the quad's: (0, 0), (w, 0), (w, h), (0, h) (four points:
      // QPolygonF(QRectF) would close the ring with a fifth, which quadToQuad refuses).
      const QPolygonF media_corners({QPointF(0, 0), QPointF(image.width(), 0),
                                     QPointF(image.width(), image.height()), QPointF(0, image.height())});
      if (!image.isNull() && QTransform::quadToQuad(media_corners, polygon, transform)) {
        painter.save();
        painter.setTransform(transform, true);
        painter.drawImage(QPointF(0, 0), image);
        painter.restore();
        textured = true;
      }
    }
    const QColor colour = selected ? kSelected : kOutline;
    if (!textured) {
      painter.setPen(Qt::NoPen);
      painter.setBrush(QColor(colour.red(), colour.green(), colour.blue(), 50));
      painter.drawPolygon(polygon);
    }
    painter.setPen(QPen(colour, selected ? 3 : 2));
    painter.setBrush(Qt::NoBrush);
    for (const auto& piece : s.outline)
      painter.drawPolyline(QPolygonF(QVector<QPointF>(piece.begin(), piece.end())));
    // Author text is drawn as text (QPainter never interprets markup).
    painter.drawText(polygon.boundingRect().topLeft() + QPointF(4, -4), QString::fromStdString(h.title));
    if (selected && mode_ == Mode::kIdle) {
      painter.setPen(QPen(Qt::black, 1));
      painter.setBrush(Qt::white);
      for (const QPointF& c : s.corners) painter.drawRect(QRectF(c - QPointF(4.5, 4.5), QSizeF(9, 9)));
    }
  }
  // The hotspot being marked.
  if (!pending_.empty()) {
    std::vector<QPointF> points;
    for (const auto& c : pending_)
      if (const auto q = view_.widget_point_of(c)) points.push_back(*q);
    painter.setPen(QPen(kPending, 2, Qt::DashLine));
    painter.setBrush(Qt::NoBrush);
    if (points.size() >= 2) painter.drawPolyline(QPolygonF(QVector<QPointF>(points.begin(), points.end())));
    painter.setPen(QPen(Qt::white, 1));
    painter.setBrush(kPending);
    for (std::size_t i = 0; i < points.size(); ++i) {
      painter.drawEllipse(points[i], 5.0, 5.0);
      painter.drawText(points[i] + QPointF(7, -7), QString::number(i + 1));
    }
  }
  if (mode_ != Mode::kIdle) {
    const QString hint = mode_ == Mode::kNewMovieTexture
                             ? tr("New movie texture: corner %1 of 4").arg(pending_.size() + 1)
                             : tr("New event hotspot: corner %1").arg(pending_.size() + 1);
    painter.setPen(Qt::white);
    const QRectF box(8, 8, painter.fontMetrics().horizontalAdvance(hint) + 16, 22);
    painter.fillRect(box, QColor(200, 40, 40, 170));
    painter.drawText(box, Qt::AlignCenter, hint);
  }
  painter.restore();
}

}  // namespace plenopath::widgets
