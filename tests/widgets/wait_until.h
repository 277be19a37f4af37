#pragma once
// Lets the event loop run until `done()` holds or the time runs out (GUI tests).
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QThread>

namespace plenopath::test {

template <typename Done>
bool wait_until(Done done, int timeout_ms = 20000) {
  QElapsedTimer timer;
  timer.start();
  while (!done()) {
    if (timer.elapsed() > timeout_ms) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(2);
  }
  return true;
}

}  // namespace plenopath::test
