// test_widgets: GoogleTest inside a QApplication (GUI tests run under xvfb-run; Mesa renders in software).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QSurfaceFormat>

int main(int argc, char** argv) {
  // Before QApplication, so VTK's widgets and the panorama view get a compatible OpenGL context.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  // Keep the tests' settings (recent files, window state) away from a real user's.
  QApplication::setOrganizationName("PlenopathTests");
  QApplication::setApplicationName("Plenopath Studio Tests");
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
