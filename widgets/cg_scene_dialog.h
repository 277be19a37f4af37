#pragma once
// Process > Render CG scene (issue 23): the author's POV-Ray or Blender scene rendered along the project's
// path (or waypoints typed in), every frame or online (coarse depth first, full frames only for the
// keyframes), into a folder that then becomes the project's capture.
#include <QDialog>
#include <string>

#include "processing/sampling/cg_capture.h"

class QCheckBox;
class QDoubleSpinBox;
class QLineEdit;
class QRadioButton;
class QSpinBox;

namespace plenopath::widgets {

struct CgSceneChoices {
  std::string scene;    // .pov or .blend file
  std::string out_dir;  // capture folder to write
  bool use_project_path = true;
  std::string waypoints;  // "X,Y X,Y ..." (metres) when not the project's path
  double step_m = 0.1;    // waypoints: metres between frames
  CgCaptureOptions options;
};

class CgSceneDialog : public QDialog {
  Q_OBJECT
 public:
  // has_path: the project has a path to render along (otherwise waypoints are the only choice).
  CgSceneDialog(QWidget* parent, bool has_path, const QString& scene = {});
  CgSceneChoices choices() const;

 private:
  QLineEdit* scene_;
  QLineEdit* out_;
  QRadioButton* project_path_;
  QRadioButton* waypoints_choice_;
  QLineEdit* waypoints_;
  QDoubleSpinBox* step_;
  QSpinBox* width_;
  QDoubleSpinBox* height_;
  QDoubleSpinBox* units_;
  QCheckBox* z_up_;
  QCheckBox* depth_;
  QCheckBox* online_;
  QDoubleSpinBox* ratio_;
  QDoubleSpinBox* loss_target_;
  QCheckBox* section_;
};

}  // namespace plenopath::widgets
