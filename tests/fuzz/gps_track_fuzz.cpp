// libFuzzer entry point for the GPS track readers (GPX through expat, NMEA 0183, GeoJSON; picked by content):
// any bytes give a track whose samples are sorted, finite and on the globe, or a plenopath::Error.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "model/error.h"
#include "processing/capture/gps_track.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const plenopath::GpsTrack track =
        plenopath::parse_gps_track(std::string(reinterpret_cast<const char*>(data), size), "fuzz.gpx");
    if (track.samples.empty()) std::abort();
    double previous = -INFINITY;
    for (const plenopath::GpsSample& s : track.samples) {
      if (!std::isfinite(s.time_s) || s.time_s < previous) std::abort();
      if (!(s.latitude_deg >= -90 && s.latitude_deg <= 90 && s.longitude_deg >= -180 &&
            s.longitude_deg <= 180))
        std::abort();
      previous = s.time_s;
    }
  } catch (const plenopath::Error&) {
  }
  return 0;
}
