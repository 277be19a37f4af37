#include "processing/export/keyframe_metadata.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exiv2/exiv2.hpp>

#include "model/error.h"
#include "processing/capture/photo_metadata.h"

namespace plenopath {
namespace {

// EXIF writes an angle as three unsigned rationals: degrees, minutes, seconds (to a millionth of a second,
// 30 micrometres on the ground).
std::string dms_rationals(double degrees_abs) {
  const long long micro_seconds = std::llround(degrees_abs * 3600.0 * 1e6);
  const long long deg = micro_seconds / (3600LL * 1000000);
  const long long min = (micro_seconds / (60LL * 1000000)) % 60;
  const long long us = micro_seconds % (60LL * 1000000);
  return std::to_string(deg) + "/1 " + std::to_string(min) + "/1 " + std::to_string(us) + "/1000000";
}

void set_value(Exiv2::ExifData& exif, const char* key, Exiv2::TypeId type, const std::string& text) {
  auto value = Exiv2::Value::create(type);  // auto: exiv2 0.27 names std::auto_ptr (deprecated)
  value->read(text);
  exif[key].setValue(value.get());
}

void write_gps(const Wgs84Position& g, const KeyframePhotoTags& tags, Exiv2::ExifData& exif) {
  set_value(exif, "Exif.GPSInfo.GPSVersionID", Exiv2::unsignedByte, "2 3 0 0");
  exif["Exif.GPSInfo.GPSLatitudeRef"] = g.latitude_deg >= 0 ? "N" : "S";
  set_value(exif, "Exif.GPSInfo.GPSLatitude", Exiv2::unsignedRational,
            dms_rationals(std::abs(g.latitude_deg)));
  exif["Exif.GPSInfo.GPSLongitudeRef"] = g.longitude_deg >= 0 ? "E" : "W";
  set_value(exif, "Exif.GPSInfo.GPSLongitude", Exiv2::unsignedRational,
            dms_rationals(std::abs(g.longitude_deg)));
  set_value(exif, "Exif.GPSInfo.GPSAltitudeRef", Exiv2::unsignedByte, g.altitude_m >= 0 ? "0" : "1");
  set_value(exif, "Exif.GPSInfo.GPSAltitude", Exiv2::unsignedRational,
            std::to_string(std::llround(std::abs(g.altitude_m) * 1000)) + "/1000");
  exif["Exif.GPSInfo.GPSMapDatum"] = "WGS-84";
  if (tags.true_north) {
    exif["Exif.GPSInfo.GPSImgDirectionRef"] = "T";
    set_value(exif, "Exif.GPSInfo.GPSImgDirection", Exiv2::unsignedRational,
              std::to_string(std::llround(tags.pose_heading_deg * 100) % 36000) + "/100");
  }
}

}  // namespace

KeyframePhotoTags keyframe_photo_tags(const Project& project, int frame) {
  const PathFrame* f = project.path.find_frame(frame);
  if (!f) throw Error("keyframe " + std::to_string(frame) + " has no pose in the path");
  KeyframePhotoTags tags;
  tags.pose_heading_deg = compass_heading_deg(project.geo, f->heading);
  tags.true_north = project.geo.valid;
  if (project.geo.valid)
    tags.position =
        wgs84_of_plan_point(project.geo, f->position(), std::max(0.0, project.capture.camera_height_m));
  return tags;
}

std::vector<unsigned char> with_photo_tags(const std::vector<unsigned char>& jpeg,
                                           const KeyframePhotoTags& tags, const std::string& name) {
  const std::unique_lock<std::mutex> lock = lock_exiv2();
  try {
    auto image = Exiv2::ImageFactory::open(jpeg.data(), static_cast<long>(jpeg.size()));
    if (!image.get()) throw Error(name + ": exiv2 does not know this image format");
    image->readMetadata();
    const int width = image->pixelWidth(), height = image->pixelHeight();
    if (width <= 0 || height <= 0) throw Error(name + ": exiv2 found no image size in the JPEG");

    // GPano: the whole sphere, nothing cropped (FullPano = CroppedArea, at 0, 0).
    Exiv2::XmpData& xmp = image->xmpData();
    xmp["Xmp.GPano.UsePanoramaViewer"] = "True";
    xmp["Xmp.GPano.ProjectionType"] = "equirectangular";
    xmp["Xmp.GPano.FullPanoWidthPixels"] = std::to_string(width);
    xmp["Xmp.GPano.FullPanoHeightPixels"] = std::to_string(height);
    xmp["Xmp.GPano.CroppedAreaImageWidthPixels"] = std::to_string(width);
    xmp["Xmp.GPano.CroppedAreaImageHeightPixels"] = std::to_string(height);
    xmp["Xmp.GPano.CroppedAreaLeftPixels"] = "0";
    xmp["Xmp.GPano.CroppedAreaTopPixels"] = "0";
    char heading[32];
    std::snprintf(heading, sizeof heading, "%.2f", tags.pose_heading_deg);
    xmp["Xmp.GPano.PoseHeadingDegrees"] = std::string(heading);

    Exiv2::ExifData& exif = image->exifData();
    exif["Exif.Image.Software"] = "Plenopath Studio";
    if (tags.position) write_gps(*tags.position, tags, exif);
    image->writeMetadata();

    Exiv2::BasicIo& io = image->io();
    if (io.open() != 0) throw Error(name + ": exiv2 cannot reopen the tagged image in memory");
    std::vector<unsigned char> out(io.size());
    io.seek(0, Exiv2::BasicIo::beg);
    const long read = io.read(out.data(), static_cast<long>(out.size()));
    io.close();
    if (read != static_cast<long>(out.size())) throw Error(name + ": exiv2 returned a short tagged image");
    return out;
  } catch (const Exiv2::AnyError& e) {
    throw Error(name + ": writing GPano/EXIF metadata failed: " + e.what());
  }
}

}  // namespace plenopath
