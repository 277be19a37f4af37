#include "widgets/clean_plate_box.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QUndoStack>

#include "model/enums.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

void push_tour(ProjectDocument& document, const TourSettings& tour, const QString& title) {
  if (tour == document.project().tour) return;
  Project after = document.snapshot();
  after.tour = tour;
  document.undo_stack()->push(new ReplacePartsCommand(document, title, after, kSettingsChanged));
}

}  // namespace

CleanPlateBox::CleanPlateBox(ProjectDocument& document, QWidget* parent)
    : QGroupBox(tr("Clean plates"), parent), document_(document) {
  clean_plates_ = new QCheckBox(tr("Without people and rig"));
  clean_plates_->setObjectName("clean_plates");
  clean_plates_->setToolTip(
      tr("Each keyframe's people, operator and trolley replaced by what other frames saw "
         "behind them (export --clean-plates)"));
  nadir_ = new QComboBox;
  nadir_->setObjectName("nadir_patch");
  for (const auto& n : EnumInfo<NadirPatch>::names) nadir_->addItem(tr(n.label), QString::fromLatin1(n.id));
  nadir_->setToolTip(tr("What covers the rig where no frame saw the scene behind it"));
  // The dock is narrow: the box shrinks with it (the items' full text is in the list).
  nadir_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  nadir_->setMinimumContentsLength(8);
  image_button_ = new QPushButton(tr("Image…"));
  image_button_->setObjectName("nadir_image");
  image_name_ = new QLabel;
  image_name_->setObjectName("nadir_image_name");
  rig_mask_button_ = new QPushButton(tr("Rig mask…"));
  rig_mask_button_->setObjectName("rig_mask");
  rig_mask_button_->setToolTip(tr(
      "An image of the frames' size, black where the trolley, the operator or the tripod cover every frame "
      "(track --mask-out writes the tracker's own to start from); cancel the dialog to clear it"));
  rig_mask_name_ = new QLabel;
  rig_mask_name_->setObjectName("rig_mask_name");
  faces_ = new QCheckBox(tr("Blur faces"));
  faces_->setObjectName("blur_faces");
  preview_ = new QPushButton(tr("Preview this frame"));
  preview_->setObjectName("preview_clean_plate");
  preview_->setToolTip(
      tr("The clean plate of the frame on screen, before/after in the panorama (Esc ends it)"));

  auto* nadir_row = new QHBoxLayout;
  nadir_row->addWidget(nadir_, 1);
  nadir_row->addWidget(image_button_);
  auto* form = new QFormLayout(this);
  form->addRow(clean_plates_);
  form->addRow(tr("Nadir patch"), nadir_row);
  form->addRow(QString(), image_name_);
  auto* rig_row = new QHBoxLayout;
  rig_row->addWidget(rig_mask_button_);
  rig_row->addWidget(rig_mask_name_, 1);
  form->addRow(tr("Rig"), rig_row);
  form->addRow(faces_);
  form->addRow(preview_);

  connect(clean_plates_, &QCheckBox::toggled, this, [this](bool on) {
    if (showing_) return;
    TourSettings t = document_.project().tour;
    t.export_clean_plates = on;
    push_tour(document_, t, on ? tr("Export clean plates") : tr("Export keyframes as captured"));
  });
  connect(nadir_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (showing_ || index < 0) return;
    const NadirPatch kind = enum_from_string<NadirPatch>(nadir_->itemData(index).toString().toStdString());
    if (kind == NadirPatch::kImage && document_.project().tour.nadir_image.empty()) {
      choose_image();  // an image patch needs its picture; cancelled: the choice goes back
      show_settings();
      return;
    }
    TourSettings t = document_.project().tour;
    t.nadir_patch = kind;
    push_tour(document_, t, tr("Nadir patch: %1").arg(nadir_->itemText(index)));
  });
  connect(image_button_, &QPushButton::clicked, this, [this] { choose_image(); });
  connect(rig_mask_button_, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Rig mask (black = rig)"),
                                                      QFileInfo(document_.file_name()).absolutePath(),
                                                      tr("Images (*.png *.jpg *.jpeg *.bmp *.tif *.tiff)"));
    set_rig_mask(file);
  });
  connect(faces_, &QCheckBox::toggled, this, [this](bool on) {
    if (showing_) return;
    TourSettings t = document_.project().tour;
    t.blur_faces = on;
    push_tour(document_, t, on ? tr("Blur faces") : tr("Leave faces as captured"));
  });
  connect(preview_, &QPushButton::clicked, this, &CleanPlateBox::preview_requested);
  connect(&document_, &ProjectDocument::changed, this, [this] { show_settings(); });
  show_settings();
}

void CleanPlateBox::set_nadir_image(const QString& file) {
  TourSettings t = document_.project().tour;
  t.nadir_patch = NadirPatch::kImage;
  t.nadir_image = QFileInfo(file).absoluteFilePath().toStdString();
  push_tour(document_, t, tr("Nadir patch: %1").arg(QFileInfo(file).fileName()));
}

void CleanPlateBox::set_rig_mask(const QString& file) {
  const std::string path = file.isEmpty() ? std::string() : QFileInfo(file).absoluteFilePath().toStdString();
  if (path == document_.project().capture.rig_mask) return;
  Project after = document_.snapshot();
  after.capture.rig_mask = path;
  document_.undo_stack()->push(new ReplacePartsCommand(
      document_, file.isEmpty() ? tr("Clear rig mask") : tr("Rig mask: %1").arg(QFileInfo(file).fileName()),
      after, kCaptureChanged));
}

void CleanPlateBox::choose_image() {
  const QString start = document_.project().tour.nadir_image.empty()
                            ? QFileInfo(document_.file_name()).absolutePath()
                            : QString::fromStdString(document_.project().tour.nadir_image);
  const QString file = QFileDialog::getOpenFileName(
      this, tr("Nadir patch image"), start, tr("Images (*.png *.jpg *.jpeg *.bmp *.tif *.tiff *.webp)"));
  if (!file.isEmpty()) set_nadir_image(file);
}

void CleanPlateBox::show_settings() {
  showing_ = true;
  const TourSettings& t = document_.project().tour;
  {
    const QSignalBlocker b1(clean_plates_), b2(nadir_), b3(faces_);
    clean_plates_->setChecked(t.export_clean_plates);
    nadir_->setCurrentIndex(nadir_->findData(QString::fromLatin1(to_string(t.nadir_patch))));
    faces_->setChecked(t.blur_faces);
  }
  nadir_->setEnabled(t.export_clean_plates);
  image_button_->setEnabled(t.export_clean_plates);
  image_name_->setText(t.nadir_patch == NadirPatch::kImage && !t.nadir_image.empty()
                           ? QFileInfo(QString::fromStdString(t.nadir_image)).fileName()
                           : QString());
  image_name_->setVisible(!image_name_->text().isEmpty());
  const Project& p = document_.project();
  rig_mask_button_->setEnabled(t.export_clean_plates && !p.capture.empty());
  rig_mask_name_->setText(p.capture.rig_mask.empty()
                              ? tr("automatic")
                              : QFileInfo(QString::fromStdString(p.capture.rig_mask)).fileName());
  preview_->setEnabled(!p.path.empty() && !p.capture.empty());
  showing_ = false;
}

}  // namespace plenopath::widgets
