#pragma once
// File > Export tour: where the package goes (a folder, or a file ending in .zip), the image sizes, and
// which files for other viewers and tools go with the web player. The choices are the project's tour
// settings, so the next export starts from them; the export itself runs as a task.
#include <QDialog>

#include "model/tour_settings.h"

class QCheckBox;
class QLineEdit;
class QSpinBox;

namespace plenopath::widgets {

class TourExportDialog : public QDialog {
  Q_OBJECT
 public:
  // `georeferenced`: whether the project has a geo-anchor (GeoJSON, KML and GPX need one).
  TourExportDialog(const TourSettings& settings, const QString& output, bool georeferenced,
                   QWidget* parent = nullptr);
  TourSettings settings() const;  // the settings passed in, with the dialog's choices
  QString output() const;

 private:
  TourSettings settings_;
  QLineEdit* output_;
  QLineEdit* title_;
  QSpinBox* max_size_;
  QSpinBox* quality_;
  QCheckBox* multires_;
  QCheckBox* pannellum_;
  QCheckBox* marzipano_;
  QCheckBox* psv_;
  QCheckBox* geojson_;
  QCheckBox* kml_gpx_;
  QCheckBox* tum_;
  QCheckBox* opensfm_;
  QCheckBox* nerfstudio_;
  QCheckBox* photo_metadata_;
};

}  // namespace plenopath::widgets
