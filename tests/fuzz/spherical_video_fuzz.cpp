// libFuzzer entry point for the 360 video metadata reader (Spherical Video V1/V2 boxes in an MP4's moov).
#include <cstddef>
#include <cstdint>

#include "model/error.h"
#include "processing/capture/spherical_video.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    plenopath::parse_spherical_moov(data, size);
  } catch (const plenopath::Error&) {
    // A clear error is the right answer for malformed boxes.
  }
  return 0;
}
