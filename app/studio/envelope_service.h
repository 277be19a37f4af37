#pragma once
// Keeps a visibility index of the current plan (built off the GUI thread whenever the plan changes) and
// gives the map view the envelope of the current frame from it.
#include <QFutureWatcher>
#include <QObject>
#include <memory>

namespace plenopath {
class VisibilityIndex;
}
namespace plenopath::widgets {
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

 signals:
  void index_ready();

 private:
  void rebuild();
  widgets::ProjectDocument& document_;
  widgets::MapView& map_;
  std::shared_ptr<const VisibilityIndex> index_;
  QFutureWatcher<std::shared_ptr<const VisibilityIndex>> watcher_;
  unsigned generation_ = 0;
  unsigned building_generation_ = 0;
  bool stale_ = false;
};

}  // namespace plenopath::studio
