#include "app/studio/profile_service.h"

#include <QtConcurrent>
#include <exception>

#include "app/studio/envelope_service.h"
#include "processing/capture/frame_source.h"
#include "processing/sampling/depth_volume.h"
#include "processing/visibility/visibility.h"
#include "widgets/project_document.h"
#include "widgets/timeline.h"

namespace plenopath::studio {

ProfileService::ProfileService(widgets::ProjectDocument& document, EnvelopeService& envelopes,
                               widgets::TimelineStrip& strip, QObject* parent)
    : QObject(parent), document_(document), envelopes_(envelopes), strip_(strip) {
  connect(&document_, &widgets::ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (widgets::kPathChanged | widgets::kCaptureChanged | widgets::kPlanChanged)) recompute();
  });
  connect(&envelopes_, &EnvelopeService::index_ready, this, &ProfileService::recompute);
  connect(&watcher_, &QFutureWatcher<Profiles>::finished, this, [this] {
    if (again_) {
      again_ = false;
      recompute();
      return;
    }
    profiles_ = watcher_.result();
    strip_.set_profiles(profiles_.envelope_area, profiles_.depth_volume);
    emit updated();
  });
  recompute();
}

ProfileService::~ProfileService() {
  if (stop_) *stop_ = true;
  watcher_.waitForFinished();
}

void ProfileService::recompute() {
  if (watcher_.isRunning()) {
    *stop_ = true;
    again_ = true;
    return;
  }
  stop_ = std::make_shared<std::atomic<bool>>(false);
  const CameraPath path = document_.project().path;
  const Capture capture = document_.project().capture;
  const std::shared_ptr<const VisibilityIndex> index = envelopes_.index();
  const std::shared_ptr<std::atomic<bool>> stop = stop_;
  watcher_.setFuture(QtConcurrent::run([path, capture, index, stop]() {
    Profiles out;
    const int n = static_cast<int>(path.size());
    if (index) {
      out.envelope_area.resize(n);
      for (int i = 0; i < n && !*stop; ++i)
        // An unplaced piece has no plan position: no envelope to speak of.
        out.envelope_area[i] =
            path.piece_placed(path.frames[i].piece) ? index->envelope_area(path.frames[i].position()) : 0.0;
    }
    if (!capture.depth_folder.empty() && capture.kind == CaptureKind::kImageFolder) {
      try {
        const std::unique_ptr<FrameSource> source = FrameSource::open_capture(capture);
        QVector<double> volume(n, 0.0);
        int found = 0;
        for (int i = 0; i < n && !*stop; ++i) {
          const int s = path.frames[i].index;
          if (s < 0 || s >= source->frame_count() || !source->has_depth(s)) continue;
          volume[i] = depth_volume(source->read_depth(s)).star_volume;
          ++found;
        }
        if (found > 0) out.depth_volume = volume;
      } catch (const std::exception&) {
        // Unreadable depth: no curve (the capture's own checks report the files).
      }
    }
    return out;
  }));
}

}  // namespace plenopath::studio
