#pragma once
// Undoable edits of the document's hotspots (one QUndoCommand per edit kind). Hotspots are addressed by id,
// so commands stay valid when others are added or removed around them.
#include <QUndoCommand>
#include <string>

#include "model/hotspots.h"

namespace plenopath::widgets {

class ProjectDocument;

// A new hotspot, appended to the list.
class AddHotspotCommand : public QUndoCommand {
 public:
  AddHotspotCommand(ProjectDocument& document, Hotspot hotspot);
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  Hotspot hotspot_;
};

// Removes the hotspot with `id`; undo puts it back where it was.
class RemoveHotspotCommand : public QUndoCommand {
 public:
  RemoveHotspotCommand(ProjectDocument& document, const std::string& id);
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  Hotspot hotspot_;
  int index_ = -1;
};

// Replaces the hotspot with `after.id` by `after`. Commands with the same non-zero `merge_session` merge,
// so dragging a corner handle or typing a name is one undo step.
class EditHotspotCommand : public QUndoCommand {
 public:
  EditHotspotCommand(ProjectDocument& document, Hotspot after, const QString& text, int merge_session = 0);
  void undo() override;
  void redo() override;
  int id() const override { return 9; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  void apply(const Hotspot& value);
  ProjectDocument& document_;
  Hotspot before_;
  Hotspot after_;
  int merge_session_;
};

// The index of the hotspot with `id` in `hotspots`, or -1.
int find_hotspot(const std::vector<Hotspot>& hotspots, const std::string& id);
// An id not used by any hotspot: "hotspot-1", "hotspot-2", ...
std::string unused_hotspot_id(const std::vector<Hotspot>& hotspots);
// A fresh merge session number for EditHotspotCommand (one per drag or per editing burst).
int new_hotspot_merge_session();

}  // namespace plenopath::widgets
