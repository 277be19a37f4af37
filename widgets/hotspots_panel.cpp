#include "widgets/hotspots_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QScrollArea>
#include <QStyle>
#include <QTimer>
#include <QUndoStack>
#include <QVBoxLayout>
#include <exception>

#include "model/hotspots.h"
#include "widgets/hotspot_commands.h"
#include "widgets/hotspot_editor.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

QString target_hint(HotspotAction action) {
  switch (action) {
    case HotspotAction::kSwapImage:
      return QObject::tr(
          "image shown instead of the region, or a video of an image sequence (played once, then "
          "held; `plenopath encode-video` makes one from frames)");
    case HotspotAction::kPlayVideo:
      return QObject::tr("video file (empty: the movie texture's own video)");
    case HotspotAction::kPlaySound:
      return QObject::tr("sound file");
    case HotspotAction::kJump:
      return QObject::tr("frame number, or another tour's http(s) address");
    case HotspotAction::kOpenUrl:
      return QObject::tr("http(s) address");
    case HotspotAction::kShowText:
      return QObject::tr("text shown as plain text");
    case HotspotAction::kNone:
      break;
  }
  return QString();
}

}  // namespace

HotspotsPanel::HotspotsPanel(ProjectDocument& document, HotspotEditor& editor, QWidget* parent)
    : QWidget(parent),
      document_(document),
      editor_(editor),
      list_(new QListWidget(this)),
      title_(new QLineEdit(this)),
      kind_(new QComboBox(this)),
      media_(new QLineEdit(this)),
      choose_media_(new QPushButton(tr("Choose…"), this)),
      trigger_(new QComboBox(this)),
      distance_(new QDoubleSpinBox(this)),
      action_(new QComboBox(this)),
      target_(new QLineEdit(this)),
      choose_target_(new QPushButton(tr("Choose…"), this)),
      info_(new QLabel(this)),
      warning_text_(new QLabel(this)),
      summary_(new QLabel(this)),
      goto_(new QPushButton(tr("Go to"), this)),
      delete_(new QPushButton(style()->standardIcon(QStyle::SP_TrashIcon), tr("Delete"), this)),
      play_(new QCheckBox(tr("Play videos in the preview"), this)),
      validate_timer_(new QTimer(this)) {
  setObjectName("hotspots_panel");
  ask_file = [this](const QString& what, const QString& current) {
    const QString filter =
        what == "media" ? tr("Images and videos (*.png *.jpg *.jpeg *.webp *.gif *.bmp *.mp4 *.m4v "
                             "*.webm *.mov *.mkv *.avi);;All files (*)")
                        : tr("Media (*.png *.jpg *.jpeg *.webp *.gif *.mp4 *.m4v *.webm *.mov *.mp3 *.ogg "
                             "*.wav);;All files (*)");
    return QFileDialog::getOpenFileName(
        this, what == "media" ? tr("Media for the hotspot") : tr("Action target"), current, filter);
  };
  // Author text and file names are shown as plain text, never as rich text.
  for (QLabel* label : {info_, warning_text_, summary_}) {
    label->setTextFormat(Qt::PlainText);
    label->setWordWrap(true);
  }
  warning_text_->setStyleSheet("color: #b05a00");
  // Kinds, triggers and actions as resources/schema/enums.json lists them; item data: the name in files.
  for (const auto& n : EnumInfo<HotspotKind>::names) kind_->addItem(tr(n.label), QString(n.id));
  for (const auto& n : EnumInfo<HotspotTrigger>::names) trigger_->addItem(tr(n.label), QString(n.id));
  distance_->setRange(0.0, 100.0);
  distance_->setDecimals(1);
  distance_->setSingleStep(0.5);
  distance_->setSuffix(" m");
  for (const auto& n : EnumInfo<HotspotAction>::names) action_->addItem(tr(n.label), QString(n.id));
  list_->setObjectName("hotspot_list");
  title_->setObjectName("hotspot_title");
  media_->setObjectName("hotspot_media");
  target_->setObjectName("hotspot_target");

  auto* media_row = new QHBoxLayout;
  media_row->addWidget(media_, 1);
  media_row->addWidget(choose_media_);
  auto* target_row = new QHBoxLayout;
  target_row->addWidget(target_, 1);
  target_row->addWidget(choose_target_);
  auto* form = new QFormLayout;
  form->addRow(tr("Name"), title_);
  form->addRow(tr("Kind"), kind_);
  form->addRow(tr("Media"), media_row);
  form->addRow(tr("Trigger"), trigger_);
  form->addRow(tr("Distance"), distance_);
  form->addRow(tr("Action"), action_);
  form->addRow(tr("Target"), target_row);
  auto* new_movie = new QPushButton(tr("New movie texture"), this);
  auto* new_event = new QPushButton(tr("New event"), this);
  new_movie->setToolTip(tr("Then click four corners in the panorama (Ctrl+Shift+M)"));
  new_event->setToolTip(
      tr("Then click four corners, or Shift+click a polygon and press Enter (Ctrl+Shift+H)"));
  connect(new_movie, &QPushButton::clicked, this,
          [this] { editor_.set_mode(HotspotEditor::Mode::kNewMovieTexture); });
  connect(new_event, &QPushButton::clicked, this,
          [this] { editor_.set_mode(HotspotEditor::Mode::kNewEvent); });
  auto* new_row = new QHBoxLayout;
  new_row->addWidget(new_movie);
  new_row->addWidget(new_event);
  new_row->addStretch(1);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(goto_);
  buttons->addWidget(delete_);
  buttons->addStretch(1);
  // Inside a scroll area: the dock must not force a minimum window height on small screens.
  auto* content = new QWidget;
  auto* layout = new QVBoxLayout(content);
  layout->setContentsMargins(4, 4, 4, 4);
  list_->setMinimumHeight(60);
  layout->addLayout(new_row);
  layout->addWidget(list_, 1);
  layout->addWidget(summary_);
  layout->addLayout(buttons);
  layout->addLayout(form);
  layout->addWidget(info_);
  layout->addWidget(warning_text_);
  layout->addWidget(play_);
  auto* scroll = new QScrollArea(this);
  scroll->setWidget(content);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  outer->addWidget(scroll);

  validate_timer_->setSingleShot(true);
  validate_timer_->setInterval(250);  // a corner drag re-validates once it pauses
  connect(validate_timer_, &QTimer::timeout, this, &HotspotsPanel::validate_now);

  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (!(flags & (kHotspotsChanged | kPathChanged | kCaptureChanged | kPlanChanged))) return;
    rebuild_list();
    show_selected();
    validate_timer_->start();
  });
  connect(&editor_, &HotspotEditor::selection_changed, this, [this] {
    last_field_.clear();
    rebuild_list();
    show_selected();
  });
  connect(list_, &QListWidget::currentRowChanged, this, [this](int row) {
    if (updating_ || row < 0 || row >= static_cast<int>(document_.project().hotspots.size())) return;
    editor_.show_hotspot(document_.project().hotspots[static_cast<std::size_t>(row)].id);
  });
  connect(goto_, &QPushButton::clicked, this, [this] {
    if (!editor_.selected().empty()) editor_.show_hotspot(editor_.selected());
  });
  connect(delete_, &QPushButton::clicked, this, [this] { editor_.delete_selected(); });
  connect(play_, &QCheckBox::toggled, &editor_, &HotspotEditor::set_playing);

  connect(title_, &QLineEdit::textEdited, this, [this](const QString& text) {
    edit_selected("title", [&](Hotspot& h) { h.title = text.toStdString(); });
  });
  connect(kind_, QOverload<int>::of(&QComboBox::activated), this, [this](int index) {
    edit_selected("kind", [&](Hotspot& h) {
      h.kind = enum_from_string<HotspotKind>(kind_->itemData(index).toString().toStdString());
      if (h.kind == HotspotKind::kEvent && h.action == HotspotAction::kNone)
        h.action = HotspotAction::kShowText;
    });
  });
  connect(media_, &QLineEdit::textEdited, this, [this](const QString& text) {
    edit_selected("media", [&](Hotspot& h) { h.media = text.toStdString(); });
  });
  connect(choose_media_, &QPushButton::clicked, this, [this] {
    const QString file = ask_file("media", media_->text());
    if (file.isEmpty()) return;
    last_field_.clear();
    edit_selected("media", [&](Hotspot& h) { h.media = QFileInfo(file).absoluteFilePath().toStdString(); });
  });
  connect(trigger_, QOverload<int>::of(&QComboBox::activated), this, [this](int index) {
    edit_selected("trigger", [&](Hotspot& h) {
      h.trigger = enum_from_string<HotspotTrigger>(trigger_->itemData(index).toString().toStdString());
      if (h.trigger == HotspotTrigger::kProximity && !(h.trigger_distance_m > 0)) h.trigger_distance_m = 2.0;
    });
  });
  connect(distance_, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this](double value) {
    edit_selected("distance", [&](Hotspot& h) { h.trigger_distance_m = value; });
  });
  connect(action_, QOverload<int>::of(&QComboBox::activated), this, [this](int index) {
    edit_selected("action", [&](Hotspot& h) {
      h.action = enum_from_string<HotspotAction>(action_->itemData(index).toString().toStdString());
    });
  });
  connect(target_, &QLineEdit::textEdited, this, [this](const QString& text) {
    edit_selected("target", [&](Hotspot& h) { h.action_target = text.toStdString(); });
  });
  connect(choose_target_, &QPushButton::clicked, this, [this] {
    const QString file = ask_file("target", target_->text());
    if (file.isEmpty()) return;
    last_field_.clear();
    edit_selected("target",
                  [&](Hotspot& h) { h.action_target = QFileInfo(file).absoluteFilePath().toStdString(); });
  });

  rebuild_list();
  show_selected();
  validate_now();
}

const Hotspot* HotspotsPanel::selected_hotspot() const {
  const int i = find_hotspot(document_.project().hotspots, editor_.selected());
  return i < 0 ? nullptr : &document_.project().hotspots[static_cast<std::size_t>(i)];
}

void HotspotsPanel::edit_selected(const QString& field, const std::function<void(Hotspot&)>& edit) {
  if (updating_) return;
  const Hotspot* current = selected_hotspot();
  if (!current) return;
  Hotspot after = *current;
  edit(after);
  if (after == *current) return;
  if (field != last_field_) {
    last_field_ = field;
    merge_session_ = new_hotspot_merge_session();
  }
  document_.undo_stack()->push(
      new EditHotspotCommand(document_, std::move(after), tr("Edit hotspot %1").arg(field), merge_session_));
}

void HotspotsPanel::rebuild_list() {
  updating_ = true;
  const auto& hotspots = document_.project().hotspots;
  while (list_->count() > static_cast<int>(hotspots.size())) delete list_->takeItem(list_->count() - 1);
  while (list_->count() < static_cast<int>(hotspots.size())) list_->addItem(QString());
  int selected_row = -1;
  for (std::size_t i = 0; i < hotspots.size(); ++i) {
    const Hotspot& h = hotspots[i];
    QListWidgetItem* item = list_->item(static_cast<int>(i));
    const QString kind = h.kind == HotspotKind::kMovieTexture ? tr("movie texture") : tr("event");
    item->setText(tr("%1 — %2, frame %3")
                      .arg(QString::fromStdString(h.title.empty() ? h.id : h.title), kind)
                      .arg(h.frame));
    QStringList problems;
    for (const HotspotWarning& w : warnings_)
      if (w.hotspot_id == h.id) problems << QString::fromStdString(w.message);
    item->setIcon(problems.isEmpty() ? QIcon() : style()->standardIcon(QStyle::SP_MessageBoxWarning));
    // Escaped inside rich text, so markup in a title shows as typed.
    item->setToolTip(problems.isEmpty()
                         ? QString()
                         : "<qt>" + problems.join("\n").toHtmlEscaped().replace("\n", "<br>") + "</qt>");
    if (h.id == editor_.selected()) selected_row = static_cast<int>(i);
  }
  list_->setCurrentRow(selected_row);
  summary_->setText(hotspots.empty()
                        ? tr("No hotspots yet: Hotspots ▸ New movie texture (Ctrl+Shift+M) or New "
                             "event hotspot (Ctrl+Shift+H), then click corners in the panorama.")
                        : tr("%n hotspot(s), ", "", static_cast<int>(hotspots.size())) +
                              tr("%n warning(s)", "", static_cast<int>(warnings_.size())));
  updating_ = false;
}

void HotspotsPanel::show_selected() {
  updating_ = true;
  const Hotspot* h = selected_hotspot();
  for (QWidget* w : std::initializer_list<QWidget*>{title_, kind_, media_, choose_media_, trigger_, distance_,
                                                    action_, target_, choose_target_, goto_, delete_})
    w->setEnabled(h != nullptr);
  auto set_text = [](QLineEdit* edit, const QString& text) {
    if (edit->text() != text) edit->setText(text);  // keeps the cursor while typing
  };
  if (!h) {
    set_text(title_, QString());
    set_text(media_, QString());
    set_text(target_, QString());
    info_->setText(tr("Select a hotspot in the list or click one in the panorama."));
    warning_text_->clear();
    updating_ = false;
    return;
  }
  set_text(title_, QString::fromStdString(h->title));
  kind_->setCurrentIndex(kind_->findData(QString(to_string(h->kind))));
  set_text(media_, QString::fromStdString(h->media));
  trigger_->setCurrentIndex(trigger_->findData(QString(to_string(h->trigger))));
  distance_->setValue(h->trigger_distance_m);
  distance_->setEnabled(h->kind == HotspotKind::kEvent && h->trigger == HotspotTrigger::kProximity);
  action_->setCurrentIndex(action_->findData(QString(to_string(h->action))));
  for (QWidget* w : std::initializer_list<QWidget*>{trigger_, action_, target_})
    w->setEnabled(h->kind == HotspotKind::kEvent);
  set_text(target_, QString::fromStdString(h->action_target));
  target_->setPlaceholderText(target_hint(h->action));
  choose_target_->setEnabled(h->kind == HotspotKind::kEvent && hotspot_action_uses_media(h->action));
  info_->setText(h->world_corners.size() >= 3
                     ? tr("%1 corners in 3-D, marked in frame %2: shown in every frame that sees it.")
                           .arg(h->world_corners.size())
                           .arg(h->frame)
                     : tr("%1 corners in frame %2 only (not placed in 3-D).")
                           .arg(h->image_corners.size())
                           .arg(h->frame));
  QStringList problems;
  for (const HotspotWarning& w : warnings_)
    if (w.hotspot_id == h->id) problems << "⚠ " + QString::fromStdString(w.message);
  warning_text_->setText(problems.join("\n"));
  updating_ = false;
}

void HotspotsPanel::validate_now() {
  validate_timer_->stop();
  try {
    warnings_ = validate_hotspots(document_.project());
  } catch (const std::exception& e) {
    warnings_ = {{"", "", std::string("hotspot check failed: ") + e.what()}};
  }
  rebuild_list();
  show_selected();
}

}  // namespace plenopath::widgets
