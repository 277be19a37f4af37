#pragma once
// A folder of still panoramas as a capture (issue 20): in the order they were shot and with where they
// were shot, from each file's own metadata (photo_metadata.h). Tripod stills are often renamed, merged from
// two cameras or numbered by a stitcher, so the file names alone may not give the order of the walk.
#include <string>
#include <vector>

#include "model/capture.h"

namespace plenopath {

class FrameSource;

struct StillsFolder {
  // The source's capture (capture_from_frame_source) with stills = true and
  //  - frame_names in shooting order: by EXIF DateTimeOriginal when every still has one (ties by name),
  //    otherwise as the source lists them (natural order of names);
  //  - frame_times_s: seconds after the first still, when ordered by time;
  //  - gps_track: one sample per still that carries an EXIF GPS position, at that still's time, with
  //    gps_time_offset_s the first still's time (so the GPS priors of the anchors find them); left as in
  //    `capture_in` when no still carries one.
  Capture capture;
  bool ordered_by_time = false;
  std::string order;  // e.g. "by EXIF DateTimeOriginal", "by file name: 3 of 19 stills have no time"
  int stills_with_gps = 0;
  std::vector<std::string> notes;  // per file: unusable tags, partial panoramas ("name: reason")
};

StillsFolder stills_folder(const FrameSource& source, const Capture& capture_in = {});

}  // namespace plenopath
