#pragma once
// The placements registration found for the document's path (placement.h), kept while that path is on the
// map: the runners-up of each piece (the top three but the applied one) are drawn as ghosts on the map
// (widgets/map_view.h), and a click on one applies it instead, as one undo step. Undo and redo return to
// placements seen before, with their ghosts; any other change of the path drops them.
#include <QObject>
#include <QString>
#include <utility>
#include <vector>

#include "app/studio/placement.h"

namespace plenopath::widgets {
class MapView;
class ProjectDocument;
}  // namespace plenopath::widgets

namespace plenopath::studio {

class PlacementService : public QObject {
  Q_OBJECT
 public:
  PlacementService(widgets::ProjectDocument& document, widgets::MapView& map, QObject* parent = nullptr);
  // What a task found; call after its result became the document's (the path is the placed one).
  void offer(PlacementChoices choices);
  // Applies candidate `candidate` of piece `piece` (one undo step). False when there is no such choice.
  bool pick(int piece, int candidate);
  const PlacementChoices& choices() const { return choices_; }
  static constexpr int kShownCandidates = 3;

 signals:
  void message(const QString& text);

 private:
  void on_path_changed();
  void update_ghosts();

  widgets::ProjectDocument& document_;
  widgets::MapView& map_;
  PlacementChoices choices_;
  std::vector<std::pair<std::vector<int>, CameraPath>> seen_;  // choices applied so far and their paths
};

}  // namespace plenopath::studio
