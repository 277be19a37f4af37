#include "widgets/hotspot_commands.h"

#include <algorithm>
#include <utility>

#include "model/error.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

int find_hotspot(const std::vector<Hotspot>& hotspots, const std::string& id) {
  for (std::size_t i = 0; i < hotspots.size(); ++i)
    if (hotspots[i].id == id) return static_cast<int>(i);
  return -1;
}

std::string unused_hotspot_id(const std::vector<Hotspot>& hotspots) {
  for (int n = 1;; ++n) {
    const std::string id = "hotspot-" + std::to_string(n);
    if (find_hotspot(hotspots, id) < 0) return id;
  }
}

int new_hotspot_merge_session() {
  static int session = 0;
  return ++session;
}

AddHotspotCommand::AddHotspotCommand(ProjectDocument& document, Hotspot hotspot)
    : QUndoCommand(hotspot.kind == HotspotKind::kMovieTexture ? QObject::tr("New movie texture")
                                                              : QObject::tr("New event hotspot")),
      document_(document),
      hotspot_(std::move(hotspot)) {}

void AddHotspotCommand::undo() {
  document_.modify(
      [this](Project& p) {
        const int i = find_hotspot(p.hotspots, hotspot_.id);
        if (i >= 0) p.hotspots.erase(p.hotspots.begin() + i);
      },
      kHotspotsChanged);
}

void AddHotspotCommand::redo() {
  document_.modify([this](Project& p) { p.hotspots.push_back(hotspot_); }, kHotspotsChanged);
}

RemoveHotspotCommand::RemoveHotspotCommand(ProjectDocument& document, const std::string& id)
    : QUndoCommand(QObject::tr("Delete hotspot %1").arg(QString::fromStdString(id))), document_(document) {
  index_ = find_hotspot(document.project().hotspots, id);
  if (index_ < 0) throw Error("no hotspot with id '" + id + "' to delete");
  hotspot_ = document.project().hotspots[static_cast<std::size_t>(index_)];
}

void RemoveHotspotCommand::undo() {
  document_.modify(
      [this](Project& p) {
        const std::size_t at = std::min(static_cast<std::size_t>(index_), p.hotspots.size());
        p.hotspots.insert(p.hotspots.begin() + static_cast<std::ptrdiff_t>(at), hotspot_);
      },
      kHotspotsChanged);
}

void RemoveHotspotCommand::redo() {
  document_.modify(
      [this](Project& p) {
        const int i = find_hotspot(p.hotspots, hotspot_.id);
        if (i >= 0) p.hotspots.erase(p.hotspots.begin() + i);
      },
      kHotspotsChanged);
}

EditHotspotCommand::EditHotspotCommand(ProjectDocument& document, Hotspot after, const QString& text,
                                       int merge_session)
    : QUndoCommand(text), document_(document), after_(std::move(after)), merge_session_(merge_session) {
  const int i = find_hotspot(document.project().hotspots, after_.id);
  if (i < 0) throw Error("no hotspot with id '" + after_.id + "' to edit");
  before_ = document.project().hotspots[static_cast<std::size_t>(i)];
}

void EditHotspotCommand::apply(const Hotspot& value) {
  document_.modify(
      [&](Project& p) {
        const int i = find_hotspot(p.hotspots, value.id);
        if (i >= 0) p.hotspots[static_cast<std::size_t>(i)] = value;
      },
      kHotspotsChanged);
}

void EditHotspotCommand::undo() { apply(before_); }
void EditHotspotCommand::redo() { apply(after_); }

bool EditHotspotCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = static_cast<const EditHotspotCommand*>(other);
  if (merge_session_ == 0 || o->merge_session_ != merge_session_ || o->after_.id != after_.id) return false;
  after_ = o->after_;
  return true;
}

}  // namespace plenopath::widgets
