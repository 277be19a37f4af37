#include "widgets/capture_import_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace plenopath::widgets {

CaptureImportDialog::CaptureImportDialog(QWidget* parent, const QString& source, bool stills)
    : QDialog(parent),
      source_(new QLineEdit(source, this)),
      first_(new QSpinBox(this)),
      last_(new QSpinBox(this)),
      stride_(new QSpinBox(this)),
      depth_(new QLineEdit(this)),
      gps_(new QLineEdit(this)),
      gps_offset_(new QDoubleSpinBox(this)),
      height_(new QDoubleSpinBox(this)),
      rate_(new QDoubleSpinBox(this)),
      stills_(new QCheckBox(tr("Still panoramas shot from a tripod, metres apart"), this)) {
  setWindowTitle(stills ? tr("Import still panoramas") : tr("Import capture"));
  stills_->setObjectName("stills");
  stills_->setChecked(stills);
  stills_->setToolTip(
      tr("Ordered by the time each was shot (EXIF), placed by their own GPS when they have it, and solved "
         "by matching across all pairs instead of tracking. Tracking also finds out by itself."));
  auto* folder_button = new QPushButton(tr("Folder…"), this);
  auto* video_button = new QPushButton(tr("Video…"), this);
  auto* depth_button = new QPushButton(tr("Folder…"), this);
  auto* source_row = new QHBoxLayout;
  source_row->addWidget(source_, 1);
  source_row->addWidget(folder_button);
  source_row->addWidget(video_button);
  auto* depth_row = new QHBoxLayout;
  depth_row->addWidget(depth_, 1);
  depth_row->addWidget(depth_button);
  auto* gps_button = new QPushButton(tr("File…"), this);
  auto* gps_row = new QHBoxLayout;
  gps_row->addWidget(gps_, 1);
  gps_row->addWidget(gps_button);
  gps_->setPlaceholderText(tr("optional: GPX, NMEA or GeoJSON track, matched to frames by time"));
  gps_offset_->setRange(-1e7, 1e7);
  gps_offset_->setDecimals(2);
  gps_offset_->setSuffix(tr(" s"));
  gps_offset_->setToolTip(tr("Time of the first frame on the GPS track, counted from its first point"));
  first_->setRange(0, 100000000);
  last_->setRange(-1, 100000000);
  last_->setValue(-1);
  last_->setSpecialValueText(tr("last"));
  stride_->setRange(1, 1000);
  height_->setRange(0.0, 10.0);
  height_->setDecimals(2);
  height_->setSuffix(tr(" m"));
  height_->setSpecialValueText(tr("unknown"));
  height_->setValue(1.6);
  rate_->setRange(0.1, 240.0);
  rate_->setValue(30.0);
  rate_->setSuffix(tr(" fps"));
  depth_->setPlaceholderText(tr("optional: 16-bit PNG (mm) or EXR (m) per frame"));

  auto* form = new QFormLayout;
  form->addRow(tr("Frames (folder or video)"), source_row);
  form->addRow(QString(), stills_);
  form->addRow(tr("First frame"), first_);
  form->addRow(tr("Last frame"), last_);
  form->addRow(tr("Keep every"), stride_);
  form->addRow(tr("Depth folder"), depth_row);
  form->addRow(tr("GPS track"), gps_row);
  form->addRow(tr("GPS time of frame 0"), gps_offset_);
  form->addRow(tr("Camera height"), height_);
  form->addRow(tr("Frame rate (folders)"), rate_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);

  // Stills are a folder of images: no video, no frame rate.
  const auto stills_changed = [this, video_button](bool on) {
    video_button->setEnabled(!on);
    rate_->setEnabled(!on);
  };
  connect(stills_, &QCheckBox::toggled, this, stills_changed);
  stills_changed(stills);
  connect(folder_button, &QPushButton::clicked, this, [this] {
    const QString f =
        QFileDialog::getExistingDirectory(this, tr("Folder of equirectangular frames"), source_->text());
    if (!f.isEmpty()) source_->setText(f);
  });
  connect(video_button, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("360° video"), source_->text(),
                                                   tr("Videos (*.mp4 *.mov *.mkv *.avi *.MP4 *.MOV)"));
    if (!f.isEmpty()) source_->setText(f);
  });
  connect(depth_button, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getExistingDirectory(this, tr("Depth maps"), depth_->text());
    if (!f.isEmpty()) depth_->setText(f);
  });
  connect(gps_button, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(
        this, tr("GPS track"), gps_->text(),
        tr("GPS tracks (*.gpx *.nmea *.nma *.txt *.log *.geojson *.json);;All files (*)"));
    if (!f.isEmpty()) gps_->setText(f);
  });
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    if (!source_->text().isEmpty()) accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
}

CaptureImportChoices CaptureImportDialog::choices() const {
  CaptureImportChoices c;
  c.source = source_->text().toStdString();
  c.options.first_frame = first_->value();
  c.options.last_frame = last_->value();
  c.options.stride = stride_->value();
  c.options.depth_folder = depth_->text().toStdString();
  c.options.folder_frame_rate = rate_->value();
  c.camera_height_m = height_->value();
  c.gps_file = gps_->text().trimmed().toStdString();
  c.gps_time_offset_s = gps_offset_->value();
  c.stills = stills_->isChecked();
  return c;
}

}  // namespace plenopath::widgets
