#include "app/studio/profile_service.h"

#include <exception>
#include <memory>

#include "processing/capture/frame_source.h"
#include "processing/sampling/depth_volume.h"
#include "processing/visibility/shared_visibility_index.h"
#include "processing/visibility/visibility.h"
#include "widgets/coalescing_runner.h"
#include "widgets/project_document.h"
#include "widgets/timeline.h"

namespace plenopath::studio {

ProfileService::ProfileService(widgets::ProjectDocument& document, widgets::TimelineStrip& strip,
                               QObject* parent)
    : QObject(parent), document_(document), strip_(strip), runner_(new widgets::CoalescingRunner(this)) {
  connect(&document_, &widgets::ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (widgets::kPathChanged | widgets::kCaptureChanged | widgets::kPlanChanged)) recompute();
  });
  recompute();
}

ProfileService::~ProfileService() = default;  // the runner cancels and waits for its worker

bool ProfileService::busy() const { return runner_->busy(); }

void ProfileService::recompute() {
  const Project& p = document_.project();
  auto path = std::make_shared<const CameraPath>(p.path);
  auto capture = std::make_shared<const Capture>(p.capture);
  // The plan's shared index, fetched (or built) on the worker.
  std::shared_ptr<const SharedVisibilityIndex> shared =
      p.plan.occluder_segments().empty() ? nullptr : document_.visibility_index();
  runner_->request([this, path, capture, shared](Progress& progress) -> widgets::CoalescingRunner::Delivery {
    auto out = std::make_shared<Profiles>();
    const int n = static_cast<int>(path->size());
    const std::shared_ptr<const VisibilityIndex> index = shared ? shared->get() : nullptr;
    if (index) {
      out->envelope_area.resize(n);
      for (int i = 0; i < n; ++i) {
        if (i % 64 == 0) progress.checkpoint(0.5 * i / n);
        // An unplaced piece has no plan position: no envelope to speak of.
        out->envelope_area[i] = path->piece_placed(path->frames[i].piece)
                                    ? index->envelope_area(path->frames[i].position())
                                    : 0.0;
      }
    }
    if (!capture->depth_folder.empty() && capture->kind == CaptureKind::kImageFolder) {
      try {
        const std::unique_ptr<FrameSource> source = FrameSource::open_capture(*capture);
        QVector<double> volume(n, 0.0);
        int found = 0;
        for (int i = 0; i < n; ++i) {
          progress.checkpoint(0.5 + 0.5 * i / n);
          const int s = path->frames[i].index;
          if (s < 0 || s >= source->frame_count() || !source->has_depth(s)) continue;
          volume[i] = depth_volume(source->read_depth(s)).star_volume;
          ++found;
        }
        if (found > 0) out->depth_volume = volume;
      } catch (const Cancelled&) {
        throw;
      } catch (const std::exception&) {
        // Unreadable depth: no curve (the capture's own checks report the files).
      }
    }
    return [this, out] {
      profiles_ = std::move(*out);
      strip_.set_profiles(profiles_.envelope_area, profiles_.depth_volume);
      emit updated();
    };
  });
}

}  // namespace plenopath::studio
