#pragma once
// What an MP4/MOV file says about its 360° video: Google's Spherical Video V2 boxes in the video track's
// sample entry (sv3d > svhd, proj > prhd + equi | cbmp | mshp; st3d for stereo) and the older V1 XML
// (a 'uuid' box ffcc8263-f855-4a93-8814-587a02521fdd in the track holding GSpherical:* tags). Tells
// equirectangular files apart and gives the initial view orientation (pose yaw, pitch, roll).
// Only the moov box is read (into memory, at most kMaxMoovBytes), never the media data.
#include <cstddef>
#include <cstdint>
#include <string>

namespace plenopath {

enum class SphericalProjection { kNone, kEquirectangular, kCubemap, kMesh };
enum class StereoMode { kMono, kTopBottom, kLeftRight, kCustom };
const char* to_string(SphericalProjection projection);  // "none", "equirectangular", "cubemap", "mesh"
const char* to_string(StereoMode mode);                 // "mono", "top-bottom", "left-right", "custom"

struct SphericalVideoInfo {
  bool iso_file = false;   // the file is MP4/MOV (ISO base media) and its moov box was read
  bool spherical = false;  // its video track declares 360° video
  std::string metadata;    // "Spherical Video V2" (sv3d) or "Spherical Video V1" (XML); "" if none
  SphericalProjection projection = SphericalProjection::kNone;
  StereoMode stereo = StereoMode::kMono;
  // Initial view: the pose of the sphere relative to the camera, in degrees (V2 prhd; V1 InitialView*).
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  // Equirectangular video covering part of the sphere: the fraction of the full panorama cut away at each
  // edge (V2 equi projection bounds; V1 cropped area). All 0 for a full sphere.
  double crop_top = 0.0, crop_bottom = 0.0, crop_left = 0.0, crop_right = 0.0;
  std::string software;  // the stitching software or metadata source, if said
  int track = -1;        // which track of the moov box (0-based) the metadata belongs to

  bool equirectangular() const { return spherical && projection == SphericalProjection::kEquirectangular; }
};

constexpr std::size_t kMaxMoovBytes = 256u << 20;

// Reads the file's top-level boxes up to moov. A file that is not ISO base media (Matroska, AVI) gives
// iso_file = false. Throws Error naming the file when it cannot be read, has no moov box, or a box on the
// way to the metadata is malformed.
SphericalVideoInfo read_spherical_video_info(const std::string& path);

// The same from a moov box's payload (the bytes after its header), e.g. for fuzzing; iso_file is set.
// Throws Error (without a file name) on malformed boxes.
SphericalVideoInfo parse_spherical_moov(const uint8_t* payload, std::size_t size);

}  // namespace plenopath
