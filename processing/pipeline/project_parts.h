#pragma once
// Which parts of a Project a step changed (issue 17): the one definition. A pipeline step returns them with
// its project; the studio applies exactly those parts as one undo step and redraws what they feed
// (widgets/project_document.h aliases these as widgets::ChangeFlag).
namespace plenopath {

enum ProjectPart : unsigned {
  kPlanChanged = 1u << 0,
  kCaptureChanged = 1u << 1,
  kPathChanged = 1u << 2,  // the path and its tracked points (Project::path_points)
  kVisibilityChanged = 1u << 3,
  kKeyframesChanged = 1u << 4,
  kHotspotsChanged = 1u << 5,
  kSettingsChanged = 1u << 6,  // geo anchor, tour settings
  kAnchorsChanged = 1u << 7,   // the author's drift anchors
  kEverythingChanged = 0xffu,
};

}  // namespace plenopath
