// `plenopath stitch --rig RIG.json --in DIR --out DIR [--size 2048x1024] [--stitch-distance M]`: stitches
// the per-head images DIR/heads/<head>/NAME (as written by `plenopath render --rig`) into equirectangular
// panoramas OUT/frames/NAME (feathered blending), and copies DIR/groundtruth.json along when there is one.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/render_common.h"
#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "rig/multi_head_rig.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string rig, in, out, size = "2048x1024";
  double stitch_distance = 0.0;
  int jpeg_quality = 92;
  bool quiet = false;
};

int run(const Options& o) {
  const MultiHeadRig rig = read_rig_file(o.rig);
  StitchOptions so;
  parse_size(o.size, &so.width, &so.height, "--size");
  so.stitch_distance = o.stitch_distance;
  so.check();
  const fs::path first_head = fs::path(o.in) / "heads" / rig.heads[0].name;
  if (!fs::is_directory(first_head))
    throw file_error(first_head.string(),
                     "no such folder (expected per-head images from `plenopath render --rig`)");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(first_head)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".jpg" || ext == ".png" || ext == ".jpeg"))
      names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end(), natural_less);
  if (names.empty()) throw file_error(first_head.string(), "holds no head images");

  const StitchMaps maps = make_stitch_maps(rig, so);
  fs::create_directories(fs::path(o.out) / "frames");
  ConsoleProgress progress("stitch", o.quiet);
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::vector<cv::Mat> images;
    for (const auto& head : rig.heads) {
      const std::string file = (fs::path(o.in) / "heads" / head.name / names[i]).string();
      cv::Mat img = cv::imread(file, cv::IMREAD_COLOR);
      if (img.empty()) throw file_error(file, "missing or unreadable head image");
      if (img.cols != head.width || img.rows != head.height)
        throw file_error(file, "is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                                   " but head '" + head.name + "' is " + std::to_string(head.width) + "x" +
                                   std::to_string(head.height));
      images.push_back(img);
    }
    const std::string stem = fs::path(names[i]).stem().string();
    write_image((fs::path(o.out) / "frames" / (stem + ".jpg")).string(), stitch_heads(maps, images),
                o.jpeg_quality);
    progress.frames(static_cast<int>(i + 1), static_cast<int>(names.size()));
  }
  progress.finish();
  const fs::path truth = fs::path(o.in) / "groundtruth.json";
  const fs::path truth_out = fs::path(o.out) / "groundtruth.json";
  if (fs::exists(truth) && !(fs::exists(truth_out) && fs::equivalent(truth, truth_out)))
    fs::copy_file(truth, truth_out, fs::copy_options::overwrite_existing);
  if (!o.quiet)
    std::cerr << "stitch: " << names.size() << " panoramas in " << (fs::path(o.out) / "frames").string()
              << "\n";
  return kExitOk;
}

}  // namespace

Command add_stitch_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("stitch", "Stitch per-head images of a multi-head rig into panoramas");
  sub->add_option("--rig", o->rig, "Rig calibration (JSON)")->required();
  sub->add_option("--in", o->in, "Folder with heads/<head>/ images")->required();
  sub->add_option("--out", o->out, "Output folder (frames/ is created)")->required();
  sub->add_option("--size", o->size, "Panorama size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--stitch-distance", o->stitch_distance,
                  "Metres at which head offsets are compensated (0 = far)")
      ->capture_default_str();
  sub->add_option("--jpeg-quality", o->jpeg_quality, "JPEG quality 1..100")->capture_default_str();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() { return run(*o); }};
}

}  // namespace plenopath::cli
