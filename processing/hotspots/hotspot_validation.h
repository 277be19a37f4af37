#pragma once
// Checks on the document's hotspots that an author should hear about before exporting: media that is
// missing or cannot be decoded, 3-D quads that disagree with the corners marked in their frame (or are not
// planar), text with markup (always shown as plain text), actions without a usable target. Never throws
// for bad hotspots: every problem is a warning.
#include <string>
#include <vector>

#include "model/project.h"

namespace plenopath {

struct HotspotWarning {
  std::string hotspot_id;
  std::string field;    // "media", "action_target", "world_corners", "title", "trigger", "frame", ...
  std::string message;  // a sentence naming the hotspot and the problem
};

struct HotspotValidationOptions {
  double max_planarity_m = 0.05;      // 3-D corners farther (rms) from their best plane: not a planar quad
  double max_inconsistency_m = 0.10;  // quad_consistency_m between the marks (lifted onto the quad's plane in
                                      // the authoring frame) and the stored 3-D corners
  bool decode_media = true;           // open images and videos to see they decode; else existence only
  void check() const;                 // throws Error naming the bad field
};

// Problems of one hotspot (an empty list when it is fine).
std::vector<HotspotWarning> validate_hotspot(const Hotspot& hotspot, const Project& project,
                                             const HotspotValidationOptions& options = {});
// All hotspots, in order; duplicate ids are reported too.
std::vector<HotspotWarning> validate_hotspots(const Project& project,
                                              const HotspotValidationOptions& options = {});

// Whether author text looks like markup (HTML/XML tags or character entities). Such text is shown as is.
bool text_has_markup(const std::string& text);

// Media type by file extension: "image", "video", "audio", or "" when unknown.
std::string media_type_of(const std::string& file);

}  // namespace plenopath
