// Face blur against known truth: a real photograph of a face (tests/data/faces, not made by the project)
// pasted into a rendered panorama at known places, one of them across the seam.
#include "processing/cleanplate/face_blur.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {

cv::Mat face_photo() {
  const std::string file = std::string(PLENOPATH_TEST_DATA_DIR) + "/faces/astronaut_head.jpg";
  cv::Mat face = cv::imread(file);
  if (face.empty()) throw Error(file + ": missing test fixture");
  return face;
}

// Sharpness of a region: variance of the Laplacian.
double sharpness(const cv::Mat& image, const cv::Rect& r) {
  cv::Mat grey, lap;
  cv::cvtColor(image(r), grey, cv::COLOR_BGR2GRAY);
  cv::Laplacian(grey, lap, CV_64F);
  cv::Scalar mean, sd;
  cv::meanStdDev(lap, mean, sd);
  return sd[0] * sd[0];
}

struct Pasted {
  cv::Mat image;
  std::vector<cv::Rect> faces;  // x may be negative for the one across the seam (wraps)
};

Pasted panorama_with_faces() {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  RenderOptions render;
  render.width = 2048;
  render.height = 1024;
  render.depth = false;
  PathFrame pose;
  pose.x = 4.0;
  pose.y = 6.0;
  Pasted out{render_panorama(scene, pose, render).rgb, {}};
  const cv::Mat photo = face_photo();
  // Head sizes of a person 1-2.5 m away on a 2048-wide panorama (a head is ~0.23 m: 5-13 deg).
  const std::vector<std::pair<cv::Point, int>> places = {
      {{400, 430}, 120}, {{1300, 470}, 70}, {{-40, 450}, 96}};
  for (const auto& [at, width] : places) {
    cv::Mat head;
    cv::resize(photo, head, {width, width * photo.rows / photo.cols}, 0, 0, cv::INTER_AREA);
    for (int y = 0; y < head.rows; ++y)
      for (int x = 0; x < head.cols; ++x)
        out.image.at<cv::Vec3b>(at.y + y, (at.x + x + out.image.cols) % out.image.cols) =
            head.at<cv::Vec3b>(y, x);
    out.faces.emplace_back(at.x, at.y, head.cols, head.rows);
  }
  return out;
}

// The face proper (eyes to chin) of a pasted head: its middle.
cv::Rect face_core(const cv::Rect& head, int width) {
  cv::Rect core(head.x + head.width * 3 / 10, head.y + head.height * 4 / 10, head.width * 4 / 10,
                head.height * 3 / 10);
  if (core.x < 0) core.x += width;
  return core;
}

TEST(FaceBlur, FacesAreFoundAndBlurredTheRestIsLeft) {
  const Pasted pasted = panorama_with_faces();
  const FaceBlurResult result = blur_faces(pasted.image);
  const int w = pasted.image.cols;
  ASSERT_EQ(result.faces.size(), pasted.faces.size()) << "each pasted face once, nothing else";
  for (const cv::Rect& truth : pasted.faces) {
    // A detection overlapping the pasted face's core, wrapped.
    const cv::Rect core = face_core(truth, w);
    bool found = false;
    for (const cv::Rect& f : result.faces)
      for (int shift : {0, -w, w})
        found = found || ((cv::Rect(f.x + shift, f.y, f.width, f.height) & core).area() > core.area() / 2);
    EXPECT_TRUE(found) << "face at x " << truth.x;
    if (core.x + core.width <= w) {
      const double before = sharpness(pasted.image, core), after = sharpness(result.image, core);
      std::printf("face at x %d (%d px): sharpness %.0f -> %.0f\n", truth.x, truth.width, before, after);
      EXPECT_LT(after, 0.1 * before);
    }
  }
  // Away from the faces nothing changes.
  cv::Mat near_faces = cv::Mat::zeros(pasted.image.size(), CV_8U);
  for (const cv::Rect& f : pasted.faces)
    for (int shift : {0, w}) {
      const cv::Rect grown(f.x + shift - f.width / 2, f.y - f.height / 2, 2 * f.width, 2 * f.height);
      near_faces(grown & cv::Rect(0, 0, w, pasted.image.rows)).setTo(255);
    }
  EXPECT_TRUE(std::isinf(test::masked_psnr(result.image, pasted.image, ~near_faces)));
}

TEST(FaceBlur, APanoramaWithoutFacesIsLeftAlone) {
  const FloorPlan plan = make_office_sample_plan();
  RenderOptions render;
  render.width = 2048;
  render.height = 1024;
  render.people = 6;  // the renderer's people are textured cylinders: no faces
  PathFrame pose;
  pose.x = 9.0;
  pose.y = 6.0;
  const cv::Mat image = render_panorama(build_synthetic_scene(plan), pose, render).rgb;
  const FaceBlurResult result = blur_faces(image);
  for (const cv::Rect& f : result.faces) std::printf("false face %d,%d %dx%d\n", f.x, f.y, f.width, f.height);
  EXPECT_TRUE(result.faces.empty());
  EXPECT_TRUE(std::isinf(test::masked_psnr(result.image, image, {})));
}

TEST(FaceBlur, AMissingDetectorIsAClearError) {
  FaceBlurOptions options;
  options.cascade_file = "/nonexistent/faces.xml";
  try {
    blur_faces(cv::Mat(64, 128, CV_8UC3, cv::Scalar(0)), options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/faces.xml"), std::string::npos) << e.what();
  }
  options.scale_factor = 1.0;
  EXPECT_THROW(options.check(), Error);
}

}  // namespace
}  // namespace plenopath
