#pragma once
// What an exported keyframe JPEG says about itself, so that photo sites and viewers (Google's, Facebook's,
// Flickr's, any GPano reader) show it as a 360 photo in the right place facing the right way: Google's
// GPano XMP (equirectangular, the full sphere, the compass heading of the centre column) and, when the
// project is georeferenced, EXIF GPS (position of the camera, and the image direction from true north).
// processing/capture/photo_metadata.h reads the same tags back.
#include <optional>
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/export/geo_tracks.h"

namespace plenopath {

struct KeyframePhotoTags {
  // GPano:PoseHeadingDegrees: compass heading of the centre column, [0, 360). From the geo-anchor's north
  // when there is one, else plan +Y taken as north (as the player's compass does).
  double pose_heading_deg = 0.0;
  bool true_north = false;                // the heading is from true north: EXIF GPSImgDirection too
  std::optional<Wgs84Position> position;  // EXIF GPS of the camera centre; only when georeferenced
};

// The tags of keyframe `frame` (a capture index with a pose in the path; Error otherwise). The camera is at
// the capture's camera height above the floor.
KeyframePhotoTags keyframe_photo_tags(const Project& project, int frame);

// The JPEG `jpeg` (encoded bytes, in memory) with the tags written into it by exiv2, whatever it held
// before of them kept; the full panorama's size is the JPEG's own. Throws Error naming `name` when exiv2
// cannot parse or write it.
std::vector<unsigned char> with_photo_tags(const std::vector<unsigned char>& jpeg,
                                           const KeyframePhotoTags& tags, const std::string& name);

}  // namespace plenopath
