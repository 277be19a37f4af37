#pragma once
// The studio's main window for GUI tests: shown at a fixed size and never blocking on a question (crash
// recovery declined, unsaved changes discarded, error boxes collected in `errors` instead of shown).
#include <gtest/gtest.h>

#include <QImage>
#include <QMessageBox>
#include <QStringList>
#include <QTest>

#include "app/studio/main_window.h"

namespace plenopath::test {

struct TestStudio {
  studio::MainWindow window;
  QStringList errors;
  TestStudio() {
    window.ask_recovery = [](const QString&) { return false; };
    window.ask_save_changes = [] { return QMessageBox::Discard; };
    window.show_error = [this](const QString& title, const QString& message) {
      errors << title + ": " + message;
    };
    window.resize(1400, 900);
    window.show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(&window));
  }
};

// Pixels of `image` within `radius` of `centre` (a square) that match `predicate`.
template <typename Predicate>
int count_near(const QImage& image, QPoint centre, int radius, Predicate predicate) {
  int n = 0;
  for (int y = centre.y() - radius; y <= centre.y() + radius; ++y)
    for (int x = centre.x() - radius; x <= centre.x() + radius; ++x)
      if (image.valid(x, y) && predicate(image.pixel(x, y))) ++n;
  return n;
}

}  // namespace plenopath::test
