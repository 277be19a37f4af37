#include "app/studio/envelope_service.h"

#include "processing/visibility/shared_visibility_index.h"
#include "processing/visibility/visibility.h"
#include "widgets/coalescing_runner.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

EnvelopeService::EnvelopeService(widgets::ProjectDocument& document, widgets::MapView& map, QObject* parent)
    : QObject(parent), document_(document), map_(map), runner_(new widgets::CoalescingRunner(this)) {
  connect(&document_, &widgets::ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & widgets::kPlanChanged) rebuild();
  });
  rebuild();
}

EnvelopeService::~EnvelopeService() = default;  // the runner waits for its worker

bool EnvelopeService::busy() const { return runner_->busy(); }

void EnvelopeService::rebuild() {
  index_.reset();
  map_.set_envelope_function({});
  if (document_.project().plan.occluder_segments().empty()) {
    runner_->cancel();
    return;
  }
  std::shared_ptr<const SharedVisibilityIndex> shared = document_.visibility_index();
  runner_->request([this, shared](Progress&) -> widgets::CoalescingRunner::Delivery {
    std::shared_ptr<const VisibilityIndex> index = shared->get();  // null: a plan CGAL cannot take
    return [this, index] {
      if (!index) return;  // the map just shows no envelope
      index_ = index;
      map_.set_envelope_function([index](const Eigen::Vector2d& p) {
        const Envelope e = index->envelope(p);
        return e.status == EnvelopeStatus::ok ? e.polygon : std::vector<Eigen::Vector2d>{};
      });
      emit index_ready();
    };
  });
}

}  // namespace plenopath::studio
