#pragma once
// The map's hotspot layer: each hotspot placed in 3-D drawn at its position seen from above (its quad's
// footprint as a thick line on the wall, and a round marker at its centre). Kept out of map_view.cpp so the
// map only creates the actor and asks for an update when hotspots change.
#include <vtkSmartPointer.h>

class vtkActor;

namespace plenopath {
struct Project;
}

namespace plenopath::widgets {

vtkSmartPointer<vtkActor> make_hotspot_marker_actor();
void update_hotspot_markers(vtkActor* actor, const Project& project);

}  // namespace plenopath::widgets
