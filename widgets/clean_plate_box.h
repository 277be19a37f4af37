#pragma once
// Clean plates in the sampling panel (issue 24): whether the tour's keyframes are exported without the
// people who walked through and without the rig, what covers the rig where no frame saw behind it (the
// nadir patch: a blurred fill, nothing, or the author's picture), whether faces that remain are blurred,
// the author's rig mask (where the operator is that no geometry can tell from what is behind them), and a
// preview of the current frame (before/after in the panorama). Each change is one undo step of the
// project's tour settings; the controls follow the document (undo, load).
#include <QGroupBox>

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;

namespace plenopath::widgets {

class ProjectDocument;

class CleanPlateBox : public QGroupBox {
  Q_OBJECT
 public:
  explicit CleanPlateBox(ProjectDocument& document, QWidget* parent = nullptr);

  QCheckBox* clean_plates_box() const { return clean_plates_; }
  QComboBox* nadir_box() const { return nadir_; }
  QPushButton* image_button() const { return image_button_; }
  QCheckBox* faces_box() const { return faces_; }
  QPushButton* preview_button() const { return preview_; }
  QPushButton* rig_mask_button() const { return rig_mask_button_; }
  // The nadir patch becomes `file` (an image): what the Image… button does after its file dialog.
  void set_nadir_image(const QString& file);
  // The capture's rig mask becomes `file` (black where the trolley, operator or tripod cover every frame,
  // as `track --mask` and `--mask-out`); empty: the tracker's estimate alone.
  void set_rig_mask(const QString& file);

 signals:
  void preview_requested();

 private:
  void show_settings();
  void choose_image();

  ProjectDocument& document_;
  QCheckBox* clean_plates_;
  QComboBox* nadir_;
  QPushButton* image_button_;
  QLabel* image_name_;
  QPushButton* rig_mask_button_;
  QLabel* rig_mask_name_;
  QCheckBox* faces_;
  QPushButton* preview_;
  bool showing_ = false;
};

}  // namespace plenopath::widgets
