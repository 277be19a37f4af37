// File > Export tour's dialog: it starts from the project's tour settings, returns the author's choices, and
// offers the georeferenced files only when the project has a geo-anchor (keeping the project's own choice
// for when it has one).
#include "widgets/tour_export_dialog.h"

#include <gtest/gtest.h>

#include <QCheckBox>
#include <QLineEdit>
#include <QSpinBox>

namespace plenopath {
namespace {

template <class T>
T* child(QWidget& parent, const char* name) {
  T* w = parent.findChild<T*>(name);
  EXPECT_NE(w, nullptr) << name;
  return w;
}

TEST(TourExportDialog, StartsFromTheSettingsAndReturnsTheChoices) {
  TourSettings settings;
  settings.title = "Office";
  settings.export_pannellum = true;
  settings.export_geojson = true;  // chosen once, on a project that had an anchor
  widgets::TourExportDialog dialog(settings, "/tmp/out", /*georeferenced=*/false);
  EXPECT_TRUE(child<QCheckBox>(dialog, "pannellum")->isChecked());
  EXPECT_FALSE(child<QCheckBox>(dialog, "marzipano")->isChecked());
  EXPECT_TRUE(child<QCheckBox>(dialog, "photo_metadata")->isChecked());  // on by default
  QCheckBox* geojson = child<QCheckBox>(dialog, "geojson");
  EXPECT_FALSE(geojson->isEnabled());
  EXPECT_FALSE(geojson->isChecked());
  EXPECT_FALSE(child<QCheckBox>(dialog, "kml_gpx")->isEnabled());
  EXPECT_EQ(child<QSpinBox>(dialog, "max_size")->value(), 4096);

  child<QCheckBox>(dialog, "marzipano")->setChecked(true);
  child<QCheckBox>(dialog, "tum")->setChecked(true);
  child<QCheckBox>(dialog, "photo_metadata")->setChecked(false);
  child<QSpinBox>(dialog, "max_size")->setValue(2048);
  child<QLineEdit>(dialog, "output")->setText("  /tmp/tour.zip ");
  child<QLineEdit>(dialog, "title")->setText("Office, second floor");
  const TourSettings chosen = dialog.settings();
  EXPECT_EQ(dialog.output(), "/tmp/tour.zip");
  EXPECT_EQ(chosen.title, "Office, second floor");
  EXPECT_TRUE(chosen.export_marzipano);
  EXPECT_TRUE(chosen.export_tum);
  EXPECT_TRUE(chosen.export_pannellum);
  EXPECT_FALSE(chosen.export_photo_metadata);
  EXPECT_EQ(chosen.max_size, 2048);
  EXPECT_EQ(chosen.preview_size, 1024);
  EXPECT_TRUE(chosen.export_geojson) << "kept for when the project has an anchor";
  EXPECT_TRUE(chosen.export_kml_gpx);

  // A picture to look at: build/tour_export_dialog.png.
  dialog.show();
  dialog.grab().save(PLENOPATH_BINARY_DIR "/tour_export_dialog.png");

  widgets::TourExportDialog anchored(settings, "/tmp/out", /*georeferenced=*/true);
  QCheckBox* kml = child<QCheckBox>(anchored, "kml_gpx");
  EXPECT_TRUE(kml->isEnabled());
  EXPECT_TRUE(kml->isChecked());
  kml->setChecked(false);
  EXPECT_FALSE(anchored.settings().export_kml_gpx);
}

}  // namespace
}  // namespace plenopath
