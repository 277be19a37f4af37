#pragma once
// Process > Render CG scene (issue 23): the author's POV-Ray or Blender scene rendered along the project's
// path (or waypoints typed in, drawn on the plan or taken from the studio's automatic walk, or a path file),
// every frame or online (coarse depth first, full frames only for the keyframes), into a folder that then
// becomes the project's capture.
// Draw on plan… hides the dialog while the map takes the waypoints (MapView::start_waypoint_drawing) and
// shows it again with them filled in: open the dialog with open() (window-modal), not exec(), which a
// hidden dialog would end.
#include <QDialog>
#include <QPointer>
#include <string>
#include <vector>

#include "model/floor_plan.h"
#include "processing/sampling/cg_capture.h"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QRadioButton;
class QSpinBox;

namespace plenopath::widgets {

class MapView;

struct CgSceneChoices {
  std::string scene;    // .pov or .blend file
  std::string out_dir;  // capture folder to write
  bool use_project_path = true;
  std::string waypoints;  // "X,Y X,Y ..." (metres) when not the project's path
  double step_m = 0.1;    // waypoints: metres between frames
  std::string path_file;  // when not empty (and not the project's path): render along this path file
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

 public:
  // Draw on plan… needs the map; Auto walk and the note on walls crossed need the plan. Without them
  // those buttons are disabled.
  void set_map(MapView* map);
  void set_plan(const FloorPlan& plan);
  // Fills the waypoints ("X,Y X,Y ..." in metres, two decimals) and selects the Waypoints choice.
  void set_waypoints(const std::vector<Eigen::Vector2d>& points);
  // The automatic walk's positions are thinned to within this of it (metres), so that with the text's
  // two decimals the rendered walk stays within 5 cm of the automatic one.
  static constexpr double kAutoWalkTolerance = 0.04;

 private:
  void draw_on_plan();
  void back_from_map();
  void fill_auto_walk();
  void update_waypoints_note();
  void update_along();

  QPushButton* draw_button_ = nullptr;       // Draw on plan…
  QPushButton* auto_walk_button_ = nullptr;  // Auto walk
  QLabel* waypoints_note_ = nullptr;         // how many waypoints, how long, legs across a wall
  QRadioButton* path_file_choice_ = nullptr;
  QLineEdit* path_file_ = nullptr;
  QPushButton* path_file_button_ = nullptr;
  QPointer<MapView> map_;
  bool drawing_ = false;  // hidden while the map takes the waypoints
  FloorPlan plan_;
  bool has_plan_ = false;
};

}  // namespace plenopath::widgets
