#include "processing/capture/spherical_video.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "model/error.h"
#include "processing/capture/mp4_boxes.h"

namespace plenopath {

const char* to_string(SphericalProjection projection) {
  switch (projection) {
    case SphericalProjection::kNone:
      return "none";
    case SphericalProjection::kEquirectangular:
      return "equirectangular";
    case SphericalProjection::kCubemap:
      return "cubemap";
    case SphericalProjection::kMesh:
      return "mesh";
  }
  return "none";
}

const char* to_string(StereoMode mode) {
  switch (mode) {
    case StereoMode::kMono:
      return "mono";
    case StereoMode::kTopBottom:
      return "top-bottom";
    case StereoMode::kLeftRight:
      return "left-right";
    case StereoMode::kCustom:
      return "custom";
  }
  return "mono";
}

namespace {

// The V1 metadata's box: uuid ffcc8263-f855-4a93-8814-587a02521fdd.
constexpr uint8_t kSphericalV1Uuid[16] = {0xff, 0xcc, 0x82, 0x63, 0xf8, 0x55, 0x4a, 0x93,
                                          0x88, 0x14, 0x58, 0x7a, 0x02, 0x52, 0x1f, 0xdd};
constexpr std::size_t kVisualSampleEntryHeader = 78;  // reserved, sizes, resolution, compressor name, depth
constexpr std::size_t kMaxV1XmlBytes = 1u << 20;

std::vector<Mp4Box> children(const Mp4Box& box, const std::string& where) {
  return mp4_child_boxes(box.payload, box.payload_size, where);
}

std::string handler_type(const Mp4Box& hdlr, const std::string& where) {
  Mp4Reader r(hdlr.payload, hdlr.payload_size, where);
  r.skip(4 + 4);  // version and flags, pre_defined (QuickTime: component type)
  std::string type(4, ' ');
  for (char& c : type) c = static_cast<char>(r.u8());
  return type;
}

double fixed_16_16(int32_t v) { return v / 65536.0; }
double fixed_0_32(uint32_t v) { return v / 4294967296.0; }

// Spherical Video V2: sv3d { svhd, proj { prhd, equi | cbmp | mshp } }.
void read_sv3d(const Mp4Box& sv3d, const std::string& where, SphericalVideoInfo* info) {
  info->spherical = true;
  info->metadata = "Spherical Video V2";
  const std::vector<Mp4Box> boxes = children(sv3d, where);
  if (const Mp4Box* svhd = find_mp4_box(boxes, "svhd")) {
    Mp4Reader r(svhd->payload, svhd->payload_size, where + "/svhd");
    r.skip(4);
    info->software = r.text_until_nul();
  }
  const Mp4Box* proj = find_mp4_box(boxes, "proj");
  if (!proj) throw Error(where + ": no 'proj' box (the projection)");
  const std::string proj_where = where + "/proj";
  const std::vector<Mp4Box> parts = children(*proj, proj_where);
  if (const Mp4Box* prhd = find_mp4_box(parts, "prhd")) {
    Mp4Reader r(prhd->payload, prhd->payload_size, proj_where + "/prhd");
    r.skip(4);
    info->yaw_deg = fixed_16_16(r.i32());
    info->pitch_deg = fixed_16_16(r.i32());
    info->roll_deg = fixed_16_16(r.i32());
  }
  if (const Mp4Box* equi = find_mp4_box(parts, "equi")) {
    Mp4Reader r(equi->payload, equi->payload_size, proj_where + "/equi");
    r.skip(4);
    info->projection = SphericalProjection::kEquirectangular;
    info->crop_top = fixed_0_32(r.u32());
    info->crop_bottom = fixed_0_32(r.u32());
    info->crop_left = fixed_0_32(r.u32());
    info->crop_right = fixed_0_32(r.u32());
    if (info->crop_top + info->crop_bottom >= 1.0 || info->crop_left + info->crop_right >= 1.0)
      throw Error(proj_where + "/equi: the projection bounds leave no picture");
  } else if (find_mp4_box(parts, "cbmp")) {
    info->projection = SphericalProjection::kCubemap;
  } else if (find_mp4_box(parts, "mshp")) {
    info->projection = SphericalProjection::kMesh;
  }
}

void read_st3d(const Mp4Box& st3d, const std::string& where, SphericalVideoInfo* info) {
  Mp4Reader r(st3d.payload, st3d.payload_size, where);
  r.skip(4);
  switch (r.u8()) {
    case 0:
      info->stereo = StereoMode::kMono;
      break;
    case 1:
      info->stereo = StereoMode::kTopBottom;
      break;
    case 2:
      info->stereo = StereoMode::kLeftRight;
      break;
    default:
      info->stereo = StereoMode::kCustom;
      break;
  }
}

// The value of a GSpherical:NAME element (or attribute) in V1 XML; false if absent.
bool v1_value(const std::string& xml, const std::string& name, std::string* value) {
  const std::string key = "GSpherical:" + name;
  for (std::size_t at = xml.find(key); at != std::string::npos; at = xml.find(key, at + 1)) {
    if (at > 0 && xml[at - 1] == '/') continue;  // a closing tag
    std::size_t p = at + key.size();
    while (p < xml.size() && std::isspace(static_cast<unsigned char>(xml[p]))) ++p;
    if (p >= xml.size()) return false;
    std::size_t end = std::string::npos;
    if (xml[p] == '>') {
      end = xml.find('<', ++p);
    } else if (xml[p] == '=' && p + 1 < xml.size() && (xml[p + 1] == '"' || xml[p + 1] == '\'')) {
      const char quote = xml[p + 1];
      p += 2;
      end = xml.find(quote, p);
    } else {
      continue;  // a longer name that starts with this one
    }
    if (end == std::string::npos) return false;
    std::string v = xml.substr(p, end - p);
    const std::size_t b = v.find_first_not_of(" \t\r\n"), e = v.find_last_not_of(" \t\r\n");
    *value = b == std::string::npos ? "" : v.substr(b, e - b + 1);
    return true;
  }
  return false;
}

double v1_number(const std::string& xml, const std::string& name, const std::string& where, double fallback) {
  std::string text;
  if (!v1_value(xml, name, &text)) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw Error(where + ": GSpherical:" + name + " is not a number ('" + text.substr(0, 40) + "')");
  return v;
}

bool v1_true(const std::string& xml, const std::string& name) {
  std::string v;
  if (!v1_value(xml, name, &v)) return false;
  for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return v == "true";
}

// Spherical Video V1: GSpherical:* XML in the track's uuid box.
void read_v1(const Mp4Box& uuid, const std::string& where, SphericalVideoInfo* info) {
  const std::string xml(reinterpret_cast<const char*>(uuid.payload),
                        std::min(uuid.payload_size, kMaxV1XmlBytes));
  if (!v1_true(xml, "Spherical")) return;
  std::string projection;
  v1_value(xml, "ProjectionType", &projection);
  info->spherical = true;
  info->metadata = "Spherical Video V1";
  info->projection =
      projection == "equirectangular" ? SphericalProjection::kEquirectangular : SphericalProjection::kNone;
  v1_value(xml, "StitchingSoftware", &info->software);
  std::string stereo;
  if (v1_value(xml, "StereoMode", &stereo))
    info->stereo = stereo == "top-bottom"   ? StereoMode::kTopBottom
                   : stereo == "left-right" ? StereoMode::kLeftRight
                                            : StereoMode::kMono;
  info->yaw_deg = v1_number(xml, "InitialViewHeadingDegrees", where, 0.0);
  info->pitch_deg = v1_number(xml, "InitialViewPitchDegrees", where, 0.0);
  info->roll_deg = v1_number(xml, "InitialViewRollDegrees", where, 0.0);
  const double full_w = v1_number(xml, "FullPanoWidthPixels", where, 0.0);
  const double full_h = v1_number(xml, "FullPanoHeightPixels", where, 0.0);
  if (full_w > 0 && full_h > 0) {
    const double w = v1_number(xml, "CroppedAreaImageWidthPixels", where, full_w);
    const double h = v1_number(xml, "CroppedAreaImageHeightPixels", where, full_h);
    const double left = v1_number(xml, "CroppedAreaLeftPixels", where, 0.0);
    const double top = v1_number(xml, "CroppedAreaTopPixels", where, 0.0);
    if (w <= 0 || h <= 0 || left < 0 || top < 0 || left + w > full_w || top + h > full_h)
      throw Error(where + ": the cropped area does not lie inside the full panorama");
    info->crop_left = left / full_w;
    info->crop_right = 1.0 - (left + w) / full_w;
    info->crop_top = top / full_h;
    info->crop_bottom = 1.0 - (top + h) / full_h;
  }
}

// The video track's sample entries (stsd): V2 boxes beside the codec configuration.
void read_sample_entries(const Mp4Box& stsd, const std::string& where, SphericalVideoInfo* info) {
  Mp4Reader r(stsd.payload, stsd.payload_size, where);
  r.skip(4);  // version, flags
  r.u32();    // entry count: the boxes that follow say it too
  for (const Mp4Box& entry : mp4_child_boxes(r.here(), r.remaining(), where)) {
    const std::string entry_where = where + "/" + entry.type;
    if (entry.payload_size < kVisualSampleEntryHeader)
      throw Error(entry_where + ": sample entry of " + std::to_string(entry.payload_size) +
                  " bytes, shorter than a video sample entry's " + std::to_string(kVisualSampleEntryHeader));
    const std::vector<Mp4Box> boxes = mp4_child_boxes(
        entry.payload + kVisualSampleEntryHeader, entry.payload_size - kVisualSampleEntryHeader, entry_where);
    if (const Mp4Box* st3d = find_mp4_box(boxes, "st3d")) read_st3d(*st3d, entry_where + "/st3d", info);
    if (const Mp4Box* sv3d = find_mp4_box(boxes, "sv3d")) {
      read_sv3d(*sv3d, entry_where + "/sv3d", info);
      return;
    }
  }
}

}  // namespace

SphericalVideoInfo parse_spherical_moov(const uint8_t* payload, std::size_t size) {
  SphericalVideoInfo first_video;
  first_video.iso_file = true;
  bool have_video = false;
  int track = -1;
  for (const Mp4Box& trak : mp4_child_boxes(payload, size, "moov")) {
    if (trak.type != "trak") continue;
    ++track;
    const std::string where = "moov/trak[" + std::to_string(track) + "]";
    const std::vector<Mp4Box> trak_boxes = children(trak, where);
    const Mp4Box* mdia = find_mp4_box(trak_boxes, "mdia");
    if (!mdia) continue;
    const std::vector<Mp4Box> mdia_boxes = children(*mdia, where + "/mdia");
    const Mp4Box* hdlr = find_mp4_box(mdia_boxes, "hdlr");
    if (!hdlr || handler_type(*hdlr, where + "/mdia/hdlr") != "vide") continue;

    SphericalVideoInfo info;
    info.iso_file = true;
    info.track = track;
    for (const Mp4Box& b : trak_boxes)
      if (b.type == "uuid" && std::memcmp(b.uuid, kSphericalV1Uuid, 16) == 0)
        read_v1(b, where + "/uuid", &info);
    // V2 supersedes V1 where both are present.
    if (const Mp4Box* minf = find_mp4_box(mdia_boxes, "minf")) {
      const std::vector<Mp4Box> minf_boxes = children(*minf, where + "/mdia/minf");
      if (const Mp4Box* stbl = find_mp4_box(minf_boxes, "stbl")) {
        const std::string stbl_where = where + "/mdia/minf/stbl";
        const std::vector<Mp4Box> stbl_boxes = children(*stbl, stbl_where);
        if (const Mp4Box* stsd = find_mp4_box(stbl_boxes, "stsd"))
          read_sample_entries(*stsd, stbl_where + "/stsd", &info);
      }
    }
    if (info.spherical) return info;
    if (!have_video) first_video = info, have_video = true;
  }
  return first_video;
}

SphericalVideoInfo read_spherical_video_info(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, "cannot open the file");
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  if (file_size < 0) throw file_error(path, "cannot read the file");
  in.seekg(0);
  SphericalVideoInfo info;
  uint64_t at = 0;
  for (std::size_t count = 0; at + 8 <= static_cast<uint64_t>(file_size); ++count) {
    if (count >= kMaxMp4ChildBoxes)
      throw file_error(path, "more than " + std::to_string(count) + " top-level boxes");
    uint8_t header[16];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(header), 8)) throw file_error(path, "cannot read the file");
    const std::string type(reinterpret_cast<const char*>(header + 4), 4);
    uint64_t size = (uint64_t(header[0]) << 24) | (uint64_t(header[1]) << 16) | (uint64_t(header[2]) << 8) |
                    uint64_t(header[3]);
    uint64_t header_size = 8;
    if (count == 0) {
      // Matroska, AVI and others start otherwise: not ours to read.
      static const char* const kFirstBoxes[] = {"ftyp", "moov", "mdat", "free",
                                                "skip", "wide", "pnot", "styp"};
      bool known = false;
      for (const char* t : kFirstBoxes) known = known || type == t;
      if (!known) return info;
    }
    if (size == 1) {
      if (at + 16 > static_cast<uint64_t>(file_size) || !in.read(reinterpret_cast<char*>(header + 8), 8))
        throw file_error(path, "box '" + type + "' is cut short in its 64-bit size");
      size = 0;
      for (int k = 8; k < 16; ++k) size = (size << 8) | header[k];
      header_size = 16;
    } else if (size == 0) {
      size = static_cast<uint64_t>(file_size) - at;
    }
    if (size < header_size || size > static_cast<uint64_t>(file_size) - at)
      throw file_error(path, "top-level box '" + type + "' at byte " + std::to_string(at) + " says it has " +
                                 std::to_string(size) + " bytes; the file has " +
                                 std::to_string(static_cast<uint64_t>(file_size) - at) + " from there");
    if (type == "moov") {
      const uint64_t payload_size = size - header_size;
      if (payload_size > kMaxMoovBytes)
        throw file_error(path, "the moov box has " + std::to_string(payload_size >> 20) +
                                   " MB, more than the " + std::to_string(kMaxMoovBytes >> 20) +
                                   " MB read for its metadata");
      std::vector<uint8_t> moov(static_cast<std::size_t>(payload_size));
      in.seekg(static_cast<std::streamoff>(at + header_size));
      if (!in.read(reinterpret_cast<char*>(moov.data()), static_cast<std::streamsize>(moov.size())))
        throw file_error(path, "cannot read the moov box");
      try {
        return parse_spherical_moov(moov.data(), moov.size());
      } catch (const Error& e) {
        throw file_error(path, std::string("malformed metadata: ") + e.what());
      }
    }
    at += size;
  }
  throw file_error(path, "an MP4/MOV file without a moov box (cut short while recording?)");
}

}  // namespace plenopath
