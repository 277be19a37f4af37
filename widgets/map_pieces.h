#pragma once
// How the map draws a path in pieces (model/camera_path.h PathPiece): each piece in its own colour, never
// joined to the next; a piece not placed on the plan yet has no plan position, so it is drawn in a tray to
// the right of the plan (stacked from the top), where the author can see it and Ctrl+drag one of its frames
// onto the plan (one anchor with the heading, or two anchors, place it).
#include <array>

#include "model/camera_path.h"
#include "model/floor_plan.h"

namespace plenopath::widgets {

// The path with every unplaced piece moved into the tray; placed pieces as they are. Frame order and
// indices are kept, so a position into one is a position into the other.
CameraPath path_as_drawn(const CameraPath& path, const PlanExtents& plan_extents);

// Colour (RGB 0..255) of piece `piece` (a qualitative palette, cycled).
std::array<unsigned char, 3> piece_colour(int piece);

}  // namespace plenopath::widgets
