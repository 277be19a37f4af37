#pragma once
// The map: the floor plan seen from above (VTK, parallel projection). Layers in their colours with occluders
// drawn dark and thick, the path coloured by visibility cell, the cells' critical lines, keyframes as
// markers, and the current frame with its envelope (visibility polygon) and the panorama view's cone.
// Left drag pans, the wheel (or right drag) zooms, a click on the path goes to the nearest frame.
// Drift anchors: Ctrl + left drag from any frame of the path puts that frame where it really was (Shift held
// at the same time snaps to the nearest plan corner within a few pixels); a plain left drag on an anchor
// marker moves it; Esc cancels a drag. While dragging, the whole path is previewed bent by the anchors (the
// fast warp, about a millisecond for 30 000 frames); the release asks the document's AnchorEditor
// (widgets/anchor_editor.h) to refine the path with all anchors on a worker, the preview staying drawn
// until the result lands as one undo step (widgets/anchor_commands.h). Anchors are magenta squares, each
// with a thin line to where its frame is on the path (the residual).
// Placement ghosts: other placements registration found for a piece of the path (issue 19), drawn as thin
// violet lines with their rank and score; a click on one asks for it (placement_clicked).
// Point picking (Process > Place still on plan): after start_point_pick the next plain click anywhere on
// the map gives its plan point (point_picked) instead of going to a frame; Esc gives up
// (point_pick_cancelled).
// Waypoint drawing (Process > Render CG scene, Draw on plan): after start_waypoint_drawing each plain click
// adds a waypoint, drawn as a green polyline with a rubber band to the cursor (legs that cross a wall of the
// plan in red); Backspace removes the last, Enter or a double-click finishes (waypoints_drawn), Esc cancels
// (waypoints_cancelled). A left drag still pans, the wheel still zooms. Renders are requested and
// coalesced (one per event-loop turn), never forced by the model.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "processing/plan/segment_grid.h"

class QTimer;
class vtkActor;
class vtkRenderer;
class vtkTextActor;

namespace plenopath::widgets {

class ProjectDocument;

// The envelope polygon of a plan point (counter-clockwise, metres), empty when there is none. Set by the
// application once a visibility index exists for the current plan.
using EnvelopeFunction = std::function<std::vector<Eigen::Vector2d>(const Eigen::Vector2d&)>;

// Another placement of one piece of the path, as the map draws it.
struct MapPlacementGhost {
  std::vector<Eigen::Vector2d> polyline;  // the piece's frames at that placement, plan metres
  std::string label;                      // "2 · score 0.71"
  int piece = 0;
  int candidate = 0;  // index into that piece's registration candidates
};

class MapView : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  explicit MapView(ProjectDocument& document, QWidget* parent = nullptr);
  ~MapView() override;

  void set_envelope_function(EnvelopeFunction function);
  // Fits the camera to the plan and path.
  void reset_camera();
  // Asks for one render on the next event-loop turn (many requests make one render).
  void request_render();
  // Renders now (tests and screenshots).
  void render_now();

  // Plan point under a widget pixel.
  Eigen::Vector2d plan_point_at(const QPoint& widget_pixel);
  // Widget pixel of a plan point.
  QPoint widget_pixel_of(const Eigen::Vector2d& plan_point);

  // How to place anchors, as the tooltip and the status bar say it.
  static QString anchor_hint();
  bool is_dragging_anchor() const { return drag_.active; }
  // The path as drawn: the document's (or the drag's preview), unplaced pieces in the tray beside the plan.
  const CameraPath& drawn_path() const { return drawn_path_; }
  // The path as previewed during an anchor drag (empty when not dragging).
  const CameraPath& anchor_preview() const { return drag_.preview; }

  // Replaces the placement ghosts (empty: none).
  void set_placement_ghosts(std::vector<MapPlacementGhost> ghosts);
  const std::vector<MapPlacementGhost>& placement_ghosts() const { return ghosts_; }
  // The next plain click gives a plan point (see above); `hint` goes to the status bar.
  void start_point_pick(const QString& hint);
  void cancel_point_pick();
  bool is_picking_point() const { return picking_point_; }

  // Waypoint drawing (see above); `hint` goes to the top of the map (its lines as they are) and to the
  // status bar (on one line).
  void start_waypoint_drawing(const QString& hint);
  void cancel_waypoint_drawing();
  bool is_drawing_waypoints() const { return drawing_waypoints_; }
  // The waypoints clicked so far (plan metres).
  const std::vector<Eigen::Vector2d>& drawn_waypoints() const { return waypoints_; }
  // How many legs of the waypoints so far cross a sight-blocking segment of the plan.
  int waypoint_legs_crossing_walls() const;

  // Index into placement_ghosts() of the ghost nearest `pixel` within `radius_px`, or -1.
  int placement_ghost_near(const QPoint& pixel, double radius_px);

 signals:
  // The user clicked on the path near the frame at `position` (the document has already moved there).
  void frame_clicked(int position);
  // A short message for the status bar (what a drag does, or why an anchor could not be placed).
  void message(const QString& text);
  // The user clicked on a placement ghost (nearer than the path): candidate `candidate` of piece `piece`.
  void placement_clicked(int piece, int candidate);
  // Point picking: the plan point clicked (metres), or Esc.
  void point_picked(double x, double y);
  void point_pick_cancelled();
  // Waypoint drawing: finished with these waypoints (two or more, plan metres), or cancelled.
  void waypoints_drawn(const std::vector<Eigen::Vector2d>& waypoints);
  void waypoints_cancelled();

 protected:
  bool event(QEvent* event) override;

 private:
  void on_document_changed(unsigned flags);
  void rebuild_plan();
  void rebuild_path();
  void set_path_geometry(const CameraPath& path);
  void rebuild_keyframes();
  void rebuild_current();
  void rebuild_anchors(const CameraPath& path, const Anchors& anchors);
  void handle_click(const QPoint& pixel);
  double metres_per_pixel() const;
  // Position (into path.frames) of the frame nearest `pixel` within `radius_px`, or -1.
  int frame_near(const QPoint& pixel, double radius_px);
  // Frame index of the anchor marker nearest `pixel` within `radius_px`, or -1.
  int anchor_near(const QPoint& pixel, double radius_px);
  // The plan point under `pixel`, snapped to the nearest segment end of a visible layer when `snap`.
  Eigen::Vector2d anchor_target(const QPoint& pixel, bool snap, bool* snapped);
  bool handle_anchor_event(QEvent* event);
  void update_anchor_drag(const QPoint& pixel, bool snap);
  void end_anchor_drag(bool apply);
  // The hint at the top of the map (anchoring, pieces, or the waypoint drawing's keys).
  void update_hint();
  // Returns true when the event belonged to waypoint drawing (clicks, keys, the rubber band).
  bool handle_waypoint_event(QEvent* event);
  void finish_waypoint_drawing();
  void end_waypoint_drawing();
  void rebuild_waypoints();

  // An anchor drag in progress.
  struct AnchorDrag {
    bool active = false;
    int frame = -1;  // capture index of the dragged frame
    QPoint press_pixel;
    bool moved = false;
    Eigen::Vector2d target = Eigen::Vector2d::Zero();
    bool snapped = false;
    bool valid = false;              // the preview could be computed
    Anchors anchors;                 // the document's anchors with the dragged one moved
    CameraPath preview;              // the path bent by them
    bool ghost_drawn = false;        // the path before the drag is drawn (once per drag)
    QPoint previewed_pixel{-1, -1};  // where the preview was last computed, and with which snap
    bool previewed_snap = false;
  };

  ProjectDocument& document_;
  EnvelopeFunction envelope_function_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> plan_actor_;
  vtkSmartPointer<vtkActor> occluder_actor_;
  vtkSmartPointer<vtkActor> opening_actor_;  // the outer walls' gaps visibility closes (glass blue)
  std::vector<Segment2> openings_;           // of the plan at openings_revision_
  unsigned openings_revision_ = ~0u;
  vtkSmartPointer<vtkActor> critical_actor_;
  vtkSmartPointer<vtkActor> path_actor_;
  vtkSmartPointer<vtkActor> keyframe_actor_;
  vtkSmartPointer<vtkActor> current_actor_;
  vtkSmartPointer<vtkActor> envelope_actor_;
  vtkSmartPointer<vtkActor> cone_actor_;
  vtkSmartPointer<vtkActor> ghost_path_actor_;  // the path before the drag, while dragging
  vtkSmartPointer<vtkActor> residual_actor_;
  vtkSmartPointer<vtkActor> anchor_actor_;
  vtkSmartPointer<vtkActor> anchor_core_actor_;
  vtkSmartPointer<vtkActor> hotspot_actor_;                      // hotspots (widgets/map_hotspot_markers.h)
  vtkSmartPointer<vtkActor> placement_actor_;                    // placement ghosts
  std::vector<vtkSmartPointer<vtkTextActor>> placement_labels_;  // their labels, at the plan point
  std::vector<MapPlacementGhost> ghosts_;
  vtkSmartPointer<vtkTextActor> caption_;
  vtkSmartPointer<vtkTextActor> hint_;
  std::vector<int> path_cells_;  // visibility cell of each path position (colours)
  CameraPath drawn_path_;        // the path as drawn: unplaced pieces in the tray (widgets/map_pieces.h)
  AnchorDrag drag_;
  QTimer* render_timer_;
  QPoint press_pixel_;
  bool picking_point_ = false;
  bool camera_fitted_ = false;
  // Waypoint drawing.
  bool drawing_waypoints_ = false;
  bool swallow_release_ = false;  // the release that ends a double-click is no click
  QString waypoint_hint_;
  std::vector<Eigen::Vector2d> waypoints_;
  std::vector<char> waypoint_leg_crosses_;   // per leg: it crosses a wall
  std::vector<PlanSegment> waypoint_walls_;  // the plan's sight-blocking segments, while drawing
  bool cursor_on_map_ = false;
  Eigen::Vector2d cursor_ = Eigen::Vector2d::Zero();  // plan point under the cursor, while drawing
  vtkSmartPointer<vtkActor> waypoint_actor_;          // the legs (coloured: green, red across a wall)
  vtkSmartPointer<vtkActor> waypoint_marker_actor_;   // the waypoints
  vtkSmartPointer<vtkActor> rubber_band_actor_;       // from the last waypoint to the cursor
};

// Colour (RGB 0..255) of visibility cell `cell` (a small qualitative palette, cycled; -1 = no cell).
std::array<unsigned char, 3> cell_colour(int cell);

}  // namespace plenopath::widgets
