#pragma once
// The studio's main window for GUI tests: shown at a fixed size and never blocking on a question (crash
// recovery declined, unsaved changes discarded, error boxes collected in `errors` instead of shown).
#include <QMessageBox>
#include <QStringList>
#include <QTest>
#include <gtest/gtest.h>

#include "app/studio/main_window.h"

namespace plenopath::test {

struct TestStudio {
  studio::MainWindow window;
  QStringList errors;
  TestStudio() {
    window.ask_recovery = [](const QString&) { return false; };
    window.ask_save_changes = [] { return QMessageBox::Discard; };
    window.show_error = [this](const QString& title, const QString& message) { errors << title + ": " + message; };
    window.resize(1400, 900);
    window.show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(&window));
  }
};

}  // namespace plenopath::test
