// `plenopath-studio [PROJECT.plenopath]`: the editor.
#include <QApplication>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include "app/studio/main_window.h"

int main(int argc, char** argv) {
  // Must precede QApplication so that VTK's OpenGL widgets get a compatible context.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("Plenopath Studio");
  QApplication::setOrganizationName("Plenopath");
  QApplication::setApplicationVersion(PLENOPATH_VERSION);

  plenopath::studio::MainWindow window;
  const QStringList args = QApplication::arguments();
  if (args.size() > 1) window.open_project(args.at(1));
  window.show();
  return QApplication::exec();
}
