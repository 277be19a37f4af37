#include "processing/export/tour_import.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "model/error.h"
#include "processing/capture/image_header.h"
#include "processing/export/package_reader.h"
#include "processing/export/tour_export.h"

namespace plenopath {
namespace fs = std::filesystem;

void TourImportOptions::check() const {
  if (package.empty()) throw Error("import tour: package is empty (a tour folder, tour.json or a .zip)");
  if (project_file.empty()) throw Error("import tour: project_file is empty");
  if (fs::path(project_file).filename().empty()) throw Error("import tour: project_file names no file");
}

std::string tour_media_folder(const std::string& project_file) {
  const fs::path p = fs::absolute(project_file);
  return (p.parent_path() / (p.stem().string() + "_tour")).string();
}

namespace {

// Removes the folder an import made unless the import finished.
class FolderGuard {
 public:
  explicit FolderGuard(std::string folder) : folder_(std::move(folder)) {}
  ~FolderGuard() {
    if (!kept_) {
      std::error_code ec;
      fs::remove_all(folder_, ec);
    }
  }
  void keep() { kept_ = true; }

 private:
  std::string folder_;
  bool kept_ = false;
};

}  // namespace

TourImportResult import_tour(const TourImportOptions& options, Progress& progress) {
  options.check();
  progress.checkpoint(0.0, "reading tour.json");
  const PackageReader reader(options.package);
  const std::string tour_file =
      reader.is_zip() ? reader.package() + ":tour.json" : (fs::path(reader.package()) / "tour.json").string();
  const std::optional<std::string> tour_text = reader.read("tour.json");
  if (!tour_text) throw file_error(tour_file, "missing");
  nlohmann::json tour;
  try {
    tour = nlohmann::json::parse(*tour_text);
  } catch (const nlohmann::json::exception& e) {
    throw file_error(tour_file, std::string("not valid JSON: ") + e.what());
  }
  TourImportResult result;
  result.project = project_from_tour_json(tour, tour_file);
  Project& project = result.project;

  // Which package files hold each keyframe's image and each hotspot's media.
  std::map<int, std::string> image_of_keyframe;
  for (const auto& k : tour.at("keyframes")) {
    std::string name;
    if (k.contains("full") && k["full"].is_string()) name = k["full"].get<std::string>();
    if (name.empty() && k.contains("preview") && k["preview"].is_string())
      name = k["preview"].get<std::string>();
    if (!name.empty()) image_of_keyframe[k.at("frame").get<int>()] = name;
  }
  std::set<std::string> wanted;
  for (const auto& [frame, name] : image_of_keyframe) wanted.insert(name);
  for (const Hotspot& h : project.hotspots) {
    if (!h.media.empty()) wanted.insert(h.media);
    if (hotspot_action_uses_media(h.action) && !h.action_target.empty()) wanted.insert(h.action_target);
  }

  result.media_folder = tour_media_folder(options.project_file);
  std::error_code ec;
  if (fs::exists(result.media_folder, ec) && !fs::is_empty(result.media_folder, ec))
    throw file_error(result.media_folder,
                     "already exists and is not empty; choose another project name or move it away");
  const bool made_folder = !fs::exists(result.media_folder, ec);
  fs::create_directories(result.media_folder, ec);
  if (ec) throw file_error(result.media_folder, "cannot be made: " + ec.message());
  FolderGuard guard(made_folder ? result.media_folder : std::string());

  SubProgress extracting(progress, 0.05, 0.95, "copying images");
  const std::vector<std::string> missing_list = reader.extract(wanted, result.media_folder, extracting);
  const std::set<std::string> missing(missing_list.begin(), missing_list.end());

  // The keyframes whose image arrived and reads as an image.
  std::map<int, std::string> found;  // frame -> path relative to the media folder
  int width = 0, height = 0;
  for (const auto& [frame, name] : image_of_keyframe) {
    if (missing.count(name)) {
      result.warnings.push_back("keyframe " + std::to_string(frame) + ": " + name +
                                " is not in the package; keyframe dropped");
      continue;
    }
    const ImageHeader header = read_image_header((fs::path(result.media_folder) / name).string());
    if (!header.ok) {
      result.warnings.push_back("keyframe " + std::to_string(frame) + ": " + name + ": " + header.problem +
                                "; keyframe dropped");
      continue;
    }
    if (width == 0) width = header.width, height = header.height;
    const fs::path in_images = fs::path(result.media_folder) / "images" / fs::path(name).filename();
    if (fs::path(result.media_folder) / name != in_images) {
      std::error_code copy_error;
      fs::create_directories(in_images.parent_path(), copy_error);
      fs::copy_file(fs::path(result.media_folder) / name, in_images, fs::copy_options::overwrite_existing,
                    copy_error);
      if (copy_error) throw file_error(in_images.string(), "cannot be written: " + copy_error.message());
    }
    found[frame] = name;
  }
  if (found.empty()) throw file_error(tour_file, "no keyframe image could be read from the package");

  // Keyframes: those with an image, pinned (there are no other frames to choose from).
  Keyframes kept;
  for (std::size_t i = 0; i < project.keyframes.indices.size(); ++i) {
    const int frame = project.keyframes.indices[i];
    if (!found.count(frame)) continue;
    kept.indices.push_back(frame);
    kept.rank.push_back(project.keyframes.rank[i]);
    kept.pinned.push_back(frame);
  }
  // Ranks stay a permutation of 0..n-1 in the same order.
  std::vector<std::size_t> by_rank(kept.rank.size());
  for (std::size_t i = 0; i < by_rank.size(); ++i) by_rank[i] = i;
  std::sort(by_rank.begin(), by_rank.end(),
            [&](std::size_t a, std::size_t b) { return kept.rank[a] < kept.rank[b]; });
  for (std::size_t r = 0; r < by_rank.size(); ++r) kept.rank[by_rank[r]] = static_cast<int>(r);
  project.keyframes = kept;
  result.keyframes = static_cast<int>(kept.indices.size());

  // The capture: the keyframe images; any other frame of the path shows the nearest keyframe.
  int frame_count = 0;
  for (const PathFrame& f : project.path.frames) frame_count = std::max(frame_count, f.index + 1);
  frame_count = std::max(frame_count, found.rbegin()->first + 1);
  Capture& capture = project.capture;
  capture.kind = CaptureKind::kImageFolder;
  // An image folder's frames are file names in one folder: the images' own (all keyframes of a tour are
  // under images/, and one that is not is copied there).
  capture.source = (fs::path(result.media_folder) / "images").string();
  capture.frame_count = frame_count;
  capture.width = width;
  capture.height = height;
  capture.frame_names.resize(static_cast<std::size_t>(frame_count));
  for (int i = 0; i < frame_count; ++i) {
    auto after = found.lower_bound(i);
    auto nearest = after;
    if (after == found.end() || (after != found.begin() && i - std::prev(after)->first < after->first - i))
      nearest = std::prev(after);
    capture.frame_names[static_cast<std::size_t>(i)] = fs::path(nearest->second).filename().string();
  }
  // Stills tours carry the walkable route between stills as frames of index -1.
  for (const auto& f : tour.at("path").at("frames"))
    if (f.is_array() && !f.empty() && f[0].is_number_integer() && f[0].get<int>() < 0) capture.stills = true;

  // Hotspot media: the copies; a missing one leaves the hotspot without it.
  for (Hotspot& h : project.hotspots) {
    auto resolve = [&](std::string& name, const char* what) {
      if (name.empty()) return;
      if (missing.count(name)) {
        result.warnings.push_back("hotspot " + h.id + ": its " + what + " " + name +
                                  " is not in the package; left out");
        name.clear();
        return;
      }
      ++result.media_files;
      name = (fs::path(result.media_folder) / name).string();
    };
    resolve(h.media, "media");
    if (hotspot_action_uses_media(h.action)) resolve(h.action_target, "action media");
  }

  // The tour's own sizes, so that exporting again writes the same images.
  const auto& image = tour.at("image");
  project.tour.max_size = image.value("full_width", project.tour.max_size);
  project.tour.preview_size =
      std::min(image.value("preview_width", project.tour.preview_size), project.tour.max_size);
  progress.report(1.0, "done");
  guard.keep();
  return result;
}

}  // namespace plenopath
