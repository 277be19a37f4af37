// An angle written in degrees and read back writes the same digits again (issue 17: the command line reads
// back what each step wrote, the studio keeps the angle in memory; both must write the same bytes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "model/camera_path.h"

namespace plenopath {
namespace {

TEST(AngleRoundTrip, WrittenDegreesReadBackWriteTheSameDigits) {
  // Headings spread over (-pi, pi] by a fixed 64-bit LCG (no seed to vary), and some hand-picked ones.
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  int plain_mismatches = 0;
  for (int i = 0; i < 20000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double h = (static_cast<double>(state >> 11) / 9007199254740992.0 * 2.0 - 1.0) * M_PI;
    const double written = degrees(h);
    if (degrees(radians(written)) != written) ++plain_mismatches;
    ASSERT_EQ(degrees(radians_of_written(written)), written) << "heading " << h;
    EXPECT_LE(std::abs(radians_of_written(written) - radians(written)),
              4 * std::abs(std::nextafter(h, 10.0) - h))
        << "heading " << h;
  }
  // The plain conversion does lose the last bit now and then: what this guards against.
  EXPECT_GT(plain_mismatches, 0);
  for (const double d : {0.0, 90.0, -90.0, 180.0, 45.0, -152.4671819563141, 37.667497818012414})
    EXPECT_EQ(degrees(radians_of_written(d)), d) << d;
}

}  // namespace
}  // namespace plenopath
