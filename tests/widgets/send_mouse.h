#pragma once
// A mouse event sent straight to a widget (GUI tests): presses and releases are of the left button, moves
// of none; `buttons` is what is held, `modifiers` the keys (Ctrl for anchor drags).
#include <QApplication>
#include <QMouseEvent>
#include <QWidget>

namespace plenopath::test {

inline void send_mouse(QWidget* widget, QEvent::Type type, QPoint pixel, Qt::MouseButtons buttons,
                       Qt::KeyboardModifiers modifiers) {
  QMouseEvent event(type, QPointF(pixel), QPointF(widget->mapToGlobal(pixel)),
                    type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton, buttons, modifiers);
  QApplication::sendEvent(widget, &event);
}

}  // namespace plenopath::test
