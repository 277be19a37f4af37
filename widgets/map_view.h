#pragma once
// The map: the floor plan seen from above (VTK, parallel projection). Layers in their colours with occluders
// drawn dark and thick, the path coloured by visibility cell, the cells' critical lines, keyframes as
// markers, and the current frame with its envelope (visibility polygon) and the panorama view's cone.
// Left drag pans, the wheel (or right drag) zooms, a click on the path goes to the nearest frame.
// Renders are requested and coalesced (one per event-loop turn), never forced by the model.
#include <Eigen/Core>
#include <QVTKOpenGLNativeWidget.h>
#include <array>
#include <functional>
#include <vector>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

class QTimer;
class vtkActor;
class vtkRenderer;
class vtkTextActor;

namespace plenopath::widgets {

class ProjectDocument;

// The envelope polygon of a plan point (counter-clockwise, metres), empty when there is none. Set by the
// application once a visibility index exists for the current plan.
using EnvelopeFunction = std::function<std::vector<Eigen::Vector2d>(const Eigen::Vector2d&)>;

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

 signals:
  // The user clicked on the path near the frame at `position` (the document has already moved there).
  void frame_clicked(int position);

 protected:
  bool event(QEvent* event) override;

 private:
  void on_document_changed(unsigned flags);
  void rebuild_plan();
  void rebuild_path();
  void rebuild_keyframes();
  void rebuild_current();
  void handle_click(const QPoint& pixel);

  ProjectDocument& document_;
  EnvelopeFunction envelope_function_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> plan_actor_;
  vtkSmartPointer<vtkActor> occluder_actor_;
  vtkSmartPointer<vtkActor> critical_actor_;
  vtkSmartPointer<vtkActor> path_actor_;
  vtkSmartPointer<vtkActor> keyframe_actor_;
  vtkSmartPointer<vtkActor> current_actor_;
  vtkSmartPointer<vtkActor> envelope_actor_;
  vtkSmartPointer<vtkActor> cone_actor_;
  vtkSmartPointer<vtkActor> hotspot_actor_;  // hotspots (widgets/map_hotspot_markers.h)
  vtkSmartPointer<vtkTextActor> caption_;
  QTimer* render_timer_;
  QPoint press_pixel_;
  bool camera_fitted_ = false;
};

// Colour (RGB 0..255) of visibility cell `cell` (a small qualitative palette, cycled; -1 = no cell).
std::array<unsigned char, 3> cell_colour(int cell);

}  // namespace plenopath::widgets
