#pragma once
// Importing a capture: a folder of equirectangular frames or a video, the frame range and stride, an
// optional depth folder, an optional GPS track (GPX, NMEA or GeoJSON) and its time offset, the camera
// height and (for folders) the frame rate. The scan itself runs as a
// background task (it can take a while on 100 000 frames); this dialog only collects the choices.
#include <QDialog>
#include <string>

#include "processing/capture/frame_source.h"

class QCheckBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;

namespace plenopath::widgets {

struct CaptureImportChoices {
  std::string source;              // folder or video file
  FrameSourceOptions options;      // range, stride, depth folder, folder frame rate
  double camera_height_m = 0.0;    // 0 = unknown
  std::string gps_file;            // optional GPS track
  double gps_time_offset_s = 0.0;  // GPS-track time of frame 0, seconds after the track's first sample
  // Still panoramas from a tripod (issue 20): ordered by their EXIF time, located by their own GPS, and
  // solved by the stills pipeline instead of tracked.
  bool stills = false;
};

class CaptureImportDialog : public QDialog {
  Q_OBJECT
 public:
  explicit CaptureImportDialog(QWidget* parent = nullptr, const QString& source = {}, bool stills = false);
  CaptureImportChoices choices() const;

 private:
  QLineEdit* source_;
  QSpinBox* first_;
  QSpinBox* last_;
  QSpinBox* stride_;
  QLineEdit* depth_;
  QLineEdit* gps_;
  QDoubleSpinBox* gps_offset_;
  QDoubleSpinBox* height_;
  QDoubleSpinBox* rate_;
  QCheckBox* stills_;
};

}  // namespace plenopath::widgets
