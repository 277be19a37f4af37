#pragma once
// Gives the map view the envelope of the current frame from the visibility index of the current plan: the
// document's shared index (widgets/project_document.h, one per plan revision), fetched (built when nobody
// has yet) off the GUI thread whenever the plan changes; the newest plan wins
// (widgets/coalescing_runner.h).
#include <QObject>
#include <memory>

namespace plenopath {
class VisibilityIndex;
}
namespace plenopath::widgets {
class CoalescingRunner;
class MapView;
class ProjectDocument;
}  // namespace plenopath::widgets

namespace plenopath::studio {

class EnvelopeService : public QObject {
  Q_OBJECT
 public:
  EnvelopeService(widgets::ProjectDocument& document, widgets::MapView& map, QObject* parent = nullptr);
  ~EnvelopeService() override;
  bool ready() const { return index_ != nullptr; }
  // The index of the current plan, or null while it is being built (or the plan has no occluders).
  std::shared_ptr<const VisibilityIndex> index() const { return index_; }
  bool busy() const;

 signals:
  void index_ready();

 private:
  void rebuild();
  widgets::ProjectDocument& document_;
  widgets::MapView& map_;
  std::shared_ptr<const VisibilityIndex> index_;
  widgets::CoalescingRunner* runner_;
};

}  // namespace plenopath::studio
