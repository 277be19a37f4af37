#include "app/studio/envelope_service.h"

#include <QtConcurrent>
#include <exception>

#include "processing/visibility/visibility.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

EnvelopeService::EnvelopeService(widgets::ProjectDocument& document, widgets::MapView& map, QObject* parent)
    : QObject(parent), document_(document), map_(map) {
  connect(&document_, &widgets::ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & widgets::kPlanChanged) rebuild();
  });
  connect(&watcher_, &QFutureWatcher<std::shared_ptr<const VisibilityIndex>>::finished, this, [this] {
    if (building_generation_ == generation_) {
      index_ = watcher_.result();
      if (index_) {
        std::shared_ptr<const VisibilityIndex> index = index_;
        map_.set_envelope_function([index](const Eigen::Vector2d& p) {
          const Envelope e = index->envelope(p);
          return e.status == EnvelopeStatus::ok ? e.polygon : std::vector<Eigen::Vector2d>{};
        });
        emit index_ready();
      }
    }
    if (stale_) {
      stale_ = false;
      rebuild();
    }
  });
  rebuild();
}

EnvelopeService::~EnvelopeService() { watcher_.waitForFinished(); }

void EnvelopeService::rebuild() {
  ++generation_;
  index_.reset();
  map_.set_envelope_function({});
  if (watcher_.isRunning()) {
    stale_ = true;
    return;
  }
  const FloorPlan plan = document_.project().plan;
  if (plan.occluder_segments().empty()) return;
  building_generation_ = generation_;
  watcher_.setFuture(QtConcurrent::run([plan]() -> std::shared_ptr<const VisibilityIndex> {
    try {
      return std::make_shared<const VisibilityIndex>(plan);
    } catch (const std::exception&) {
      return nullptr;  // a plan CGAL cannot take: the map just shows no envelope
    }
  }));
}

}  // namespace plenopath::studio
