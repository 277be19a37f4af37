// libFuzzer entry point for the image header probe (JPEG, PNG, TIFF, OpenEXR): it reports a problem for bad
// bytes and never throws, crashes or reads out of bounds.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "processing/capture/image_header.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const plenopath::ImageHeader h =
      plenopath::read_image_header_from_memory(std::string(reinterpret_cast<const char*>(data), size));
  if (h.ok != h.problem.empty() || h.width < 0 || h.height < 0) std::abort();
  return 0;
}
