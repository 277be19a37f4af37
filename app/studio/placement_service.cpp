#include "app/studio/placement_service.h"

#include <QUndoStack>
#include <cstdio>

#include "model/error.h"
#include "processing/pipeline/visibility_step.h"
#include "widgets/document_commands.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

PlacementService::PlacementService(widgets::ProjectDocument& document, widgets::MapView& map, QObject* parent)
    : QObject(parent), document_(document), map_(map) {
  connect(&document_, &widgets::ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & widgets::kPathChanged) on_path_changed();
  });
  connect(&map_, &widgets::MapView::placement_clicked, this,
          [this](int piece, int candidate) { pick(piece, candidate); });
}

void PlacementService::offer(PlacementChoices choices) {
  choices_ = std::move(choices);
  seen_.clear();
  if (!choices_.empty()) seen_.emplace_back(choices_.choice, document_.project().path);
  update_ghosts();
}

bool PlacementService::pick(int piece, int candidate) {
  if (choices_.empty() || piece < 0 || piece >= static_cast<int>(choices_.result.pieces.size())) return false;
  const PieceRegistration& r = choices_.result.pieces[static_cast<std::size_t>(piece)];
  if (candidate < 0 || candidate >= static_cast<int>(r.candidates.size())) return false;
  std::vector<int> choice = choices_.choice;
  choice[static_cast<std::size_t>(piece)] = candidate;
  Project after = document_.snapshot();
  apply_placement(choices_, choice, &after.path, &after.path_points);
  unsigned flags = widgets::kPathChanged;
  if (std::optional<VisibilityCells> cells = cells_following_path(
          document_.project(), after.path, null_progress(), document_.visibility_index().get())) {
    after.visibility = std::move(*cells);
    flags |= widgets::kVisibilityChanged;
  }
  seen_.emplace_back(choice, after.path);
  const QString text = choices_.result.pieces.size() > 1
                           ? tr("Place piece %1 by candidate %2").arg(piece + 1).arg(candidate + 1)
                           : tr("Place path by candidate %1").arg(candidate + 1);
  document_.undo_stack()->push(new widgets::ReplacePartsCommand(document_, text, after, flags));
  const RegistrationCandidate& picked = r.candidates[static_cast<std::size_t>(candidate)];
  char line[200];
  std::snprintf(line, sizeof line,
                "candidate %d: score %.2f, %.0f %% of wall points on walls, %.0f %% seen through walls",
                candidate + 1, picked.score, 100.0 * picked.wall_share, 100.0 * picked.through_share);
  emit message(text + ": " + QString::fromUtf8(line));
  return true;
}

void PlacementService::on_path_changed() {
  if (choices_.empty()) return;
  const CameraPath& path = document_.project().path;
  for (const auto& [choice, placed] : seen_)
    if (placed == path) {  // undo or redo back to a placement seen before
      choices_.choice = choice;
      update_ghosts();
      return;
    }
  choices_ = {};  // the path changed some other way: the candidates belong to another path
  seen_.clear();
  update_ghosts();
}

void PlacementService::update_ghosts() {
  std::vector<widgets::MapPlacementGhost> ghosts;
  const bool in_pieces = choices_.result.pieces.size() > 1;
  for (std::size_t k = 0; k < choices_.result.pieces.size(); ++k) {
    const PieceRegistration& r = choices_.result.pieces[k];
    if (!r.ok) continue;
    for (int c = 0; c < std::min<int>(kShownCandidates, static_cast<int>(r.candidates.size())); ++c) {
      if (c == choices_.choice[k]) continue;
      widgets::MapPlacementGhost g;
      g.piece = r.piece;
      g.candidate = c;
      const Similarity2& t = r.candidates[static_cast<std::size_t>(c)].transform;
      for (const PathFrame& f : choices_.unplaced_path.frames)
        if (f.piece == r.piece) g.polyline.push_back(t.apply(f.position()));
      char label[80];
      if (in_pieces)
        std::snprintf(label, sizeof label, "piece %d #%d · %.2f", r.piece + 1, c + 1,
                      r.candidates[static_cast<std::size_t>(c)].score);
      else
        std::snprintf(label, sizeof label, "#%d · %.2f", c + 1,
                      r.candidates[static_cast<std::size_t>(c)].score);
      g.label = label;
      ghosts.push_back(std::move(g));
    }
  }
  map_.set_placement_ghosts(std::move(ghosts));
}

}  // namespace plenopath::studio
