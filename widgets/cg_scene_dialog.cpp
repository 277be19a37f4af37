#include "widgets/cg_scene_dialog.h"

#include <QApplication>
#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>

#include "model/error.h"
#include "processing/walk/walk_route.h"
#include "rig/synthetic_camera.h"
#include "widgets/map_view.h"

namespace plenopath::widgets {

CgSceneDialog::CgSceneDialog(QWidget* parent, bool has_path, const QString& scene)
    : QDialog(parent),
      scene_(new QLineEdit(scene, this)),
      out_(new QLineEdit(this)),
      project_path_(new QRadioButton(tr("The project's path"), this)),
      waypoints_choice_(new QRadioButton(tr("Waypoints"), this)),
      waypoints_(new QLineEdit(this)),
      step_(new QDoubleSpinBox(this)),
      width_(new QSpinBox(this)),
      height_(new QDoubleSpinBox(this)),
      units_(new QDoubleSpinBox(this)),
      z_up_(new QCheckBox(tr("Modelled with z up (sky z, as CAD exports are)"), this)),
      depth_(new QCheckBox(tr("Depth (two more passes)"), this)),
      online_(
          new QCheckBox(tr("Online: coarse depth of the whole path, full frames only for keyframes"), this)),
      ratio_(new QDoubleSpinBox(this)),
      loss_target_(new QDoubleSpinBox(this)),
      section_(new QCheckBox(tr("Plan from the render: the scene cut at eye height"), this)) {
  setWindowTitle(tr("Render CG scene"));
  setObjectName("cg_scene_dialog");
  auto* scene_button = new QPushButton(tr("Scene…"), this);
  auto* out_button = new QPushButton(tr("Folder…"), this);
  auto* scene_row = new QHBoxLayout;
  scene_row->addWidget(scene_, 1);
  scene_row->addWidget(scene_button);
  auto* out_row = new QHBoxLayout;
  out_row->addWidget(out_, 1);
  out_row->addWidget(out_button);
  scene_->setPlaceholderText(
      tr("POV-Ray scene (.pov) or Blender scene (.blend); its own camera is replaced"));
  out_->setPlaceholderText(tr("folder for the frames, depth and ground truth"));
  if (!scene.isEmpty())
    out_->setText(QFileInfo(scene).absolutePath() + "/" + QFileInfo(scene).baseName() + "-capture");
  project_path_->setEnabled(has_path);
  (has_path ? project_path_ : waypoints_choice_)->setChecked(true);
  waypoints_->setPlaceholderText(tr("X,Y X,Y … in metres on the plan"));
  step_->setRange(0.01, 10.0);
  step_->setValue(0.1);
  step_->setDecimals(2);
  step_->setSuffix(tr(" m"));
  width_->setRange(64, 8192);
  width_->setSingleStep(256);
  width_->setValue(2048);
  width_->setSuffix(tr(" px wide (2:1)"));
  height_->setRange(0.1, 10.0);
  height_->setDecimals(2);
  height_->setValue(1.6);
  height_->setSuffix(tr(" m"));
  units_->setRange(0.001, 100000.0);
  units_->setDecimals(3);
  units_->setValue(1.0);
  units_->setToolTip(tr("Scene units in a metre (100: a scene drawn in centimetres)"));
  depth_->setChecked(true);
  section_->setObjectName("cg_section_plan");
  section_->setToolTip(
      tr("For a scene without a DXF plan: the project's plan becomes the walls the path saw at eye height "
         "(it replaces the current plan)"));
  ratio_->setRange(1.0, 10000.0);
  ratio_->setValue(50.0);
  ratio_->setToolTip(tr("Frames of the path per keyframe"));
  ratio_->setEnabled(false);
  loss_target_->setObjectName("cg_loss_target");
  loss_target_->setRange(0.0, 0.9);
  loss_target_->setDecimals(3);
  loss_target_->setSingleStep(0.01);
  loss_target_->setValue(0.0);
  loss_target_->setSpecialValueText(tr("off (frames per keyframe)"));
  loss_target_->setToolTip(
      tr("Render the fewest keyframes whose geometric loss (mean 1 − IoU of what each frame sees and what "
         "its keyframe sees) is at most this; frames per keyframe is then not used"));
  auto* path_row = new QHBoxLayout;
  path_row->addWidget(project_path_);
  path_row->addWidget(waypoints_choice_);
  path_row->addWidget(waypoints_, 1);
  auto* form = new QFormLayout;
  form->addRow(tr("Scene"), scene_row);
  form->addRow(tr("Along"), path_row);
  form->addRow(tr("Waypoint step"), step_);
  form->addRow(tr("Panorama size"), width_);
  form->addRow(tr("Camera height"), height_);
  form->addRow(tr("Scene units per metre"), units_);
  form->addRow(QString(), z_up_);
  form->addRow(QString(), depth_);
  form->addRow(QString(), section_);
  form->addRow(QString(), online_);
  form->addRow(tr("Frames per keyframe"), ratio_);
  form->addRow(tr("Loss target"), loss_target_);
  form->addRow(tr("Capture folder"), out_row);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);
  auto update = [this] {
    waypoints_->setEnabled(waypoints_choice_->isChecked());
    step_->setEnabled(waypoints_choice_->isChecked());
    ratio_->setEnabled(online_->isChecked() && loss_target_->value() <= 0.0);
    loss_target_->setEnabled(online_->isChecked());
    section_->setEnabled(depth_->isChecked());
    if (!depth_->isChecked()) section_->setChecked(false);
    // A Blender scene knows its units (its unit scale) and is z up: those two are POV-Ray's alone.
    const bool blender = is_blender_scene(scene_->text().toStdString());
    units_->setEnabled(!blender);
    z_up_->setEnabled(!blender);
    units_->setToolTip(blender ? tr("A Blender scene's own unit scale says its units")
                               : tr("Scene units in a metre (100: a scene drawn in centimetres)"));
    depth_->setText(blender ? tr("Depth (Cycles' Z pass: one more render)") : tr("Depth (two more passes)"));
  };
  update();
  connect(waypoints_choice_, &QRadioButton::toggled, this, update);
  connect(online_, &QCheckBox::toggled, this, update);
  connect(depth_, &QCheckBox::toggled, this, update);
  connect(loss_target_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, update);
  connect(scene_, &QLineEdit::textChanged, this, update);
  connect(scene_button, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(
        this, tr("CG scene"), scene_->text(),
        tr("CG scenes (*.pov *.blend);;POV-Ray scenes (*.pov);;Blender scenes (*.blend);;All files (*)"));
    if (f.isEmpty()) return;
    scene_->setText(f);
    if (out_->text().isEmpty())
      out_->setText(QFileInfo(f).absolutePath() + "/" + QFileInfo(f).baseName() + "-capture");
  });
  connect(out_button, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getExistingDirectory(this, tr("Capture folder"), out_->text());
    if (!f.isEmpty()) out_->setText(f);
  });
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    QString problem;
    if (!QFileInfo(scene_->text()).isFile())
      problem = tr("Choose the POV-Ray or Blender scene to render (%1 is no file).").arg(scene_->text());
    else if (out_->text().trimmed().isEmpty())
      problem = tr("Choose the folder to write the capture into.");
    else if (waypoints_choice_->isChecked() && waypoints_->text().trimmed().isEmpty())
      problem = tr("Type the waypoints (X,Y X,Y … in metres), or render along the project's path.");
    else if (path_file_choice_->isChecked() && !QFileInfo(path_file_->text().trimmed()).isFile())
      problem = tr("Choose the path file to render along (%1 is no file).").arg(path_file_->text());
    if (!problem.isEmpty()) {
      QMessageBox::warning(this, tr("Render CG scene"), problem);
      return;
    }
    accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

  // The walk drawn on the plan or the automatic one (issue 23), under the Along row; then a path file.
  draw_button_ = new QPushButton(tr("Draw on plan…"), this);
  draw_button_->setObjectName("cg_draw_on_plan");
  draw_button_->setToolTip(
      tr("Click the waypoints on the map: Backspace removes the last, Enter or a double-click finishes, Esc "
         "cancels"));
  auto_walk_button_ = new QPushButton(tr("Auto walk"), this);
  auto_walk_button_->setObjectName("cg_auto_walk");
  auto_walk_button_->setToolTip(
      tr("The studio's automatic walk through every room of the plan, as waypoints at its corners"));
  waypoints_note_ = new QLabel(this);
  waypoints_note_->setObjectName("cg_waypoints_note");
  waypoints_->setObjectName("cg_waypoints");
  path_file_choice_ = new QRadioButton(tr("Path file"), this);
  path_file_choice_->setObjectName("cg_path_file_choice");
  path_file_ = new QLineEdit(this);
  path_file_->setObjectName("cg_path_file");
  path_file_->setPlaceholderText(tr("path JSON (File > Import path reads the same)"));
  path_file_button_ = new QPushButton(tr("File…"), this);
  auto* draw_row = new QHBoxLayout;
  draw_row->addWidget(draw_button_);
  draw_row->addWidget(auto_walk_button_);
  draw_row->addWidget(waypoints_note_, 1);
  auto* file_row = new QHBoxLayout;
  file_row->addWidget(path_file_choice_);
  file_row->addWidget(path_file_, 1);
  file_row->addWidget(path_file_button_);
  int along_row = 0;
  QFormLayout::ItemRole role;
  form->getLayoutPosition(path_row, &along_row, &role);
  form->insertRow(along_row + 1, QString(), draw_row);
  form->insertRow(along_row + 2, QString(), file_row);
  update_along();
  for (QRadioButton* choice : {project_path_, waypoints_choice_, path_file_choice_})
    connect(choice, &QRadioButton::toggled, this, &CgSceneDialog::update_along);
  connect(waypoints_, &QLineEdit::textChanged, this, &CgSceneDialog::update_waypoints_note);
  connect(draw_button_, &QPushButton::clicked, this, &CgSceneDialog::draw_on_plan);
  connect(auto_walk_button_, &QPushButton::clicked, this, &CgSceneDialog::fill_auto_walk);
  connect(path_file_button_, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Path file"), path_file_->text(),
                                                   tr("Path files (*.json);;All files (*)"));
    if (f.isEmpty()) return;
    path_file_->setText(f);
    path_file_choice_->setChecked(true);
  });
}

void CgSceneDialog::update_along() {
  const bool file = path_file_choice_->isChecked();
  path_file_->setEnabled(file);
  path_file_button_->setEnabled(file);
  draw_button_->setEnabled(!map_.isNull());
  auto_walk_button_->setEnabled(has_plan_);
  auto_walk_button_->setToolTip(
      has_plan_
          ? tr("The studio's automatic walk through every room of the plan, as waypoints at its corners")
          : tr("Import the floor plan first"));
}

void CgSceneDialog::set_map(MapView* map) {
  if (map_) disconnect(map_, nullptr, this, nullptr);
  map_ = map;
  if (map_) {
    connect(map_, &MapView::waypoints_drawn, this, [this](const std::vector<Eigen::Vector2d>& points) {
      if (!drawing_) return;  // another dialog's drawing
      set_waypoints(points);
      back_from_map();
    });
    connect(map_, &MapView::waypoints_cancelled, this, [this] {
      if (drawing_) back_from_map();
    });
  }
  update_along();
}

void CgSceneDialog::set_plan(const FloorPlan& plan) {
  plan_ = plan;
  has_plan_ = !plan.empty();
  update_along();
  update_waypoints_note();
}

void CgSceneDialog::set_waypoints(const std::vector<Eigen::Vector2d>& points) {
  waypoints_->setText(QString::fromStdString(waypoints_text(points)));
  waypoints_->setCursorPosition(0);
  waypoints_choice_->setChecked(true);
}

void CgSceneDialog::draw_on_plan() {
  if (!map_) return;
  drawing_ = true;
  hide();  // window-modal: hidden, it lets the map have the clicks
  if (QWidget* window = map_->window()) {
    window->raise();
    window->activateWindow();
  }
  map_->start_waypoint_drawing(
      tr("Click the walk's waypoints\nBackspace removes the last  ·  Esc cancels\nEnter or a double-click "
         "finishes"));
}

void CgSceneDialog::back_from_map() {
  drawing_ = false;
  show();
  raise();
  activateWindow();
}

void CgSceneDialog::fill_auto_walk() {
  if (!has_plan_) return;
  QApplication::setOverrideCursor(Qt::WaitCursor);
  try {
    AutoWalkOptions options;
    options.frame_pattern.clear();
    set_waypoints(path_corners(auto_walk(plan_, options), kAutoWalkTolerance));
  } catch (const Error& e) {
    QApplication::restoreOverrideCursor();
    QMessageBox::warning(this, tr("Auto walk"), QString::fromStdString(e.what()));
    return;
  }
  QApplication::restoreOverrideCursor();
}

void CgSceneDialog::update_waypoints_note() {
  std::vector<Eigen::Vector2d> points;
  try {
    points = parse_waypoints(waypoints_->text().toStdString());
  } catch (const Error& e) {
    waypoints_note_->setStyleSheet("color: #c01f2a");
    waypoints_note_->setText(QString::fromStdString(e.what()).remove("--waypoints: "));
    return;
  }
  if (points.empty()) {
    waypoints_note_->clear();
    return;
  }
  double length = 0.0;
  int crossing = 0;
  const std::vector<PlanSegment> walls = has_plan_ ? plan_.occluder_segments() : std::vector<PlanSegment>{};
  for (std::size_t k = 1; k < points.size(); ++k) {
    length += (points[k] - points[k - 1]).norm();
    crossing += crosses_any_wall(walls, points[k - 1], points[k]);
  }
  QString text = tr("%n waypoint(s), %1 m", "", static_cast<int>(points.size())).arg(length, 0, 'f', 2);
  if (crossing > 0) text += tr("; %n leg(s) cross a wall of the plan", "", crossing);
  waypoints_note_->setStyleSheet(crossing > 0 ? "color: #c01f2a" : "");
  waypoints_note_->setText(text);
}

CgSceneChoices CgSceneDialog::choices() const {
  CgSceneChoices c;
  c.scene = scene_->text().toStdString();
  c.out_dir = out_->text().trimmed().toStdString();
  c.use_project_path = project_path_->isChecked();
  c.waypoints = waypoints_->text().toStdString();
  c.step_m = step_->value();
  c.options.povray.width = width_->value() / 2 * 2;
  c.options.povray.camera_height_m = height_->value();
  c.options.povray.units_per_metre = units_->value();
  c.options.povray.z_up = z_up_->isChecked();
  c.options.povray.depth = depth_->isChecked();
  // A Blender scene: the same size, height and depth; its units are its own unit scale's.
  c.options.blender.width = c.options.povray.width;
  c.options.blender.camera_height_m = c.options.povray.camera_height_m;
  c.options.blender.depth = c.options.povray.depth;
  c.options.online = online_->isChecked();
  c.options.online_parameters.ratio = ratio_->value();
  c.options.online_loss_target = loss_target_->value();
  c.options.section_plan = section_->isChecked();
  if (path_file_choice_->isChecked()) c.path_file = path_file_->text().trimmed().toStdString();
  return c;
}

}  // namespace plenopath::widgets
