#pragma once
// What a still panorama's file says about itself (issue 20), read with exiv2: when it was taken (EXIF
// DateTimeOriginal, to order a folder of tripod stills as they were shot), where (EXIF GPS), and how it was
// projected (Google's GPano XMP, which every 360 camera and stitcher writes: a cropped or partial panorama
// is not the full sphere the stills pipeline expects).
//
// Missing metadata is normal and never an error: the fields stay empty. A file exiv2 cannot parse, or a
// tag whose value makes no sense (a month 13, a latitude of 95 degrees), leaves the fields empty and says
// why in `notes`.
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace plenopath {

struct PhotoMetadata {
  // EXIF DateTimeOriginal (plus SubSecTimeOriginal), seconds since 1970-01-01 00:00. The camera's clock is
  // local time; with OffsetTimeOriginal it is converted to UTC (time_is_utc), otherwise it is taken as it
  // reads, which orders one camera's shots right all the same.
  std::optional<double> capture_time_s;
  bool time_is_utc = false;
  // EXIF GPS position: degrees north / east, metres above sea level (0 when the file gives no altitude).
  std::optional<double> latitude_deg, longitude_deg;
  double altitude_m = 0.0;
  // GPano XMP.
  std::string projection;                     // GPano:ProjectionType, e.g. "equirectangular"; "" if absent
  std::optional<double> pose_heading_deg;     // GPano:PoseHeadingDegrees: compass heading of the image centre
  int full_width = 0, full_height = 0;        // GPano:FullPanoWidthPixels / FullPanoHeightPixels
  int cropped_width = 0, cropped_height = 0;  // GPano:CroppedAreaImageWidthPixels / ...HeightPixels
  int cropped_left = 0, cropped_top = 0;      // GPano:CroppedAreaLeftPixels / CroppedAreaTopPixels
  std::vector<std::string> notes;             // tags that were present but unusable, and why

  bool has_gps() const { return latitude_deg.has_value() && longitude_deg.has_value(); }
  // GPano says the image is only part of the full sphere (cropped), or not equirectangular: "" when it is
  // a full sphere or says nothing, else the reason, e.g. "GPano: cropped to 4000 x 1500 of 4000 x 2000".
  std::string partial_reason() const;
};

// exiv2 0.27's XMP toolkit is not thread-safe: every use of exiv2 holds this one lock (reading stills here,
// tagging exported keyframes in processing/export/keyframe_metadata.h). The first call initialises the XMP
// parser and mutes exiv2's warnings on stderr.
std::unique_lock<std::mutex> lock_exiv2();

// Reads the metadata of an image file (JPEG, PNG, TIFF, WebP; whatever exiv2 knows). Never throws: a file
// that cannot be read gives empty fields and a note.
PhotoMetadata read_photo_metadata(const std::string& path);

// "YYYY:MM:DD HH:MM:SS" (EXIF's format; '-' also accepted between the date's fields) to seconds since
// 1970-01-01 00:00 of the same clock; nullopt when malformed or out of range.
std::optional<double> parse_exif_date_time(const std::string& text);
// "+HH:MM" / "-HH:MM" (EXIF OffsetTime*) to seconds east of UTC; nullopt when malformed.
std::optional<double> parse_exif_time_offset(const std::string& text);

}  // namespace plenopath
