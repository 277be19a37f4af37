#include "widgets/map_hotspot_markers.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

#include "model/project.h"

namespace plenopath::widgets {

namespace {
constexpr double kHotspotZ = 0.035;  // above the path and the current frame, below anchor markers
}

vtkSmartPointer<vtkActor> make_hotspot_marker_actor() {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  mapper->SetScalarVisibility(false);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.98, 0.80, 0.0);  // gold: apart from the orange critical lines
  actor->GetProperty()->SetLineWidth(4.0f);
  actor->GetProperty()->SetPointSize(11.0f);
  actor->GetProperty()->RenderPointsAsSpheresOn();
  actor->GetProperty()->LightingOff();
  return actor;
}

void update_hotspot_markers(vtkActor* actor, const Project& project) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts, lines;
  for (const Hotspot& h : project.hotspots) {
    if (h.world_corners.size() < 3) continue;  // not placed in 3-D: no position on the map
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& c : h.world_corners) centre += c / static_cast<double>(h.world_corners.size());
    const vtkIdType id = points->InsertNextPoint(centre.x(), centre.y(), kHotspotZ);
    verts->InsertNextCell(1, &id);
    // Seen from above a quad on a wall is a line: its closed outline in plan coordinates.
    std::vector<vtkIdType> ids;
    for (const auto& c : h.world_corners) ids.push_back(points->InsertNextPoint(c.x(), c.y(), kHotspotZ));
    ids.push_back(ids.front());
    lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetVerts(verts);
  data->SetLines(lines);
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(data);
}

}  // namespace plenopath::widgets
