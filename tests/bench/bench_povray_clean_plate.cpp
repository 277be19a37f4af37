// Clean plates on a scene the project's renderer did not make (issue 24): the POV-Ray corpus's "people"
// walk (tests/bench/povray/corpus.py: a trolley capture along two legs of a corridor loop, three people
// walking past, the operator and trolley in every frame, auto-exposure drift), every 20th frame rendered
// again without people, operator and trolley: the truth. As `export --clean-plates` does it: the true
// poses (the bench measures the clean plate, not the tracker), the static depth rendered from the scene's
// DXF plan, the rig found by the tracker's static mask over the first frames. Per keyframe: PSNR in the
// people's pixels before and after, in the rig's pixels that were filled and the share filled, in all of
// the rig's pixels the plate changed (filled as the rig or replaced as a mover: a missed operator comes
// back as a ghost there), elsewhere, and the seconds. Usage: bench_povray_clean_plate [SCENE [DUMP_FOLDER
// [OPTION=VALUE ...]]]. Renders the scene first when it is not cached (POV-Ray, slow: about 10 CPU-minutes).
// Prints one JSON object with the commit, the load and a baseline measured in the same run.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/path_io.h"
#include "processing/cleanplate/clean_plate.h"
#include "processing/cleanplate/rig_from_geometry.h"
#include "processing/cleanplate/rig_mask.h"
#include "processing/plan/dxf_import.h"
#include "rig/synthetic_camera.h"
#include "tests/bench/bench_common.h"
#include "tests/processing/cleanplate/masked_psnr.h"

using namespace plenopath;
using namespace plenopath::bench;
namespace fs = std::filesystem;

namespace {

double psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  return test::masked_psnr_capped(a, b, mask);
}

double baseline_seconds() {
  cv::Mat image(512, 1024, CV_8UC3), map_x(512, 1024, CV_32F), map_y(512, 1024, CV_32F), out;
  cv::randu(image, 0, 255);
  cv::randu(map_x, 0, 1023);
  cv::randu(map_y, 0, 511);
  const auto t0 = Clock::now();
  for (int i = 0; i < 40; ++i) cv::remap(image, out, map_x, map_y, cv::INTER_CUBIC, cv::BORDER_WRAP);
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string scene_name = argc > 1 ? argv[1] : "people";
    const std::string dump = argc > 2 ? argv[2] : "";  // a folder: each keyframe's images, to look at
    const std::string corpus = std::string(PLENOPATH_SOURCE_DIR) + "/tests/bench/povray/corpus.py";
    // `corpus.py render` prints the scene's folder last, after rendering what is missing.
    std::string dir;
    if (FILE* p = popen(("/usr/bin/python3 '" + corpus + "' render " + scene_name).c_str(), "r")) {
      char buf[4096];
      while (std::fgets(buf, sizeof buf, p)) dir = buf;
      if (pclose(p) != 0) throw std::runtime_error("corpus.py render " + scene_name + " failed");
    }
    while (!dir.empty() && (dir.back() == '\n' || dir.back() == '\r')) dir.pop_back();
    const double baseline = baseline_seconds();
    const nlohmann::json truth = nlohmann::json::parse(std::ifstream(fs::path(dir) / "truth.json"));
    const CameraPath path = read_path_file((fs::path(dir) / "truth.json").string());
    const FloorPlan plan = import_dxf((fs::path(dir) / "plan.dxf").string());
    SceneOptions scene_options;
    scene_options.camera_height = truth.at("camera_height_m").get<double>();
    scene_options.wall_height = 2.6;
    const SyntheticScene plan_scene = build_synthetic_scene(plan, scene_options);

    std::map<int, cv::Mat> frames;
    auto frame = [&](int position) -> cv::Mat {
      auto it = frames.find(position);
      if (it == frames.end()) {
        const std::string file =
            (fs::path(dir) / truth["frames"][position]["file"].get<std::string>()).string();
        cv::Mat image = cv::imread(file);
        if (image.empty()) throw std::runtime_error(file + ": cannot read");
        it = frames.emplace(position, image).first;
      }
      return it->second;
    };
    const cv::Size size = frame(0).size();
    std::map<int, cv::Mat> depths;
    auto static_depth = [&](int position) -> cv::Mat {
      auto it = depths.find(position);
      if (it == depths.end()) {
        RenderOptions render;
        render.width = size.width;
        render.height = size.height;
        it = depths.emplace(position, render_panorama(plan_scene, path.frames[position], render).depth).first;
      }
      return it->second;
    };
    const auto rig_start = Clock::now();
    const cv::Mat tracker_rig =
        rig_mask_of_capture(frame, static_cast<int>(path.size()), size, std::string());
    cv::Mat rig_mask = tracker_rig;
    if (!std::getenv("NO_GEOMETRY")) {
      const CaptureStillness stillness = capture_stillness(frame, static_cast<int>(path.size()));
      rig_mask = rig_from_geometry(path, frame, static_depth, tracker_rig, stillness);
    }
    const double rig_seconds = seconds_since(rig_start);
    if (!dump.empty()) {
      fs::create_directories(dump);
      cv::Mat rig_view = frame(static_cast<int>(path.size()) / 2).clone();
      if (!rig_mask.empty()) rig_view.setTo(cv::Scalar(0, 255, 0), rig_mask);
      if (!tracker_rig.empty()) rig_view.setTo(cv::Scalar(255, 0, 255), tracker_rig);
      cv::imwrite((fs::path(dump) / "rig.png").string(), rig_view);  // magenta: tracker's, green: found
    }

    // The truths: each truth frame without people and rig ("clean"), and without people only: the people's
    // pixels are where the frame differs from the second, the rig's where the second differs from the first.
    struct Truth {
      int index;
      cv::Mat clean, no_people;
    };
    std::vector<Truth> truths;
    if (truth.contains("truth_variants") && rig_mask.empty())
      throw std::runtime_error("no rig found in " + dir);
    // A scene without truth variants: the rig alone (the dump's rig.png), no keyframe measured.
    const nlohmann::json variants = truth.contains("truth_variants")
                                        ? truth["truth_variants"]
                                        : nlohmann::json{{"clean", {{"frames", {}}}}};
    for (std::size_t i = 0; i < variants.at("clean").at("frames").size(); ++i) {
      Truth t;
      t.index = variants["clean"]["frames"][i].at("index").get<int>();
      for (const auto& [name, image] :
           {std::pair<const char*, cv::Mat*>{"clean", &t.clean}, {"no_people", &t.no_people}}) {
        const std::string file =
            (fs::path(dir) / variants[name]["frames"][i].at("file").get<std::string>()).string();
        *image = cv::imread(file);
        if (image->empty()) throw std::runtime_error("missing truth frame " + file);
      }
      truths.push_back(t);
    }

    CleanPlateOptions options;
    options.camera_height_m = scene_options.camera_height;
    // Further arguments NAME=VALUE set options, to compare them within one run's conditions.
    for (int i = 3; i < argc; ++i) {
      const std::string arg = argv[i];
      const auto eq = arg.find('=');
      const std::string name = arg.substr(0, eq);
      const double value = eq == std::string::npos ? 1.0 : std::stod(arg.substr(eq + 1));
      if (name == "max_explained_share")
        options.max_explained_share = value;
      else if (name == "max_spread")
        options.max_spread = static_cast<int>(value);
      else if (name == "detect_rig")
        options.detect_rig = value != 0;
      else if (name == "neighbours")
        options.neighbours = static_cast<int>(value);
      else if (name == "max_baseline_m")
        options.max_baseline_m = value;
      else
        throw std::runtime_error("unknown option " + name);
    }
    options.check();
    nlohmann::json keyframes = nlohmann::json::array();
    double total_seconds = 0, worst_people = 99, worst_rig = 99, least_filled = 100, worst_rig_replaced = 99,
           worst_elsewhere = 99;
    int with_people = 0;
    for (const Truth& t : truths) {
      const int k = t.index;
      const cv::Mat& clean = t.clean;
      if (k < 10 || k + 10 >= static_cast<int>(path.size())) continue;  // a walk's ends have one side only
      for (int j = std::max(0, k - 60); j < std::min<int>(path.size(), k + 60); ++j)
        frame(j), static_depth(j);
      const auto t0 = Clock::now();
      const CleanPlate plate = clean_plate(path, k, frame, static_depth, rig_mask, options);
      const double seconds = seconds_since(t0);
      total_seconds += seconds;
      const cv::Mat original = frame(k);
      const cv::Mat differs = test::differing_pixels(original, clean, 8);
      const cv::Mat people = test::differing_pixels(original, t.no_people, 8);
      const cv::Mat rig_truth = test::differing_pixels(t.no_people, clean, 8);
      const cv::Mat filled = rig_truth & plate.rig_filled;
      // Everything of the rig the plate changed, as a mover or as the rig: an operator the rig mask missed
      // is replaced by the other frames' median, which may show the operator again (a ghost).
      const cv::Mat replaced = rig_truth & (plate.rig_filled | plate.moving_mask);
      cv::Mat near_change;
      cv::dilate(differs, near_change, cv::Mat(), cv::Point(-1, -1), 3);
      const int people_px = cv::countNonZero(people);
      const double filled_pct = 100.0 * cv::countNonZero(filled) / std::max(1, cv::countNonZero(rig_truth));
      const double people_after = psnr(plate.image, clean, people),
                   rig_after = psnr(plate.image, clean, filled);
      keyframes.push_back({{"keyframe", k},
                           {"people_pixels", people_px},
                           {"psnr_people_before_db", psnr(original, clean, people)},
                           {"psnr_people_after_db", people_after},
                           {"rig_pixels", cv::countNonZero(rig_truth)},
                           {"rig_filled_pct", filled_pct},
                           {"psnr_rig_before_db", psnr(original, clean, filled)},
                           {"psnr_rig_filled_db", rig_after},
                           {"rig_replaced_pct",
                            100.0 * cv::countNonZero(replaced) / std::max(1, cv::countNonZero(rig_truth))},
                           {"psnr_rig_replaced_db", psnr(plate.image, clean, replaced)},
                           {"psnr_elsewhere_before_db", psnr(original, clean, ~near_change)},
                           {"psnr_elsewhere_after_db", psnr(plate.image, clean, ~near_change)},
                           {"replaced_pct", 100 * plate.moving_share},
                           {"seconds", seconds},
                           {"ratio_to_baseline", seconds / baseline}});
      if (!dump.empty()) {
        fs::create_directories(dump);
        const std::string stem = (fs::path(dump) / std::to_string(k)).string();
        cv::imwrite(stem + "_original.png", original);
        cv::imwrite(stem + "_truth.png", clean);
        cv::imwrite(stem + "_plate.png", plate.image);
        cv::Mat masks;
        const cv::Mat rig_used = plate.detected_rig.empty() ? rig_mask : (rig_mask | plate.detected_rig);
        cv::merge(std::vector<cv::Mat>{plate.moving_mask, rig_used, people},
                  masks);  // B moving, G rig, R people
        cv::imwrite(stem + "_masks.png", masks);
      }
      if (people_px > 300) {
        ++with_people;
        worst_people = std::min(worst_people, people_after);
      }
      worst_rig = std::min(worst_rig, rig_after);
      worst_rig_replaced = std::min(worst_rig_replaced, psnr(plate.image, clean, replaced));
      worst_elsewhere = std::min(worst_elsewhere, psnr(plate.image, clean, ~near_change));
      least_filled = std::min(least_filled, filled_pct);
      // Frames far behind are not needed again.
      for (auto it = frames.begin(); it != frames.end();)
        it = it->first < k - 60 ? frames.erase(it) : std::next(it);
      for (auto it = depths.begin(); it != depths.end();)
        it = it->first < k - 60 ? depths.erase(it) : std::next(it);
    }
    const nlohmann::json out = {
        {"benchmark", "povray_clean_plate"},
        {"scene", scene_name},
        {"commit", git_commit()},
        {"load_average", load_average()},
        {"size", std::to_string(size.width) + "x" + std::to_string(size.height)},
        {"baseline_seconds", baseline},
        {"rig_mask_pct", 100.0 * cv::countNonZero(rig_mask) / double(rig_mask.total())},
        {"rig_mask_seconds", rig_seconds},
        {"seconds_per_keyframe", keyframes.empty() ? 0.0 : total_seconds / keyframes.size()},
        {"keyframes_with_people", with_people},
        {"worst_psnr_people_db", worst_people},
        {"worst_psnr_rig_filled_db", worst_rig},
        {"least_rig_filled_pct", least_filled},
        {"worst_psnr_rig_replaced_db", worst_rig_replaced},
        {"worst_psnr_elsewhere_db", worst_elsewhere},
        {"keyframes", keyframes}};
    std::cout << out.dump() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "bench_povray_clean_plate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
