#include "widgets/map_view.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleImage.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QTimer>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <limits>

#include "model/error.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/plan/exterior_openings.h"
#include "processing/walk/walk_route.h"
#include "widgets/anchor_commands.h"
#include "widgets/anchor_editor.h"
#include "widgets/map_hotspot_markers.h"
#include "widgets/map_pieces.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

// Left drag pans (the plan never rotates); right drag and the wheel zoom.
class PanZoomStyle : public vtkInteractorStyleImage {
 public:
  static PanZoomStyle* New();
  vtkTypeMacro(PanZoomStyle, vtkInteractorStyleImage) void OnLeftButtonDown() override {
    FindPokedRenderer(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
    if (CurrentRenderer) StartPan();
  }
  void OnLeftButtonUp() override {
    if (State == VTKIS_PAN) EndPan();
  }
  void OnChar() override {}  // no 'w'ireframe, 'r'eset, 'q'uit surprises
};
vtkStandardNewMacro(PanZoomStyle);

// Z of each layer: the camera looks down -Z, so larger Z is drawn on top.
constexpr double kEnvelopeZ = -0.02;
constexpr double kConeZ = -0.01;
constexpr double kPlanZ = 0.0;
constexpr double kCriticalZ = 0.005;
constexpr double kGhostPathZ = 0.008;
constexpr double kPlacementZ = 0.009;
constexpr double kPathZ = 0.01;
constexpr double kKeyframeZ = 0.02;
constexpr double kResidualZ = 0.025;
constexpr double kCurrentZ = 0.03;
constexpr double kWaypointZ = 0.45;  // above the current-frame sphere too, under the anchors
constexpr double kAnchorZ = 0.5;  // well above the current-frame sphere, whose depth bulges toward the camera

// How close (pixels) a press must be to a frame or an anchor marker, and a plan corner to snap to.
constexpr double kPickRadiusPx = 12.0;
constexpr double kSnapRadiusPx = 10.0;

const std::array<unsigned char, 3> kBackground{246, 245, 240};

// AutoCAD colour index to RGB for the common indices; others get a hue from the index.
std::array<unsigned char, 3> aci_colour(int aci) {
  switch (aci) {
    case 1:
      return {200, 40, 40};
    case 2:
      return {190, 170, 20};
    case 3:
      return {40, 150, 40};
    case 4:
      return {20, 160, 170};
    case 5:
      return {40, 70, 200};
    case 6:
      return {170, 40, 170};
    case 8:
      return {110, 110, 110};
    case 9:
      return {160, 160, 160};
    case 7:
    case 0:
    case 256:
      return {60, 60, 60};
    default: {
      const double hue = std::fmod(aci * 0.618034, 1.0) * 6.0;
      const double x = 1.0 - std::fabs(std::fmod(hue, 2.0) - 1.0);
      double r = 0, g = 0, b = 0;
      if (hue < 1)
        r = 1, g = x;
      else if (hue < 2)
        r = x, g = 1;
      else if (hue < 3)
        g = 1, b = x;
      else if (hue < 4)
        g = x, b = 1;
      else if (hue < 5)
        r = x, b = 1;
      else
        r = 1, b = x;
      return {static_cast<unsigned char>(40 + 150 * r), static_cast<unsigned char>(40 + 150 * g),
              static_cast<unsigned char>(40 + 150 * b)};
    }
  }
}

// Blends a colour toward the background (weight = share of the colour kept).
std::array<unsigned char, 3> faded(std::array<unsigned char, 3> c, double weight) {
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<unsigned char>(weight * c[k] + (1.0 - weight) * kBackground[k]);
  return c;
}

vtkSmartPointer<vtkActor> make_actor(const double rgb[3], double line_width, double opacity = 1.0) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->SetLineWidth(static_cast<float>(line_width));
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->LightingOff();
  return actor;
}

void set_polydata(vtkActor* actor, vtkPolyData* data) {
  auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  mapper->SetInputData(data);
  mapper->SetScalarVisibility(data->GetPointData()->GetScalars() != nullptr ||
                              data->GetCellData()->GetScalars() != nullptr);
  mapper->SetColorModeToDirectScalars();
}

// Which cell each path position falls in (-1 when none).
std::vector<int> cell_of_positions(const ProjectDocument& document) {
  const Project& p = document.project();
  const std::vector<PathFrame>& frames = p.path.frames;
  std::vector<int> cell(frames.size(), -1);
  const bool sorted = std::is_sorted(
      frames.begin(), frames.end(), [](const PathFrame& l, const PathFrame& r) { return l.index < r.index; });
  for (std::size_t c = 0; c < p.visibility.cells.size(); ++c) {
    const VisibilityCell& vc = p.visibility.cells[c];
    // Frames in capture order (as paths are): the cell's frames by bisection, not by a scan of the whole
    // path per cell (20 000 frames x 1 300 cells took 26 M steps on the GUI thread at every path change).
    std::size_t i = 0, end = frames.size();
    if (sorted) {
      i = static_cast<std::size_t>(
          std::lower_bound(frames.begin(), frames.end(), vc.first_frame,
                           [](const PathFrame& f, int index) { return f.index < index; }) -
          frames.begin());
      end = static_cast<std::size_t>(
          std::upper_bound(frames.begin(), frames.end(), vc.last_frame,
                           [](int index, const PathFrame& f) { return index < f.index; }) -
          frames.begin());
    }
    for (; i < end; ++i)
      if (frames[i].index >= vc.first_frame && frames[i].index <= vc.last_frame)
        cell[i] = static_cast<int>(c);
  }
  return cell;
}

}  // namespace

std::array<unsigned char, 3> cell_colour(int cell) {
  static const std::array<std::array<unsigned char, 3>, 8> palette{{{31, 119, 180},
                                                                    {255, 127, 14},
                                                                    {44, 160, 44},
                                                                    {214, 39, 40},
                                                                    {148, 103, 189},
                                                                    {140, 86, 75},
                                                                    {227, 119, 194},
                                                                    {23, 190, 207}}};
  if (cell < 0) return {31, 119, 180};
  return palette[static_cast<std::size_t>(cell) % palette.size()];
}

MapView::MapView(ProjectDocument& document, QWidget* parent)
    : QVTKOpenGLNativeWidget(parent), document_(document), render_timer_(new QTimer(this)) {
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  setRenderWindow(window.Get());
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->SetBackground(kBackground[0] / 255.0, kBackground[1] / 255.0, kBackground[2] / 255.0);
  renderer_->GetActiveCamera()->ParallelProjectionOn();
  renderWindow()->AddRenderer(renderer_);
  vtkNew<PanZoomStyle> style;
  renderWindow()->GetInteractor()->SetInteractorStyle(style);

  const double grey[3] = {0.6, 0.6, 0.6};
  const double dark[3] = {0.12, 0.14, 0.18};
  const double amber[3] = {0.95, 0.6, 0.1};
  const double red[3] = {0.85, 0.1, 0.15};
  const double cone[3] = {0.95, 0.75, 0.2};
  const double envelope[3] = {0.3, 0.65, 0.95};
  envelope_actor_ = make_actor(envelope, 1.0, 0.28);
  cone_actor_ = make_actor(cone, 1.0, 0.55);
  plan_actor_ = make_actor(grey, 1.5);
  occluder_actor_ = make_actor(dark, 3.5);
  const double glass[3] = {0.2, 0.55, 0.95};
  opening_actor_ = make_actor(glass, 3.0, 0.9);
  critical_actor_ = make_actor(amber, 1.0, 0.55);
  path_actor_ = make_actor(grey, 4.0);
  keyframe_actor_ = make_actor(red, 1.0);
  keyframe_actor_->GetProperty()->SetPointSize(9.0f);
  keyframe_actor_->GetProperty()->RenderPointsAsSpheresOn();
  current_actor_ = make_actor(dark, 1.0);
  current_actor_->GetProperty()->SetPointSize(15.0f);
  current_actor_->GetProperty()->RenderPointsAsSpheresOn();
  const double ghost[3] = {0.55, 0.55, 0.55};
  const double anchor[3] = {0.82, 0.0, 0.55};
  const double white[3] = {1.0, 1.0, 1.0};
  ghost_path_actor_ = make_actor(ghost, 2.0, 0.6);
  const double placement[3] = {0.5, 0.3, 0.85};
  placement_actor_ = make_actor(placement, 2.5, 0.55);
  renderer_->AddActor(placement_actor_);
  residual_actor_ = make_actor(anchor, 2.0);
  anchor_actor_ = make_actor(anchor, 1.0);
  anchor_actor_->GetProperty()->SetPointSize(13.0f);  // squares: distinct from the round keyframes
  anchor_core_actor_ = make_actor(white, 1.0);
  anchor_core_actor_->GetProperty()->SetPointSize(5.0f);
  for (vtkActor* a : {envelope_actor_.Get(), cone_actor_.Get(), plan_actor_.Get(), occluder_actor_.Get(),
                      opening_actor_.Get(), critical_actor_.Get(), ghost_path_actor_.Get(), path_actor_.Get(),
                      keyframe_actor_.Get(), residual_actor_.Get(), current_actor_.Get(), anchor_actor_.Get(),
                      anchor_core_actor_.Get()})
    renderer_->AddActor(a);

  hotspot_actor_ = make_hotspot_marker_actor();  // hotspots at their 3-D position
  renderer_->AddActor(hotspot_actor_);

  // Waypoint drawing: green legs (red across a wall), darker green waypoints, a fainter rubber band.
  const double waypoint_green[3] = {0.0, 0.62, 0.38};
  const double waypoint_dark[3] = {0.0, 0.38, 0.22};
  waypoint_actor_ = make_actor(waypoint_green, 3.5);
  waypoint_marker_actor_ = make_actor(waypoint_dark, 1.0);
  waypoint_marker_actor_->GetProperty()->SetPointSize(10.0f);
  waypoint_marker_actor_->GetProperty()->RenderPointsAsSpheresOn();
  rubber_band_actor_ = make_actor(waypoint_green, 2.0, 0.6);
  for (vtkActor* a : {waypoint_actor_.Get(), rubber_band_actor_.Get(), waypoint_marker_actor_.Get()})
    renderer_->AddActor(a);

  caption_ = vtkSmartPointer<vtkTextActor>::New();
  caption_->GetTextProperty()->SetFontSize(14);
  caption_->GetTextProperty()->SetColor(0.2, 0.2, 0.25);
  caption_->SetDisplayPosition(10, 8);
  renderer_->AddViewProp(caption_);
  hint_ = vtkSmartPointer<vtkTextActor>::New();
  hint_->GetTextProperty()->SetFontSize(12);
  hint_->GetTextProperty()->SetColor(0.45, 0.45, 0.5);
  hint_->GetTextProperty()->SetVerticalJustificationToTop();
  hint_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  hint_->GetPositionCoordinate()->SetValue(0.01, 0.985);
  renderer_->AddViewProp(hint_);
  setToolTip(anchor_hint());

  render_timer_->setSingleShot(true);
  render_timer_->setInterval(0);
  connect(render_timer_, &QTimer::timeout, this, [this] { renderWindow()->Render(); });
  connect(&document_, &ProjectDocument::changed, this, &MapView::on_document_changed);
  connect(&document_, &ProjectDocument::current_position_changed, this, [this] {
    rebuild_current();
    request_render();
  });
  connect(&document_, &ProjectDocument::look_changed, this, [this] {
    rebuild_current();
    request_render();
  });
  setMinimumSize(200, 150);
  on_document_changed(kEverythingChanged);
}

MapView::~MapView() = default;

void MapView::set_envelope_function(EnvelopeFunction function) {
  envelope_function_ = std::move(function);
  rebuild_current();
  request_render();
}

void MapView::request_render() { render_timer_->start(); }

void MapView::render_now() {
  render_timer_->stop();
  renderWindow()->Render();
}

void MapView::on_document_changed(unsigned flags) {
  if (drag_.active && (flags & (kPathChanged | kAnchorsChanged))) end_anchor_drag(false);  // undone under us
  if (flags & (kPlanChanged | kVisibilityChanged)) rebuild_plan();
  if (flags & (kPathChanged | kVisibilityChanged | kCaptureChanged)) rebuild_path();
  if (flags & (kPathChanged | kKeyframesChanged)) rebuild_keyframes();
  if (flags & (kPathChanged | kAnchorsChanged)) rebuild_anchors(drawn_path_, document_.project().anchors);
  if (drawing_waypoints_ && (flags & kPlanChanged)) {
    waypoint_walls_ = document_.project().plan.occluder_segments();
    rebuild_waypoints();
  }
  update_hint();
  if (flags & kHotspotsChanged) update_hotspot_markers(hotspot_actor_, document_.project());
  rebuild_current();
  if ((flags & (kPlanChanged | kPathChanged)) && (flags & kPlanChanged || !camera_fitted_)) reset_camera();
  request_render();
}

void MapView::update_hint() {
  vtkTextProperty* text = hint_->GetTextProperty();
  if (drawing_waypoints_) {
    text->SetFontSize(14);
    text->SetBold(true);
    text->SetColor(0.0, 0.38, 0.22);
    hint_->SetInput(waypoint_hint_.toStdString().c_str());
    return;
  }
  text->SetFontSize(12);
  text->SetBold(false);
  text->SetColor(0.45, 0.45, 0.5);
  int unplaced = 0;
  for (int k = 0; k < document_.project().path.piece_count(); ++k)
    unplaced += !document_.project().path.piece_placed(k);
  hint_->SetInput(
      document_.project().path.empty() ? ""
      : unplaced > 0
          ? (std::to_string(document_.project().path.piece_count()) + " pieces, " + std::to_string(unplaced) +
             " unplaced (right of the plan): Ctrl+drag one of a piece's frames onto the plan to place it")
                .c_str()
          : "Ctrl+drag a frame: anchor it where it really was  ·  + Shift: snap to a plan corner  ·  "
            "drag an anchor to move it");
}

void MapView::rebuild_plan() {
  const Project& p = document_.project();
  // Non-occluders by layer colour, faded; occluders dark and thick.
  vtkNew<vtkPoints> points, occ_points;
  vtkNew<vtkCellArray> lines, occ_lines;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  for (const PlanSegment& s : p.plan.segments) {
    const PlanLayer* layer = p.plan.find_layer(s.layer);
    if (layer && !layer->visible) continue;
    vtkPoints* pts = s.occluder ? occ_points.Get() : points.Get();
    vtkCellArray* cells = s.occluder ? occ_lines.Get() : lines.Get();
    const vtkIdType a = pts->InsertNextPoint(s.a.x(), s.a.y(), kPlanZ);
    const vtkIdType b = pts->InsertNextPoint(s.b.x(), s.b.y(), kPlanZ);
    const vtkIdType ids[2] = {a, b};
    cells->InsertNextCell(2, ids);
    if (!s.occluder) {
      const auto c = faded(aci_colour(layer ? layer->color : 8), 0.6);
      colours->InsertNextTypedTuple(c.data());
    }
  }
  vtkNew<vtkPolyData> plan, occluders;
  plan->SetPoints(points);
  plan->SetLines(lines);
  plan->GetCellData()->SetScalars(colours);
  occluders->SetPoints(occ_points);
  occluders->SetLines(occ_lines);
  set_polydata(plan_actor_, plan);
  set_polydata(occluder_actor_, occluders);

  // The gaps in the outer walls that visibility and registration close (windows drawn as gaps): drawn as
  // glass so the author sees what the studio assumed. Computed once per plan, not per visibility change.
  if (openings_revision_ != document_.plan_revision()) {
    openings_revision_ = document_.plan_revision();
    std::vector<Segment2> walls;
    for (const PlanSegment& s : p.plan.occluder_segments()) walls.push_back({s.a, s.b});
    try {
      openings_ = exterior_openings(walls);
    } catch (const Error&) {
      openings_.clear();  // a plan too odd to rasterise: nothing drawn, visibility says what is wrong
    }
  }
  vtkNew<vtkPoints> opening_points;
  vtkNew<vtkCellArray> opening_lines;
  for (const Segment2& s : openings_) {
    const vtkIdType ids[2] = {opening_points->InsertNextPoint(s.a.x(), s.a.y(), kPlanZ),
                              opening_points->InsertNextPoint(s.b.x(), s.b.y(), kPlanZ)};
    opening_lines->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> openings;
  openings->SetPoints(opening_points);
  openings->SetLines(opening_lines);
  set_polydata(opening_actor_, openings);

  vtkNew<vtkPoints> cpoints;
  vtkNew<vtkCellArray> clines;
  for (const CriticalLine& l : p.visibility.critical_lines) {
    const vtkIdType ids[2] = {cpoints->InsertNextPoint(l.a.x(), l.a.y(), kCriticalZ),
                              cpoints->InsertNextPoint(l.b.x(), l.b.y(), kCriticalZ)};
    clines->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> critical;
  critical->SetPoints(cpoints);
  critical->SetLines(clines);
  set_polydata(critical_actor_, critical);
}

void MapView::rebuild_path() {
  path_cells_ = cell_of_positions(document_);
  set_path_geometry(document_.project().path);
}

void MapView::set_path_geometry(const CameraPath& path) {
  drawn_path_ = path_as_drawn(path, document_.project().plan.extents());
  const CameraPath& path_frames = drawn_path_;
  const bool in_pieces = path_frames.piece_count() > 1;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  // One segment per pair of frames so each takes its cell's colour sharply.
  for (std::size_t i = 0; i < path_frames.size(); ++i)
    points->InsertNextPoint(path_frames.frames[i].x, path_frames.frames[i].y, kPathZ);
  for (std::size_t i = 0; i + 1 < path_frames.size(); ++i) {
    if (path_frames.frames[i].piece != path_frames.frames[i + 1].piece) continue;  // pieces do not connect
    const vtkIdType ids[2] = {static_cast<vtkIdType>(i), static_cast<vtkIdType>(i + 1)};
    lines->InsertNextCell(2, ids);
    const auto c = in_pieces ? piece_colour(path_frames.frames[i].piece)
                             : cell_colour(i < path_cells_.size() ? path_cells_[i] : -1);
    colours->InsertNextTypedTuple(c.data());
  }
  vtkNew<vtkPolyData> lines_data;
  lines_data->SetPoints(points);
  lines_data->SetLines(lines);
  lines_data->GetCellData()->SetScalars(colours);
  set_polydata(path_actor_, lines_data);
}

void MapView::rebuild_anchors(const CameraPath& path, const Anchors& anchors) {
  vtkNew<vtkPoints> points, line_points;
  vtkNew<vtkCellArray> verts, lines;
  for (const Anchor& a : anchors) {
    const vtkIdType id = points->InsertNextPoint(a.position.x(), a.position.y(), kAnchorZ);
    verts->InsertNextCell(1, &id);
    // The residual: from the anchor to where its frame is on the path.
    if (const PathFrame* f = path.find_frame(a.frame)) {
      const vtkIdType ids[2] = {line_points->InsertNextPoint(a.position.x(), a.position.y(), kResidualZ),
                                line_points->InsertNextPoint(f->x, f->y, kResidualZ)};
      lines->InsertNextCell(2, ids);
    }
  }
  vtkNew<vtkPolyData> markers, residuals;
  markers->SetPoints(points);
  markers->SetVerts(verts);
  residuals->SetPoints(line_points);
  residuals->SetLines(lines);
  set_polydata(anchor_actor_, markers);
  set_polydata(anchor_core_actor_, markers);
  set_polydata(residual_actor_, residuals);
}

void MapView::rebuild_keyframes() {
  const Project& p = document_.project();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  for (int index : p.keyframes.indices) {
    const PathFrame* f = drawn_path_.find_frame(index);
    if (!f) continue;
    const vtkIdType id = points->InsertNextPoint(f->x, f->y, kKeyframeZ);
    verts->InsertNextCell(1, &id);
  }
  vtkNew<vtkPolyData> keyframes;
  keyframes->SetPoints(points);
  keyframes->SetVerts(verts);
  set_polydata(keyframe_actor_, keyframes);
}

void MapView::rebuild_current() {
  const Project& p = document_.project();
  const int position = document_.current_position();
  vtkNew<vtkPolyData> marker, cone, envelope;
  std::string caption;
  if (!drawn_path_.empty() && position >= 0 && position < static_cast<int>(drawn_path_.size())) {
    const PathFrame& f = drawn_path_.frames[position];
    vtkNew<vtkPoints> mp;
    vtkNew<vtkCellArray> mv;
    const vtkIdType id = mp->InsertNextPoint(f.x, f.y, kCurrentZ);
    mv->InsertNextCell(1, &id);
    marker->SetPoints(mp);
    marker->SetVerts(mv);

    // The panorama view's cone: world angle = heading - azimuth (azimuth grows clockwise).
    const PlanExtents e = p.plan.extents();
    const double reach = e.valid ? 0.08 * e.size().norm() : 1.0;
    const double centre = f.heading - document_.look_azimuth();
    const double half = 0.5 * document_.look_fov();
    vtkNew<vtkPoints> cp;
    vtkNew<vtkCellArray> cpolys;
    cp->InsertNextPoint(f.x, f.y, kConeZ);
    const int steps = 12;
    for (int k = 0; k <= steps; ++k) {
      const double a = centre - half + 2.0 * half * k / steps;
      cp->InsertNextPoint(f.x + reach * std::cos(a), f.y + reach * std::sin(a), kConeZ);
    }
    for (int k = 0; k < steps; ++k) {
      const vtkIdType tri[3] = {0, k + 1, k + 2};
      cpolys->InsertNextCell(3, tri);
    }
    cone->SetPoints(cp);
    cone->SetPolys(cpolys);

    // The envelope is star-shaped around the viewpoint: a fan from it is a valid triangulation.
    if (envelope_function_) {
      const std::vector<Eigen::Vector2d> polygon = envelope_function_(f.position());
      if (polygon.size() >= 3) {
        vtkNew<vtkPoints> ep;
        vtkNew<vtkCellArray> epolys;
        ep->InsertNextPoint(f.x, f.y, kEnvelopeZ);
        for (const auto& q : polygon) ep->InsertNextPoint(q.x(), q.y(), kEnvelopeZ);
        const vtkIdType n = static_cast<vtkIdType>(polygon.size());
        for (vtkIdType k = 0; k < n; ++k) {
          const vtkIdType tri[3] = {0, 1 + k, 1 + (k + 1) % n};
          epolys->InsertNextCell(3, tri);
        }
        envelope->SetPoints(ep);
        envelope->SetPolys(epolys);
        double area = 0.0;
        for (std::size_t k = 0; k < polygon.size(); ++k) {
          const auto& a = polygon[k];
          const auto& b = polygon[(k + 1) % polygon.size()];
          area += a.x() * b.y() - a.y() * b.x();
        }
        caption =
            " · envelope " + std::to_string(static_cast<int>(std::round(0.5 * std::fabs(area)))) + " m²";
      }
    }
    char head[128];
    std::snprintf(head, sizeof head, "frame %d  (%.2f, %.2f) m  heading %.0f°", f.index, f.x, f.y,
                  degrees(f.heading));
    caption = head + caption;
  }
  set_polydata(current_actor_, marker);
  set_polydata(cone_actor_, cone);
  set_polydata(envelope_actor_, envelope);
  if (!drawing_waypoints_) caption_->SetInput(caption.c_str());  // while drawing: the waypoints' caption
}

void MapView::reset_camera() {
  const Project& p = document_.project();
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  const PlanExtents e = p.plan.extents();
  if (e.valid) {
    lo = lo.cwiseMin(e.min);
    hi = hi.cwiseMax(e.max);
  }
  for (const PathFrame& f : drawn_path_.frames) {
    lo = lo.cwiseMin(f.position());
    hi = hi.cwiseMax(f.position());
  }
  if (lo.x() > hi.x()) {
    lo = {-5, -5};
    hi = {5, 5};
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d(1.0, 1.0));
  const double aspect = std::max(1, width()) / static_cast<double>(std::max(1, height()));
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(centre.x(), centre.y(), 0.0);
  camera->SetPosition(centre.x(), centre.y(), 100.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(0.55 * std::max(size.y(), size.x() / aspect));
  camera->SetClippingRange(1.0, 200.0);
  camera_fitted_ = e.valid || !p.path.empty();
  request_render();
}

Eigen::Vector2d MapView::plan_point_at(const QPoint& widget_pixel) {
  const double dpr = devicePixelRatioF();
  const int* size = renderWindow()->GetSize();
  renderer_->SetDisplayPoint(widget_pixel.x() * dpr, size[1] - 1 - widget_pixel.y() * dpr, 0.0);
  renderer_->DisplayToWorld();
  const double* w = renderer_->GetWorldPoint();
  const double h = w[3] != 0.0 ? w[3] : 1.0;
  return {w[0] / h, w[1] / h};
}

QPoint MapView::widget_pixel_of(const Eigen::Vector2d& plan_point) {
  const double dpr = devicePixelRatioF();
  const int* size = renderWindow()->GetSize();
  renderer_->SetWorldPoint(plan_point.x(), plan_point.y(), 0.0, 1.0);
  renderer_->WorldToDisplay();
  const double* d = renderer_->GetDisplayPoint();
  return QPoint(static_cast<int>(std::lround(d[0] / dpr)),
                static_cast<int>(std::lround((size[1] - 1 - d[1]) / dpr)));
}

void MapView::start_point_pick(const QString& hint) {
  cancel_waypoint_drawing();
  picking_point_ = true;
  setCursor(Qt::CrossCursor);
  setFocus();
  emit message(hint);
}

void MapView::cancel_point_pick() {
  if (!picking_point_) return;
  picking_point_ = false;
  unsetCursor();
  emit point_pick_cancelled();
}

bool MapView::event(QEvent* e) {
  // The release that ends a double-click (which finished a waypoint drawing) is no click.
  if (swallow_release_ && e->type() == QEvent::MouseButtonPress) swallow_release_ = false;
  if (swallow_release_ && e->type() == QEvent::MouseButtonRelease) {
    swallow_release_ = false;
    return QVTKOpenGLNativeWidget::event(e);  // ends VTK's pan, if any
  }
  if (drawing_waypoints_ && handle_waypoint_event(e)) return true;
  if (picking_point_ && e->type() == QEvent::KeyPress &&
      static_cast<QKeyEvent*>(e)->key() == Qt::Key_Escape) {
    cancel_point_pick();
    return true;
  }
  if (!picking_point_ && !drawing_waypoints_ && handle_anchor_event(e)) {
    e->accept();
    return true;
  }
  if (e->type() == QEvent::MouseButtonPress) {
    auto* m = static_cast<QMouseEvent*>(e);
    if (m->button() == Qt::LeftButton) press_pixel_ = m->pos();
  } else if (e->type() == QEvent::MouseButtonRelease) {
    auto* m = static_cast<QMouseEvent*>(e);
    if (m->button() == Qt::LeftButton && (m->pos() - press_pixel_).manhattanLength() <= 4) {
      const bool handled = QVTKOpenGLNativeWidget::event(e);
      handle_click(m->pos());
      return handled;
    }
  }
  return QVTKOpenGLNativeWidget::event(e);
}

void MapView::set_placement_ghosts(std::vector<MapPlacementGhost> ghosts) {
  ghosts_ = std::move(ghosts);
  for (const auto& label : placement_labels_) renderer_->RemoveViewProp(label);
  placement_labels_.clear();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  for (std::size_t k = 0; k < ghosts_.size(); ++k) {
    const MapPlacementGhost& g = ghosts_[k];
    if (g.polyline.empty()) continue;
    lines->InsertNextCell(static_cast<vtkIdType>(g.polyline.size()));
    for (const Eigen::Vector2d& p : g.polyline)
      lines->InsertCellPoint(points->InsertNextPoint(p.x(), p.y(), kPlacementZ));
    // The label on the ghost, in plan coordinates so that it follows pan and zoom; ghosts of one piece
    // often cross at their middles, so each label sits at its own fraction of its ghost.
    const Eigen::Vector2d& at = g.polyline[g.polyline.size() * (k % 3 + 1) / 4];
    auto label = vtkSmartPointer<vtkTextActor>::New();
    label->SetInput(g.label.c_str());
    label->GetTextProperty()->SetFontSize(13);
    label->GetTextProperty()->SetColor(0.4, 0.2, 0.7);
    label->GetTextProperty()->SetBold(true);
    label->GetPositionCoordinate()->SetCoordinateSystemToWorld();
    label->GetPositionCoordinate()->SetValue(at.x(), at.y(), kPlacementZ);
    renderer_->AddViewProp(label);
    placement_labels_.push_back(label);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  set_polydata(placement_actor_, data);
  request_render();
}

int MapView::placement_ghost_near(const QPoint& pixel, double radius_px) {
  const Eigen::Vector2d q = plan_point_at(pixel);
  int best = -1;
  double best_distance = radius_px * metres_per_pixel();
  for (std::size_t k = 0; k < ghosts_.size(); ++k) {
    const std::vector<Eigen::Vector2d>& line = ghosts_[k].polyline;
    for (std::size_t i = 0; i < line.size(); ++i) {
      // Distance to the segment from this vertex to the next (to the vertex for the last one).
      const Eigen::Vector2d a = line[i], b = i + 1 < line.size() ? line[i + 1] : line[i];
      const Eigen::Vector2d ab = b - a;
      const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      const double d = (a + t * ab - q).norm();
      if (d < best_distance) {
        best_distance = d;
        best = static_cast<int>(k);
      }
    }
  }
  return best;
}

void MapView::handle_click(const QPoint& pixel) {
  if (picking_point_) {
    picking_point_ = false;
    unsetCursor();
    const Eigen::Vector2d q = plan_point_at(pixel);
    emit point_picked(q.x(), q.y());
    return;
  }
  const int best = frame_near(pixel, 15.0);  // a click within 15 pixels of the path counts
  // A ghost wins when it is nearer than the path (within 10 pixels).
  if (const int ghost = placement_ghost_near(pixel, 10.0); ghost >= 0) {
    const Eigen::Vector2d q = plan_point_at(pixel);
    const double path_distance =
        best >= 0 ? (drawn_path_.frames[static_cast<std::size_t>(best)].position() - q).norm()
                  : std::numeric_limits<double>::infinity();
    if (path_distance > 3.0 * metres_per_pixel()) {
      const MapPlacementGhost& g = ghosts_[static_cast<std::size_t>(ghost)];
      emit placement_clicked(g.piece, g.candidate);
      return;
    }
  }
  if (best < 0) return;
  document_.set_current_position(best);
  emit frame_clicked(best);
}

double MapView::metres_per_pixel() const {
  return 2.0 * renderer_->GetActiveCamera()->GetParallelScale() / std::max(1, height());
}

int MapView::frame_near(const QPoint& pixel, double radius_px) {
  const CameraPath& path = drawn_path_;  // where the frames are drawn (unplaced pieces in the tray)
  const Eigen::Vector2d q = plan_point_at(pixel);
  int best = -1;
  double best_distance = radius_px * metres_per_pixel();
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double d = (path.frames[i].position() - q).norm();
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

int MapView::anchor_near(const QPoint& pixel, double radius_px) {
  const Eigen::Vector2d q = plan_point_at(pixel);
  int best = -1;
  double best_distance = radius_px * metres_per_pixel();
  for (const Anchor& a : document_.project().anchors) {
    const double d = (a.position - q).norm();
    if (d < best_distance) {
      best_distance = d;
      best = a.frame;
    }
  }
  return best;
}

Eigen::Vector2d MapView::anchor_target(const QPoint& pixel, bool snap, bool* snapped) {
  const Eigen::Vector2d q = plan_point_at(pixel);
  *snapped = false;
  if (!snap) return q;
  const Project& p = document_.project();
  Eigen::Vector2d best = q;
  double best_distance = kSnapRadiusPx * metres_per_pixel();
  for (const PlanSegment& s : p.plan.segments) {
    const PlanLayer* layer = p.plan.find_layer(s.layer);
    if (layer && !layer->visible) continue;
    for (const Eigen::Vector2d& corner : {s.a, s.b}) {
      const double d = (corner - q).norm();
      if (d < best_distance) {
        best_distance = d;
        best = corner;
        *snapped = true;
      }
    }
  }
  return best;
}

QString MapView::anchor_hint() {
  return tr(
      "Ctrl + drag a frame of the path to where it really was (an anchor); hold Shift too to snap to a "
      "plan corner. Drag an anchor marker to move it; Esc cancels a drag.");
}

// Returns true when the event belonged to an anchor drag (it then does not reach VTK's pan and zoom).
bool MapView::handle_anchor_event(QEvent* e) {
  if (e->type() == QEvent::MouseButtonPress) {
    auto* m = static_cast<QMouseEvent*>(e);
    if (m->button() != Qt::LeftButton || document_.project().path.empty()) return false;
    int frame = -1;
    if (m->modifiers() & Qt::ControlModifier) {
      const int position = frame_near(m->pos(), kPickRadiusPx);
      if (position >= 0) frame = document_.project().path.frames[position].index;
    }
    if (frame < 0) frame = anchor_near(m->pos(), kPickRadiusPx);  // an existing marker: no modifier needed
    if (frame < 0) return false;
    drag_ = AnchorDrag{};
    drag_.active = true;
    drag_.frame = frame;
    drag_.press_pixel = m->pos();
    setFocus(Qt::MouseFocusReason);  // so Esc reaches the drag
    const PathFrame* f = document_.project().path.find_frame(frame);
    if (f) document_.set_current_position(document_.position_of_frame_index(frame));
    emit message(tr("Anchoring frame %1: release where it really was (Shift snaps, Esc cancels)").arg(frame));
    return true;
  }
  if (!drag_.active) return false;
  if (e->type() == QEvent::MouseMove) {
    auto* m = static_cast<QMouseEvent*>(e);
    if (!drag_.moved && (m->pos() - drag_.press_pixel).manhattanLength() <= 3) return true;
    drag_.moved = true;
    update_anchor_drag(m->pos(), m->modifiers() & Qt::ShiftModifier);
    return true;
  }
  if (e->type() == QEvent::MouseButtonRelease) {
    auto* m = static_cast<QMouseEvent*>(e);
    if (m->button() != Qt::LeftButton) return true;
    if (drag_.moved) {
      // The release is nearly always where the last move was: that preview is drawn already (recomputing
      // and redrawing it cost the GUI thread a redraw of 20 000 frames for nothing).
      const bool snap = m->modifiers() & Qt::ShiftModifier;
      if (m->pos() != drag_.previewed_pixel || snap != drag_.previewed_snap)
        update_anchor_drag(m->pos(), snap);
      end_anchor_drag(true);
    } else {
      end_anchor_drag(false);  // a click on a marker: the frame is already current
    }
    return true;
  }
  if (e->type() == QEvent::KeyPress && static_cast<QKeyEvent*>(e)->key() == Qt::Key_Escape) {
    end_anchor_drag(false);
    emit message(tr("Anchor drag cancelled"));
    return true;
  }
  return false;
}

void MapView::update_anchor_drag(const QPoint& pixel, bool snap) {
  drag_.previewed_pixel = pixel;
  drag_.previewed_snap = snap;
  drag_.target = anchor_target(pixel, snap, &drag_.snapped);
  const CameraPath& path = document_.project().path;
  // From the anchors of an edit still being computed, so a quick second drag keeps the first anchor.
  drag_.anchors = anchors_with(AnchorEditor::of(document_).anchors(), drag_.frame, drag_.target);
  try {
    drag_.preview = preview_path_with_anchors(path, drag_.anchors);
    drag_.valid = true;
  } catch (const Error& e) {
    drag_.valid = false;
    drag_.preview = path;
    emit message(QString::fromStdString(e.what()));
  }
  set_path_geometry(drag_.preview);
  rebuild_anchors(drawn_path_, drag_.anchors);
  char text[160];
  std::snprintf(text, sizeof text, "anchor frame %d -> (%.2f, %.2f) m%s  ·  Esc cancels", drag_.frame,
                drag_.target.x(), drag_.target.y(), drag_.snapped ? "  [snapped to a plan corner]" : "");
  caption_->SetInput(text);
  request_render();
  if (drag_.ghost_drawn) return;
  // The path before the drag stays as a grey ghost under the bent one (drawn once per drag).
  drag_.ghost_drawn = true;
  vtkNew<vtkPoints> ghost_points;
  vtkNew<vtkCellArray> ghost_lines;
  const CameraPath ghost_path = path_as_drawn(path, document_.project().plan.extents());
  for (std::size_t i = 0; i < ghost_path.size(); ++i)
    ghost_points->InsertNextPoint(ghost_path.frames[i].x, ghost_path.frames[i].y, kGhostPathZ);
  ghost_lines->InsertNextCell(static_cast<vtkIdType>(path.size()));
  for (std::size_t i = 0; i < path.size(); ++i) ghost_lines->InsertCellPoint(static_cast<vtkIdType>(i));
  vtkNew<vtkPolyData> ghost;
  ghost->SetPoints(ghost_points);
  ghost->SetLines(ghost_lines);
  set_polydata(ghost_path_actor_, ghost);
}

void MapView::end_anchor_drag(bool apply) {
  if (!drag_.active) return;
  const AnchorDrag drag = drag_;
  drag_ = AnchorDrag{};
  set_polydata(ghost_path_actor_, vtkNew<vtkPolyData>().Get());
  if (apply && drag.valid) {
    AnchorEditor& editor = AnchorEditor::of(document_);
    const bool existing = std::any_of(editor.anchors().begin(), editor.anchors().end(),
                                      [&](const Anchor& a) { return a.frame == drag.frame; });
    // The correction is computed on a worker; the preview stays drawn until it lands (the document's
    // change redraws everything) or is refused (back to the document's path).
    AnchorEditor::Callbacks callbacks;
    callbacks.context = this;
    const int count = static_cast<int>(drag.anchors.size());
    callbacks.landed = [this, frame = drag.frame, target = drag.target, count](PathCorrection applied) {
      emit message(
          tr("Frame %1 anchored at (%2, %3) m; %4")
              .arg(frame)
              .arg(target.x(), 0, 'f', 2)
              .arg(target.y(), 0, 'f', 2)
              .arg(applied == PathCorrection::kRefine
                       ? tr("path refined with %n anchor(s)", "", count)
                       : tr("path warped (long path: Process > Refine path with anchors for the full "
                            "correction)")));
    };
    callbacks.refused = [this](const QString& why) {
      emit message(why);
      if (drag_.active) return;  // a new drag draws its own preview
      set_path_geometry(document_.project().path);
      rebuild_anchors(drawn_path_, document_.project().anchors);
      rebuild_current();
      request_render();
    };
    editor.request(
        existing ? tr("Move anchor of frame %1").arg(drag.frame) : tr("Anchor frame %1").arg(drag.frame),
        drag.anchors, PathCorrection::kRefine, callbacks);
    if (editor.busy()) emit message(tr("Frame %1: correcting the path...").arg(drag.frame));
    return;
  }
  // Cancelled or refused: back to the document's path and anchors.
  set_path_geometry(document_.project().path);
  rebuild_anchors(drawn_path_, document_.project().anchors);
  rebuild_current();
  request_render();
}

void MapView::start_waypoint_drawing(const QString& hint) {
  cancel_point_pick();
  if (drag_.active) end_anchor_drag(false);
  drawing_waypoints_ = true;
  swallow_release_ = false;
  waypoint_hint_ = hint;
  waypoints_.clear();
  waypoint_leg_crosses_.clear();
  waypoint_walls_ = document_.project().plan.occluder_segments();
  cursor_on_map_ = false;
  setMouseTracking(true);  // the rubber band follows the cursor
  setCursor(Qt::CrossCursor);
  setFocus();
  update_hint();
  rebuild_waypoints();
  emit message(QString(hint).replace('\n', "  ·  "));  // the hint's lines on one
}

void MapView::cancel_waypoint_drawing() {
  if (!drawing_waypoints_) return;
  end_waypoint_drawing();
  emit message(tr("Waypoint drawing cancelled"));
  emit waypoints_cancelled();
}

int MapView::waypoint_legs_crossing_walls() const {
  return static_cast<int>(std::count(waypoint_leg_crosses_.begin(), waypoint_leg_crosses_.end(), 1));
}

void MapView::finish_waypoint_drawing() {
  if (waypoints_.size() < 2) {
    emit message(tr("Two waypoints at least: click another, or Esc to cancel"));
    return;
  }
  const std::vector<Eigen::Vector2d> waypoints = waypoints_;
  double length = 0.0;
  for (std::size_t k = 1; k < waypoints.size(); ++k) length += (waypoints[k] - waypoints[k - 1]).norm();
  const int crossing = waypoint_legs_crossing_walls();
  end_waypoint_drawing();
  QString text =
      tr("%n waypoint(s) drawn, %1 m", "", static_cast<int>(waypoints.size())).arg(length, 0, 'f', 2);
  if (crossing > 0) text += tr(" (%n leg(s) cross a wall)", "", crossing);
  emit message(text);
  emit waypoints_drawn(waypoints);
}

void MapView::end_waypoint_drawing() {
  drawing_waypoints_ = false;
  waypoints_.clear();
  waypoint_leg_crosses_.clear();
  waypoint_walls_.clear();
  setMouseTracking(false);
  unsetCursor();
  update_hint();
  rebuild_waypoints();
  rebuild_current();  // the frame's caption again
  request_render();
}

bool MapView::handle_waypoint_event(QEvent* e) {
  switch (e->type()) {
    case QEvent::ShortcutOverride:
    case QEvent::KeyPress: {
      auto* k = static_cast<QKeyEvent*>(e);
      const int key = k->key();
      if (key != Qt::Key_Escape && key != Qt::Key_Backspace && key != Qt::Key_Return && key != Qt::Key_Enter)
        return false;
      e->accept();  // an override: the key comes here as a KeyPress, not to a menu shortcut
      if (e->type() == QEvent::ShortcutOverride) return true;
      if (key == Qt::Key_Escape) {
        cancel_waypoint_drawing();
      } else if (key == Qt::Key_Backspace) {
        if (!waypoints_.empty()) {
          waypoints_.pop_back();
          if (!waypoint_leg_crosses_.empty()) waypoint_leg_crosses_.pop_back();
          rebuild_waypoints();
          emit message(tr("%n waypoint(s) left", "", static_cast<int>(waypoints_.size())));
        }
      } else {
        finish_waypoint_drawing();
      }
      return true;
    }
    case QEvent::MouseButtonDblClick: {
      if (static_cast<QMouseEvent*>(e)->button() != Qt::LeftButton) return false;
      // The double-click's first click added its waypoint already; its second release adds none.
      swallow_release_ = true;
      finish_waypoint_drawing();
      return true;
    }
    case QEvent::MouseMove: {
      cursor_on_map_ = true;
      cursor_ = plan_point_at(static_cast<QMouseEvent*>(e)->pos());
      rebuild_waypoints();
      return false;  // a drag still pans
    }
    case QEvent::Leave:
      cursor_on_map_ = false;
      rebuild_waypoints();
      return false;
    case QEvent::MouseButtonRelease: {
      auto* m = static_cast<QMouseEvent*>(e);
      if (m->button() != Qt::LeftButton) return false;
      if ((m->pos() - press_pixel_).manhattanLength() > 4) return false;  // a drag: panned
      QVTKOpenGLNativeWidget::event(e);
      const Eigen::Vector2d q = plan_point_at(m->pos());
      if (!waypoints_.empty() && (q - waypoints_.back()).norm() < 1e-6) return true;
      if (!waypoints_.empty())
        waypoint_leg_crosses_.push_back(crosses_any_wall(waypoint_walls_, waypoints_.back(), q) ? 1 : 0);
      waypoints_.push_back(q);
      cursor_ = q;
      rebuild_waypoints();
      QString text =
          tr("Waypoint %1 at (%2, %3) m").arg(waypoints_.size()).arg(q.x(), 0, 'f', 2).arg(q.y(), 0, 'f', 2);
      if (!waypoint_leg_crosses_.empty() && waypoint_leg_crosses_.back())
        text += tr(" — this leg crosses a wall");
      emit message(text + tr(" · Backspace removes it, Enter or a double-click finishes, Esc cancels"));
      return true;
    }
    default:
      return false;
  }
}

void MapView::rebuild_waypoints() {
  vtkNew<vtkPoints> points, band_points;
  vtkNew<vtkCellArray> lines, verts, band;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  const std::array<unsigned char, 3> green{0, 158, 97}, red{220, 30, 40};
  for (const Eigen::Vector2d& p : waypoints_) {
    const vtkIdType id = points->InsertNextPoint(p.x(), p.y(), kWaypointZ);
    verts->InsertNextCell(1, &id);
  }
  for (std::size_t k = 0; k + 1 < waypoints_.size(); ++k) {
    const vtkIdType ids[2] = {static_cast<vtkIdType>(k), static_cast<vtkIdType>(k + 1)};
    lines->InsertNextCell(2, ids);
    const bool crosses = k < waypoint_leg_crosses_.size() && waypoint_leg_crosses_[k];
    colours->InsertNextTypedTuple((crosses ? red : green).data());
  }
  bool band_crosses = false;
  if (drawing_waypoints_ && cursor_on_map_ && !waypoints_.empty()) {
    band_crosses = crosses_any_wall(waypoint_walls_, waypoints_.back(), cursor_);
    const vtkIdType ids[2] = {
        band_points->InsertNextPoint(waypoints_.back().x(), waypoints_.back().y(), kWaypointZ),
        band_points->InsertNextPoint(cursor_.x(), cursor_.y(), kWaypointZ)};
    band->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> legs, markers, rubber;
  legs->SetPoints(points);
  legs->SetLines(lines);
  legs->GetCellData()->SetScalars(colours);
  markers->SetPoints(points);
  markers->SetVerts(verts);
  rubber->SetPoints(band_points);
  rubber->SetLines(band);
  set_polydata(waypoint_actor_, legs);
  set_polydata(waypoint_marker_actor_, markers);
  set_polydata(rubber_band_actor_, rubber);
  rubber_band_actor_->GetProperty()->SetColor(band_crosses ? 0.86 : 0.0, band_crosses ? 0.12 : 0.62,
                                              band_crosses ? 0.16 : 0.38);
  if (drawing_waypoints_) {
    double length = 0.0;
    for (std::size_t k = 1; k < waypoints_.size(); ++k) length += (waypoints_[k] - waypoints_[k - 1]).norm();
    char text[200];
    std::snprintf(text, sizeof text, "%d waypoint%s  ·  %.2f m", static_cast<int>(waypoints_.size()),
                  waypoints_.size() == 1 ? "" : "s", length);
    std::string caption = text;
    if (cursor_on_map_) {
      std::snprintf(text, sizeof text, "  ·  cursor (%.2f, %.2f) m", cursor_.x(), cursor_.y());
      caption += text;
    }
    if (const int crossing = waypoint_legs_crossing_walls(); crossing > 0)
      caption +=
          "  ·  " + std::to_string(crossing) + (crossing == 1 ? " leg crosses" : " legs cross") + " a wall";
    caption_->SetInput(caption.c_str());
  }
  request_render();
}

}  // namespace plenopath::widgets
