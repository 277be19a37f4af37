#include "processing/capture/photo_metadata.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exiv2/exiv2.hpp>
#include <mutex>

namespace plenopath {
namespace {

// exiv2 0.27's XMP parser is not thread-safe by itself, and it logs warnings to stderr: one lock, muted.
std::mutex& exiv2_mutex() {
  static std::mutex m;
  return m;
}

void initialise_exiv2() {
  static std::once_flag once;
  std::call_once(once, [] {
    Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);
    Exiv2::XmpParser::initialize();
  });
}

// Days from 1970-01-01 to a civil date (proleptic Gregorian; H. Hinnant's algorithm).
long long days_from_civil(long long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long long>(doe) - 719468;
}

bool is_leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (!end || *end != '\0' || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Degrees from EXIF's three rationals (degrees, minutes, seconds); nullopt on a zero denominator or a
// value out of range.
std::optional<double> degrees_from_rationals(const Exiv2::Value& v, double limit) {
  if (v.count() < 1) return std::nullopt;
  double parts[3] = {0, 0, 0};
  for (long i = 0; i < std::min<long>(3, v.count()); ++i) {
    const Exiv2::Rational r = v.toRational(i);
    if (r.second == 0) {
      if (r.first == 0) continue;  // 0/0 is written by some cameras for "no seconds"
      return std::nullopt;
    }
    parts[i] = static_cast<double>(r.first) / static_cast<double>(r.second);
  }
  const double deg = parts[0] + parts[1] / 60.0 + parts[2] / 3600.0;
  if (!std::isfinite(deg) || deg < 0 || deg > limit) return std::nullopt;
  return deg;
}

const Exiv2::Exifdatum* find_exif(const Exiv2::ExifData& exif, const char* key, int ifd_tag = -1) {
  for (const Exiv2::Exifdatum& d : exif)
    if (d.key() == key || (ifd_tag >= 0 && d.tag() == ifd_tag && d.groupName() == "Photo")) return &d;
  return nullptr;
}

std::string xmp_text(const Exiv2::XmpData& xmp, const char* key) {
  for (const Exiv2::Xmpdatum& d : xmp)
    if (d.key() == key) return d.toString();
  return {};
}

void read_time(const Exiv2::ExifData& exif, PhotoMetadata* m) {
  const Exiv2::Exifdatum* when = find_exif(exif, "Exif.Photo.DateTimeOriginal");
  if (!when) return;
  const std::string text = when->toString();
  std::optional<double> t = parse_exif_date_time(text);
  if (!t) {
    m->notes.push_back("EXIF DateTimeOriginal \"" + text + "\" is not a date and time");
    return;
  }
  if (const Exiv2::Exifdatum* sub = find_exif(exif, "Exif.Photo.SubSecTimeOriginal")) {
    std::string digits = sub->toString();
    while (!digits.empty() && digits.back() == ' ') digits.pop_back();
    bool all_digits = !digits.empty() && digits.size() <= 9;
    for (char c : digits) all_digits = all_digits && c >= '0' && c <= '9';
    if (all_digits) *t += std::atof(("0." + digits).c_str());
  }
  if (const Exiv2::Exifdatum* offset = find_exif(exif, "Exif.Photo.OffsetTimeOriginal", 0x9011)) {
    if (const std::optional<double> east = parse_exif_time_offset(offset->toString())) {
      *t -= *east;
      m->time_is_utc = true;
    }
  }
  m->capture_time_s = t;
}

void read_gps(const Exiv2::ExifData& exif, PhotoMetadata* m) {
  const Exiv2::Exifdatum* lat = find_exif(exif, "Exif.GPSInfo.GPSLatitude");
  const Exiv2::Exifdatum* lon = find_exif(exif, "Exif.GPSInfo.GPSLongitude");
  if (!lat || !lon) return;
  const std::optional<double> la = degrees_from_rationals(lat->value(), 90.0);
  const std::optional<double> lo = degrees_from_rationals(lon->value(), 180.0);
  if (!la || !lo) {
    m->notes.push_back("EXIF GPS position is out of range or malformed: ignored");
    return;
  }
  const Exiv2::Exifdatum* lat_ref = find_exif(exif, "Exif.GPSInfo.GPSLatitudeRef");
  const Exiv2::Exifdatum* lon_ref = find_exif(exif, "Exif.GPSInfo.GPSLongitudeRef");
  const bool south = lat_ref && !lat_ref->toString().empty() && lat_ref->toString()[0] == 'S';
  const bool west = lon_ref && !lon_ref->toString().empty() && lon_ref->toString()[0] == 'W';
  m->latitude_deg = south ? -*la : *la;
  m->longitude_deg = west ? -*lo : *lo;
  if (const Exiv2::Exifdatum* alt = find_exif(exif, "Exif.GPSInfo.GPSAltitude")) {
    const Exiv2::Rational r = alt->value().toRational(0);
    if (r.second != 0) {
      m->altitude_m = static_cast<double>(r.first) / static_cast<double>(r.second);
      const Exiv2::Exifdatum* ref = find_exif(exif, "Exif.GPSInfo.GPSAltitudeRef");
      if (ref && ref->value().count() > 0 && ref->value().toLong(0) == 1) m->altitude_m = -m->altitude_m;
    }
  }
}

void read_gpano(const Exiv2::XmpData& xmp, PhotoMetadata* m) {
  m->projection = xmp_text(xmp, "Xmp.GPano.ProjectionType");
  if (const std::string h = xmp_text(xmp, "Xmp.GPano.PoseHeadingDegrees"); !h.empty()) {
    const std::optional<double> v = parse_number(h);
    if (v && *v >= 0 && *v <= 360)
      m->pose_heading_deg = *v;
    else
      m->notes.push_back("GPano:PoseHeadingDegrees \"" + h + "\" is not a heading in degrees: ignored");
  }
  const auto pixels = [&](const char* key, int* out) {
    const std::string text = xmp_text(xmp, key);
    if (text.empty()) return;
    const std::optional<double> v = parse_number(text);
    if (v && *v >= 0 && *v < 1e6 && *v == std::floor(*v))
      *out = static_cast<int>(*v);
    else
      m->notes.push_back(std::string(key + 9) + " \"" + text + "\" is not a pixel count: ignored");
  };
  pixels("Xmp.GPano.FullPanoWidthPixels", &m->full_width);
  pixels("Xmp.GPano.FullPanoHeightPixels", &m->full_height);
  pixels("Xmp.GPano.CroppedAreaImageWidthPixels", &m->cropped_width);
  pixels("Xmp.GPano.CroppedAreaImageHeightPixels", &m->cropped_height);
  pixels("Xmp.GPano.CroppedAreaLeftPixels", &m->cropped_left);
  pixels("Xmp.GPano.CroppedAreaTopPixels", &m->cropped_top);
}

}  // namespace

std::optional<double> parse_exif_date_time(const std::string& text) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, s = 0;
  char sep1 = 0, sep2 = 0;
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%4d%c%2d%c%2d %2d:%2d:%2d%n", &y, &sep1, &mo, &sep2, &d, &h, &mi, &s,
                  &consumed) != 8)
    return std::nullopt;
  if (sep1 != sep2 || (sep1 != ':' && sep1 != '-')) return std::nullopt;
  for (std::size_t i = static_cast<std::size_t>(consumed); i < text.size(); ++i)
    if (text[i] != ' ' && text[i] != '\0') return std::nullopt;
  static const int days_in_month[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (y < 1900 || y > 9999 || mo < 1 || mo > 12 || h > 23 || mi > 59 || s > 60) return std::nullopt;
  const int month_days = days_in_month[mo - 1] + (mo == 2 && is_leap(y));
  if (d < 1 || d > month_days || h < 0 || mi < 0 || s < 0) return std::nullopt;
  const long long days = days_from_civil(y, static_cast<unsigned>(mo), static_cast<unsigned>(d));
  return static_cast<double>(days * 86400LL + h * 3600LL + mi * 60LL + s);
}

std::optional<double> parse_exif_time_offset(const std::string& text) {
  int h = 0, m = 0;
  char sign = 0;
  if (std::sscanf(text.c_str(), "%c%2d:%2d", &sign, &h, &m) != 3) return std::nullopt;
  if ((sign != '+' && sign != '-') || h < 0 || h > 14 || m < 0 || m > 59) return std::nullopt;
  const double east = h * 3600.0 + m * 60.0;
  return sign == '-' ? -east : east;
}

std::string PhotoMetadata::partial_reason() const {
  if (!projection.empty() && projection != "equirectangular")
    return "GPano: projection \"" + projection + "\", not equirectangular";
  const bool cropped = full_width > 0 && full_height > 0 && cropped_width > 0 && cropped_height > 0 &&
                       (cropped_width < full_width || cropped_height < full_height);
  if (cropped)
    return "GPano: cropped to " + std::to_string(cropped_width) + " x " + std::to_string(cropped_height) +
           " of " + std::to_string(full_width) + " x " + std::to_string(full_height);
  return {};
}

std::unique_lock<std::mutex> lock_exiv2() {
  std::unique_lock<std::mutex> lock(exiv2_mutex());
  initialise_exiv2();
  return lock;
}

PhotoMetadata read_photo_metadata(const std::string& path) {
  PhotoMetadata m;
  const std::unique_lock<std::mutex> lock = lock_exiv2();
  try {
    // auto: exiv2 0.27 names the type std::auto_ptr, which clang flags as deprecated in C++17.
    auto image = Exiv2::ImageFactory::open(path);
    if (!image.get()) {
      m.notes.push_back("no metadata reader for this file");
      return m;
    }
    image->readMetadata();
    read_time(image->exifData(), &m);
    read_gps(image->exifData(), &m);
    read_gpano(image->xmpData(), &m);
  } catch (const std::exception& e) {  // Exiv2::AnyError derives from std::exception
    m = PhotoMetadata{};
    m.notes.push_back(std::string("metadata unreadable: ") + e.what());
  }
  return m;
}

}  // namespace plenopath
