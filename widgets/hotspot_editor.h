#pragma once
// Hotspot authoring in the panorama view: the "new movie texture" / "new event hotspot" modes (clicks mark
// corners in the current frame; the quad is lifted to 3-D by processing/hotspots/hotspot_placement.h), the
// selection shared with the hotspots panel, corner handles that drag (one undo step per drag), Esc to cancel,
// Delete to remove; and the overlay: every hotspot re-projected into the current frame where it is visible,
// movie textures previewed with their media warped onto the quad.
// The view forwards its mouse and key events here first; what this does not use, the view handles.
#include <QImage>
#include <QObject>
#include <QPointF>
#include <QString>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/hotspots.h"
#include "rig/spherical.h"

class QKeyEvent;
class QMouseEvent;
class QPainter;
class QTimer;

namespace plenopath::widgets {

class PanoramaView;
class ProjectDocument;

class HotspotEditor : public QObject {
  Q_OBJECT
 public:
  enum class Mode { kIdle, kNewMovieTexture, kNewEvent };

  HotspotEditor(ProjectDocument& document, PanoramaView& view);
  ~HotspotEditor() override;

  Mode mode() const { return mode_; }
  // Starts marking a new hotspot of that kind (kIdle cancels a half-made one).
  void set_mode(Mode mode);
  // Corners clicked so far for the hotspot being made.
  const std::vector<SphericalAngles>& pending_corners() const { return pending_; }
  // Ends a hotspot being marked now (Enter): needs at least three corners.
  void finish_pending();

  // The selected hotspot's id ("" = none).
  const std::string& selected() const { return selected_; }
  void select(const std::string& id);
  // Selects the hotspot, moves to a frame that sees it (its authoring frame when on the path) and turns the
  // view towards it.
  void show_hotspot(const std::string& id);
  // Removes the selected hotspot (one undo step); false when nothing is selected.
  bool delete_selected();

  // Where the corners of hotspot `id` are drawn in the current view (widget pixels), when it is shown.
  std::optional<std::vector<QPointF>> corner_points(const std::string& id) const;
  // What the last placement did (status bar text), e.g. "snapped to the wall ...".
  const QString& last_message() const { return last_message_; }

  // Media preview: the picked image, or a video's current frame. Videos play while `playing`.
  void set_playing(bool playing);
  bool playing() const { return playing_; }

  // Forwarded by the view; true when used.
  bool mouse_press(QMouseEvent* event);
  bool mouse_move(QMouseEvent* event);
  bool mouse_release(QMouseEvent* event);
  bool mouse_double_click(QMouseEvent* event);
  bool key_press(QKeyEvent* event);
  // Draws the hotspots, handles and the hotspot being marked.
  void paint(QPainter& painter);

 signals:
  void mode_changed(Mode mode);
  void selection_changed(const QString& id);
  // A hint or a result for the status bar.
  void status_message(const QString& message);

 private:
  struct Shown {
    const Hotspot* hotspot = nullptr;
    std::vector<QPointF> corners;  // widget pixels, one per corner
    std::vector<std::vector<QPointF>>
        outline;  // polyline pieces along the edges (curved in whole-image mode)
  };
  std::vector<Shown> shown_hotspots() const;
  std::optional<Shown> shown(const Hotspot& h) const;
  void add_corner(const SphericalAngles& direction, bool keep_going);
  void create_from_pending();
  void drag_corner_to(const QPointF& widget_point);
  const QImage& media_image(const std::string& file);
  void advance_videos();
  void announce_mode();

  ProjectDocument& document_;
  PanoramaView& view_;
  Mode mode_ = Mode::kIdle;
  std::vector<SphericalAngles> pending_;
  std::string selected_;
  QString last_message_;
  // A corner drag in progress.
  int drag_corner_ = -1;
  int drag_session_ = 0;
  QPointF press_point_;
  bool pressed_in_mode_ = false;
  // Decoded media by file (null image = unreadable), and open videos for playback.
  std::map<std::string, QImage> media_;
  struct Video;
  std::map<std::string, std::unique_ptr<Video>> videos_;
  QTimer* video_timer_;
  bool playing_ = false;
};

}  // namespace plenopath::widgets
