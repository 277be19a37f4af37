#include "widgets/tour_export_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace plenopath::widgets {
namespace {

QCheckBox* check_box(const QString& text, const QString& name, bool checked, const QString& tip,
                     QWidget* parent) {
  auto* box = new QCheckBox(text, parent);
  box->setObjectName(name);
  box->setChecked(checked);
  box->setToolTip(tip);
  return box;
}

}  // namespace

TourExportDialog::TourExportDialog(const TourSettings& settings, const QString& output, bool georeferenced,
                                   QWidget* parent)
    : QDialog(parent),
      settings_(settings),
      output_(new QLineEdit(output, this)),
      title_(new QLineEdit(QString::fromStdString(settings.title), this)),
      max_size_(new QSpinBox(this)),
      quality_(new QSpinBox(this)) {
  setWindowTitle(tr("Export tour"));
  output_->setObjectName("output");
  title_->setObjectName("title");
  max_size_->setObjectName("max_size");
  quality_->setObjectName("quality");
  max_size_->setRange(256, 16384);
  max_size_->setSingleStep(512);
  max_size_->setSuffix(tr(" px wide"));
  max_size_->setValue(settings.max_size);
  max_size_->setToolTip(tr("Keyframes wider than this are scaled down; never scaled up"));
  quality_->setRange(1, 100);
  quality_->setValue(settings.jpeg_quality);
  auto* folder_button = new QPushButton(tr("Folder…"), this);
  auto* zip_button = new QPushButton(tr("Zip…"), this);
  auto* output_row = new QHBoxLayout;
  output_row->addWidget(output_, 1);
  output_row->addWidget(folder_button);
  output_row->addWidget(zip_button);
  connect(folder_button, &QPushButton::clicked, this, [this] {
    const QString dir = QFileDialog::getSaveFileName(this, tr("Tour folder"), output_->text());
    if (!dir.isEmpty()) output_->setText(dir);
  });
  connect(zip_button, &QPushButton::clicked, this, [this] {
    QString file =
        QFileDialog::getSaveFileName(this, tr("Tour archive"), output_->text(), tr("Zip archive (*.zip)"));
    if (file.isEmpty()) return;
    if (!file.endsWith(".zip", Qt::CaseInsensitive)) file += ".zip";
    output_->setText(file);
  });

  const QString needs_anchor = georeferenced ? QString() : tr(" (needs a geo-anchor: the project has none)");
  multires_ = check_box(tr("Multi-resolution tiles"), "multires", settings.export_multires,
                        tr("Cube tiles at several sizes, so a phone loads the level it can hold; the player "
                           "and Pannellum use them"),
                        this);
  pannellum_ = check_box(tr("Pannellum tour (pannellum.json)"), "pannellum", settings.export_pannellum,
                         tr("One scene per keyframe, linked along the path, with the hotspots"), this);
  marzipano_ = check_box(tr("Marzipano tour"), "marzipano", settings.export_marzipano,
                         tr("marzipano.html and its data on the cube tiles"), this);
  psv_ = check_box(tr("Photo Sphere Viewer tour (psv.json)"), "psv", settings.export_psv,
                   tr("Virtual-tour nodes with their links, and the plan as its map"), this);
  geojson_ = check_box(tr("Path as GeoJSON") + needs_anchor, "geojson",
                       settings.export_geojson && georeferenced, tr("path.geojson in WGS84"), this);
  kml_gpx_ =
      check_box(tr("Path as KML and GPX") + needs_anchor, "kml_gpx", settings.export_kml_gpx && georeferenced,
                tr("path.kml and path.gpx for Google Earth, GIS and GPS tools"), this);
  geojson_->setEnabled(georeferenced);
  kml_gpx_->setEnabled(georeferenced);
  tum_ = check_box(tr("Path as a TUM trajectory"), "tum", settings.export_tum,
                   tr("trajectory.tum: time, position and orientation per frame, for SLAM evaluation tools"),
                   this);
  opensfm_ = check_box(tr("Keyframes as an OpenSfM reconstruction"), "opensfm", settings.export_opensfm,
                       tr("reconstruction.json with spherical cameras"), this);
  nerfstudio_ = check_box(tr("Keyframes for nerfstudio"), "nerfstudio", settings.export_nerfstudio,
                          tr("transforms.json with equirectangular cameras"), this);
  photo_metadata_ = check_box(tr("360° photo tags in each keyframe (GPano, GPS)"), "photo_metadata",
                              settings.export_photo_metadata,
                              tr("So photo sites and viewers show each keyframe as a 360° photo"), this);

  auto* form = new QFormLayout;
  form->addRow(tr("Export to"), output_row);
  form->addRow(tr("Title"), title_);
  form->addRow(tr("Keyframe size"), max_size_);
  form->addRow(tr("JPEG quality"), quality_);
  auto* viewers = new QGroupBox(tr("Also for other viewers"), this);
  auto* viewers_layout = new QVBoxLayout(viewers);
  for (QCheckBox* b : {multires_, pannellum_, marzipano_, psv_}) viewers_layout->addWidget(b);
  auto* tools = new QGroupBox(tr("Also for maps, photo and 3-D tools"), this);
  auto* tools_layout = new QVBoxLayout(tools);
  for (QCheckBox* b : {photo_metadata_, geojson_, kml_gpx_, tum_, opensfm_, nerfstudio_})
    tools_layout->addWidget(b);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("Export"));
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(output_, &QLineEdit::textChanged, this, [this, buttons](const QString& text) {
    buttons->button(QDialogButtonBox::Ok)->setEnabled(!text.trimmed().isEmpty());
  });
  buttons->button(QDialogButtonBox::Ok)->setEnabled(!output.trimmed().isEmpty());
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(viewers);
  layout->addWidget(tools);
  layout->addWidget(buttons);
}

TourSettings TourExportDialog::settings() const {
  TourSettings s = settings_;
  s.title = title_->text().toStdString();
  s.max_size = max_size_->value();
  s.preview_size = std::min(s.preview_size, s.max_size);
  s.jpeg_quality = quality_->value();
  s.export_multires = multires_->isChecked();
  s.export_pannellum = pannellum_->isChecked();
  s.export_marzipano = marzipano_->isChecked();
  s.export_psv = psv_->isChecked();
  // Unavailable without an anchor: the project's own choice stays for when it has one.
  if (geojson_->isEnabled()) s.export_geojson = geojson_->isChecked();
  if (kml_gpx_->isEnabled()) s.export_kml_gpx = kml_gpx_->isChecked();
  s.export_tum = tum_->isChecked();
  s.export_opensfm = opensfm_->isChecked();
  s.export_nerfstudio = nerfstudio_->isChecked();
  s.export_photo_metadata = photo_metadata_->isChecked();
  return s;
}

QString TourExportDialog::output() const { return output_->text().trimmed(); }

}  // namespace plenopath::widgets
