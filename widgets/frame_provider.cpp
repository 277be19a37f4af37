#include "widgets/frame_provider.h"

#include <QtConcurrent>
#include <exception>
#include <opencv2/imgproc.hpp>

#include "processing/capture/frame_cache.h"
#include "processing/capture/frame_source.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {
constexpr qint64 kCacheBytes = qint64(128) << 20;
}

FrameProvider::FrameProvider(ProjectDocument& document, QObject* parent)
    : QObject(parent), document_(document) {
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & kCaptureChanged) reopen();
  });
  connect(&watcher_, &QFutureWatcher<std::pair<QImage, QString>>::finished, this, &FrameProvider::on_decoded);
  reopen();
}

FrameProvider::~FrameProvider() { watcher_.waitForFinished(); }

void FrameProvider::reopen() {
  ++generation_;
  cache_.clear();
  cache_bytes_ = 0;
  source_.reset();
  frame_cache_.reset();
  error_.clear();
  const Capture& capture = document_.project().capture;
  if (capture.empty()) {
    error_ = tr("No capture");
    return;
  }
  try {
    source_ = FrameSource::open_capture(capture);
    FrameCacheOptions options;
    options.frame_bytes_bound = std::size_t(256) << 20;
    frame_cache_ = std::make_shared<FrameCache>(source_, options);
  } catch (const std::exception& e) {
    error_ = QString::fromStdString(e.what());
  }
}

int FrameProvider::source_index_of(int position) const {
  return document_.project().capture.kept_of_frame_index(document_.frame_index_at(position));
}

QImage FrameProvider::cached(int position) const {
  for (const auto& entry : cache_)
    if (entry.first == position) return entry.second;
  return {};
}

void FrameProvider::request(int position) {
  for (int k = 0; k < cache_.size(); ++k)
    if (cache_[k].first == position) {
      cache_.move(k, 0);
      emit frame_ready(position, cache_.front().second);
      return;
    }
  if (!source_) {
    emit frame_failed(position, error_);
    return;
  }
  if (decoding_ >= 0) {
    waiting_ = position;
    return;
  }
  start(position);
}

void FrameProvider::start(int position) {
  decoding_ = position;
  decoding_generation_ = generation_;
  std::shared_ptr<FrameSource> source = source_;
  std::shared_ptr<FrameCache> cache = frame_cache_;
  const int i = source_index_of(position);
  const int direction = position >= last_position_ ? +1 : -1;
  last_position_ = position;
  watcher_.setFuture(QtConcurrent::run([source, cache, i, direction]() -> std::pair<QImage, QString> {
    try {
      if (i < 0 || i >= source->frame_count())
        return {QImage(),
                QObject::tr("frame %1 is not in the capture (%2 frames)").arg(i).arg(source->frame_count())};
      const cv::Mat bgr = cache->get(i);
      cache->prefetch(i, direction);  // decode what playback or scrubbing will ask for next
      cv::Mat rgba;
      cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
      QImage image(rgba.data, rgba.cols, rgba.rows, static_cast<int>(rgba.step), QImage::Format_RGBA8888);
      return {image.copy(), QString()};
    } catch (const std::exception& e) {
      return {QImage(), QString::fromStdString(e.what())};
    }
  }));
}

void FrameProvider::on_decoded() {
  const auto [image, message] = watcher_.result();
  const int position = decoding_;
  decoding_ = -1;
  if (decoding_generation_ == generation_) {
    if (image.isNull()) {
      emit frame_failed(position, message);
    } else {
      cache_.prepend({position, image});
      cache_bytes_ += image.sizeInBytes();
      while (cache_.size() > 1 && cache_bytes_ > kCacheBytes) {
        cache_bytes_ -= cache_.back().second.sizeInBytes();
        cache_.removeLast();
      }
      emit frame_ready(position, image);
    }
  }
  if (waiting_ >= 0) {
    const int next = std::exchange(waiting_, -1);
    request(next);
  }
}

}  // namespace plenopath::widgets
