#include "processing/sampling/sampling_loss.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "model/error.h"
#include "processing/sampling/image_similarity.h"
#include "processing/sampling/polygon_iou.h"
#include "processing/util/parallel_for.h"

namespace plenopath {

PathEnvelopes compute_path_envelopes(const VisibilityIndex& index, const CameraPath& path, int threads,
                                     Progress& progress) {
  PathEnvelopes out;
  const int n = static_cast<int>(path.size());
  out.frames.resize(n);
  std::atomic<int> done{0};
  parallel_for_each(n, threads, [&](int i) {
    out.frames[i] = index.envelope(path.frames[i].position());
    const int d = ++done;
    if (d % 64 == 0) progress.checkpoint(static_cast<double>(d) / n);
  });
  progress.checkpoint(1.0);
  return out;
}

std::vector<int> stand_in_positions(const CameraPath& path, const Keyframes& keyframes) {
  const int n = static_cast<int>(path.size());
  std::vector<int> keys;  // positions of keyframes, ascending
  for (int index : keyframes.indices)
    if (const PathFrame* f = path.find_frame(index)) keys.push_back(static_cast<int>(f - path.frames.data()));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (keys.empty()) return {};
  const std::vector<double> s = path.arc_lengths();
  std::vector<int> stand_in(n);
  std::size_t k = 0;  // keys[k] is the first keyframe at or after frame i
  for (int i = 0; i < n; ++i) {
    while (k < keys.size() && keys[k] < i) ++k;
    if (k < keys.size() && keys[k] == i)
      stand_in[i] = i;
    else if (k == keys.size())
      stand_in[i] = keys.back();
    else if (k == 0)
      stand_in[i] = keys[0];
    else
      stand_in[i] = (s[i] - s[keys[k - 1]] <= s[keys[k]] - s[i]) ? keys[k - 1] : keys[k];
  }
  return stand_in;
}

GeometricLoss geometric_loss(const CameraPath& path, const Keyframes& keyframes,
                             const PathEnvelopes& envelopes, int threads) {
  if (envelopes.frames.size() != path.size())
    throw Error("geometric loss: " + std::to_string(envelopes.frames.size()) + " envelopes for a path of " +
                std::to_string(path.size()) + " frames");
  GeometricLoss loss;
  const std::vector<int> stand_in = stand_in_positions(path, keyframes);
  if (stand_in.empty()) return loss;
  std::vector<int> dropped;
  for (int i = 0; i < static_cast<int>(path.size()); ++i)
    if (stand_in[i] != i) dropped.push_back(i);
  loss.dropped = static_cast<int>(dropped.size());
  std::vector<double> value(dropped.size(), -1.0);  // -1: not evaluated
  std::vector<char> exact(dropped.size(), 1);
  parallel_for_each(static_cast<int>(dropped.size()), threads, [&](int j) {
    const Envelope& a = envelopes.frames[dropped[j]];
    const Envelope& b = envelopes.frames[stand_in[dropped[j]]];
    if (a.status != EnvelopeStatus::ok || b.status != EnvelopeStatus::ok) return;
    bool is_exact = true;
    value[j] = 1.0 - polygon_iou(a.polygon, b.polygon, &is_exact);
    exact[j] = is_exact;
  });
  std::vector<double> measured;
  for (std::size_t j = 0; j < value.size(); ++j) {
    if (value[j] < 0.0) continue;
    measured.push_back(value[j]);
    if (!exact[j]) ++loss.inexact;
  }
  loss.evaluated = static_cast<int>(measured.size());
  if (measured.empty()) return loss;
  double sum = 0.0;
  for (double v : measured) sum += v;
  loss.mean = sum / measured.size();
  std::sort(measured.begin(), measured.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * measured.size()));
  loss.p95 = measured[std::max<std::size_t>(rank, 1) - 1];
  loss.max = measured.back();
  return loss;
}

void PhotometricOptions::check() const {
  if (max_frames < 1) throw Error("photometric loss: max_frames must be >= 1");
  if (max_width < 16) throw Error("photometric loss: max_width must be >= 16");
}

PhotometricLoss photometric_loss(const CameraPath& path, const Keyframes& keyframes,
                                 const std::function<cv::Mat(int index)>& read_frame,
                                 const PhotometricOptions& options) {
  options.check();
  PhotometricLoss loss;
  const std::vector<int> stand_in = stand_in_positions(path, keyframes);
  if (stand_in.empty()) return loss;
  std::vector<int> dropped;
  for (int i = 0; i < static_cast<int>(path.size()); ++i)
    if (stand_in[i] != i) dropped.push_back(i);
  if (dropped.empty()) return loss;
  const int count = std::min<int>(options.max_frames, static_cast<int>(dropped.size()));
  auto shrink = [&](const cv::Mat& m) {
    if (m.cols <= options.max_width) return m;
    cv::Mat out;
    cv::resize(m, out, cv::Size(options.max_width, std::max(1, m.rows * options.max_width / m.cols)), 0, 0,
               cv::INTER_AREA);
    return out;
  };
  double psnr_sum = 0.0, ssim_sum = 0.0;
  loss.psnr_min_db = std::numeric_limits<double>::infinity();
  loss.ssim_min = 1.0;
  for (int k = 0; k < count; ++k) {
    // Evenly over the dropped frames (the middle of each of `count` equal shares).
    const int j = static_cast<int>((k + 0.5) * dropped.size() / count);
    const PathFrame& frame = path.frames[dropped[j]];
    const PathFrame& key = path.frames[stand_in[dropped[j]]];
    const cv::Mat a = shrink(read_frame(frame.index));
    const cv::Mat b = shrink(rotate_to_heading(read_frame(key.index), key.heading, frame.heading));
    if (a.size() != b.size() || a.type() != b.type())
      throw Error("photometric loss: frames " + std::to_string(frame.index) + " and " +
                  std::to_string(key.index) + " differ in size or type");
    const double p = std::min(psnr_db(a, b), 100.0);
    const double s = ssim(a, b);
    psnr_sum += p;
    ssim_sum += s;
    loss.psnr_min_db = std::min(loss.psnr_min_db, p);
    loss.ssim_min = std::min(loss.ssim_min, s);
    ++loss.frames;
  }
  loss.psnr_mean_db = psnr_sum / loss.frames;
  loss.ssim_mean = ssim_sum / loss.frames;
  return loss;
}

}  // namespace plenopath
