#include "widgets/panorama_view.h"

#include <Eigen/Geometry>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLBuffer>
#include <QOpenGLContext>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "model/camera_path.h"
#include "model/tour_settings.h"
#include "rig/spherical.h"
#include "widgets/frame_provider.h"
#include "widgets/fullscreen_triangle.h"
#include "widgets/hotspot_editor.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

// Perspective mode: the ray through a screen pixel, in the camera frame (+x forward, +y left, +z up), is
// forward + s*right + t*up; its azimuth a = atan2(-y, x) (grows to the right) and elevation e map to the
// equirect texture by u = (a + pi) / 2pi, v = (pi/2 - e) / pi with texture row 0 = the image's top row.
// Whole-image mode: the texture letterboxed to the widget.
const char* kFragmentShader = R"(#version 150
uniform sampler2D equirect;
uniform int whole_image;
uniform vec3 forward;
uniform vec3 left;
uniform vec3 up;
uniform float tan_half_fov;
uniform float aspect;
uniform vec2 image_scale;
uniform sampler2D after;
uniform float split;  // > 1: no comparison
in vec2 ndc;
out vec4 colour;
const float PI = 3.14159265358979;
void main() {
  vec2 uv;
  if (whole_image == 1) {
    vec2 p = ndc / image_scale;
    if (abs(p.x) > 1.0 || abs(p.y) > 1.0) { colour = vec4(0.12, 0.12, 0.14, 1.0); return; }
    uv = vec2(0.5 * p.x + 0.5, 0.5 - 0.5 * p.y);
  } else {
    vec3 d = forward - ndc.x * tan_half_fov * left + ndc.y * tan_half_fov / aspect * up;
    float azimuth = atan(-d.y, d.x);
    float elevation = atan(d.z, length(d.xy));
    uv = vec2((azimuth + PI) / (2.0 * PI), (0.5 * PI - elevation) / PI);
  }
  if (0.5 * ndc.x + 0.5 > split) colour = vec4(texture(after, uv).rgb, 1.0);
  else colour = vec4(texture(equirect, uv).rgb, 1.0);
}
)";

constexpr double kMinFov = 0.35;  // 20 degrees
constexpr double kMaxFov = 2.1;   // 120 degrees

}  // namespace

PanoramaView::PanoramaView(ProjectDocument& document, FrameProvider& frames, QWidget* parent)
    : QOpenGLWidget(parent),
      document_(document),
      frames_(frames),
      hotspots_(new HotspotEditor(document, *this)) {
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(240, 160);
  connect(&document_, &ProjectDocument::current_position_changed, this, [this] {
    if (comparing() && document_.current_position() != comparison_position_) clear_comparison();
    show_current();
  });
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (kCaptureChanged | kPathChanged)) {
      shown_position_ = -1;
      show_current();
    }
    if (flags & kHotspotsChanged) update();
  });
  connect(&frames_, &FrameProvider::frame_ready, this, [this](int position, const QImage& image) {
    if (position != document_.current_position()) return;
    pending_image_ = image;
    pending_position_ = position;
    message_.clear();
    update();
  });
  connect(&frames_, &FrameProvider::frame_failed, this, [this](int position, const QString& message) {
    if (position != document_.current_position()) return;
    message_ = message;
    update();
  });
  show_current();
}

PanoramaView::~PanoramaView() {
  if (context()) {
    makeCurrent();
    release_gl();
    doneCurrent();
  }
}

void PanoramaView::release_gl() {
  if (texture_) glDeleteTextures(1, &texture_);
  if (after_texture_) glDeleteTextures(1, &after_texture_);
  texture_ = after_texture_ = 0;
  quad_.reset();
  vao_.reset();
  program_.reset();
}

void PanoramaView::show_current() {
  if (document_.frame_count() == 0) {
    message_ = document_.project().capture.empty() ? tr("No capture: import one with File ▸ Import capture")
                                                   : QString();
    update();
    return;
  }
  frames_.request(document_.current_position());
}

void PanoramaView::set_look(double azimuth, double elevation, double fov) {
  azimuth_ = wrap_angle(azimuth);
  elevation_ = std::clamp(elevation, -1.45, 1.45);
  fov_ = std::clamp(fov, kMinFov, kMaxFov);
  document_.set_look(azimuth_, fov_);
  update();
}

void PanoramaView::set_equirect_mode(bool whole_image) {
  if (whole_image == equirect_mode_) return;
  equirect_mode_ = whole_image;
  emit equirect_mode_changed(whole_image);
  update();
}

void PanoramaView::initializeGL() {
  initializeOpenGLFunctions();
  connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, [this] {
    makeCurrent();
    release_gl();
    doneCurrent();
  });
  program_ = std::make_unique<QOpenGLShaderProgram>();
  program_->addShaderFromSourceCode(QOpenGLShader::Vertex, kFullscreenTriangleVertexShader);
  program_->addShaderFromSourceCode(QOpenGLShader::Fragment, kFragmentShader);
  program_->bindAttributeLocation("corner", 0);
  if (!program_->link()) message_ = tr("Panorama shader failed: %1").arg(program_->log());
  vao_ = std::make_unique<QOpenGLVertexArrayObject>();
  vao_->create();
  vao_->bind();
  quad_ = std::make_unique<QOpenGLBuffer>(QOpenGLBuffer::VertexBuffer);
  quad_->create();
  quad_->bind();
  const GLfloat corners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
  quad_->allocate(corners, sizeof corners);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  vao_->release();
  glGenTextures(1, &texture_);
  glGenTextures(1, &after_texture_);
  texture_size_ = QSize();
  // A new context lost the old texture: upload the shown frame again.
  if (shown_position_ >= 0) {
    pending_image_ = frames_.cached(shown_position_);
    pending_position_ = shown_position_;
  }
}

void PanoramaView::set_comparison(int position, const QImage& after, const QString& label) {
  comparison_position_ = position;
  comparison_label_ = label;
  pending_after_ = after;
  comparison_size_ = after.size();
  if (document_.current_position() != position) document_.set_current_position(position);
  emit comparison_changed(true);
  update();
}

void PanoramaView::clear_comparison() {
  if (!comparing()) return;
  comparison_position_ = -1;
  pending_after_ = QImage();
  dragging_split_ = false;
  emit comparison_changed(false);
  update();
}

void PanoramaView::set_comparison_split(double split) {
  split_ = std::clamp(split, 0.0, 1.0);
  update();
}

// An image into a texture, top row first (texture v = 0 is the zenith), repeating across the seam.
static void upload_equirect(QOpenGLFunctions& gl, unsigned texture, const QImage& source) {
  GLint max_size = 4096;
  gl.glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  QImage image = source.convertToFormat(QImage::Format_RGBA8888);
  if (image.width() > max_size || image.height() > max_size)
    image = image.scaled(std::min(image.width(), static_cast<int>(max_size)),
                         std::min(image.height(), static_cast<int>(max_size) / 2), Qt::KeepAspectRatio,
                         Qt::SmoothTransformation);
  gl.glBindTexture(GL_TEXTURE_2D, texture);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, image.width(), image.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                  image.constBits());
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void PanoramaView::upload_pending_image() {
  if (!pending_after_.isNull() && after_texture_) {
    upload_equirect(*this, after_texture_, pending_after_);
    pending_after_ = QImage();
  }
  if (pending_image_.isNull()) return;
  upload_equirect(*this, texture_, pending_image_);
  texture_size_ = pending_image_.size();
  shown_position_ = pending_position_;
  pending_image_ = QImage();
  emit image_shown(shown_position_);
}

void PanoramaView::paintGL() {
  glClearColor(0.12f, 0.12f, 0.14f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  upload_pending_image();
  if (program_ && program_->isLinked() && texture_size_.isValid()) {
    const double aspect = std::max(1, width()) / static_cast<double>(std::max(1, height()));
    const Eigen::Vector3d forward = angles_to_bearing({azimuth_, elevation_});
    const Eigen::Vector3d left = angles_to_bearing({azimuth_ - M_PI / 2, 0.0});
    const Eigen::Vector3d up = forward.cross(left).normalized();
    program_->bind();
    program_->setUniformValue("equirect", 0);
    program_->setUniformValue("whole_image", equirect_mode_ ? 1 : 0);
    program_->setUniformValue("forward", QVector3D(forward.x(), forward.y(), forward.z()));
    program_->setUniformValue("left", QVector3D(left.x(), left.y(), left.z()));
    program_->setUniformValue("up", QVector3D(up.x(), up.y(), up.z()));
    program_->setUniformValue("tan_half_fov", static_cast<GLfloat>(std::tan(0.5 * fov_)));
    program_->setUniformValue("aspect", static_cast<GLfloat>(aspect));
    // Letterbox the 2:1 image in whole-image mode.
    const double image_aspect = texture_size_.width() / static_cast<double>(texture_size_.height());
    const QVector2D scale = aspect > image_aspect ? QVector2D(image_aspect / aspect, 1.0f)
                                                  : QVector2D(1.0f, aspect / image_aspect);
    program_->setUniformValue("image_scale", scale);
    const bool compare = comparing() && shown_position_ == comparison_position_;
    program_->setUniformValue("after", 1);
    program_->setUniformValue("split", static_cast<GLfloat>(compare ? split_ : 2.0));
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, after_texture_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    vao_->bind();
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    vao_->release();
    program_->release();
  }
  draw_overlay();
}

void PanoramaView::draw_overlay() {
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  hotspots_->paint(painter);
  if (comparing() && shown_position_ == comparison_position_) {
    // The split line with a grip, and what each side shows.
    const double x = split_ * width();
    painter.setPen(QPen(QColor(255, 255, 255, 220), 2));
    painter.drawLine(QPointF(x, 0), QPointF(x, height() - 22));
    painter.setBrush(QColor(255, 255, 255, 220));
    painter.drawEllipse(QPointF(x, height() / 2.0), 7, 7);
    QFont label_font = painter.font();
    label_font.setBold(true);
    painter.setFont(label_font);
    const QString left_text = tr("Captured");
    const double left_width = painter.fontMetrics().horizontalAdvance(left_text) + 8.0,
                 right_width = painter.fontMetrics().horizontalAdvance(comparison_label_) + 8.0;
    const QRectF left_label(std::max(4.0, x - 8 - left_width), 8, left_width, 20),
        right_label(std::min(x + 8, width() - 4 - right_width), x + 8 + right_width > width() - 4 ? 32 : 8,
                    right_width, 20);
    painter.fillRect(left_label, QColor(0, 0, 0, 120));
    painter.fillRect(right_label, QColor(0, 0, 0, 120));
    painter.setPen(Qt::white);
    painter.drawText(left_label, Qt::AlignCenter, left_text);
    painter.drawText(right_label, Qt::AlignCenter, comparison_label_);
    // The stroke being painted: red for away, green for back.
    if (paint_value_) {
      painter.setPen(Qt::NoPen);
      painter.setBrush(paint_value_ == kCleanPlateKeep ? QColor(60, 200, 90, 110) : QColor(230, 60, 60, 110));
      const double r = equirect_mode_ ? 2.5 / 360.0 * image_box().width()
                                      : std::tan(2.5 * M_PI / 180) * 0.5 * width() / std::tan(0.5 * fov_);
      for (const QPointF& p : stroke_points_) painter.drawEllipse(p, r, r);
    }
    painter.setFont(QFont());
  }

  // Caption: frame, look direction; or why there is nothing to show.
  painter.setPen(Qt::white);
  QFont font = painter.font();
  font.setPointSizeF(9.5);
  painter.setFont(font);
  QString caption;
  if (shown_position_ >= 0) {
    caption = equirect_mode_ ? tr("frame %1 · whole image").arg(document_.frame_index_at(shown_position_))
                             : tr("frame %1 · look %2° / %3° · fov %4°")
                                   .arg(document_.frame_index_at(shown_position_))
                                   .arg(degrees(azimuth_), 0, 'f', 0)
                                   .arg(degrees(elevation_), 0, 'f', 0)
                                   .arg(degrees(fov_), 0, 'f', 0);
  }
  const QRectF bar(0, height() - 22, width(), 22);
  painter.fillRect(bar, QColor(0, 0, 0, 110));
  painter.drawText(bar.adjusted(8, 0, -8, 0), Qt::AlignVCenter | Qt::AlignLeft, caption);
  if (!message_.isEmpty())
    painter.drawText(rect().adjusted(12, 12, -12, -30), Qt::AlignCenter | Qt::TextWordWrap, message_);
}

QRectF PanoramaView::image_box() const {
  const double aspect = std::max(1, width()) / static_cast<double>(std::max(1, height()));
  const double image_aspect =
      texture_size_.isValid() ? texture_size_.width() / static_cast<double>(texture_size_.height()) : 2.0;
  const QSizeF box = aspect > image_aspect ? QSizeF(height() * image_aspect, height())
                                           : QSizeF(width(), width() / image_aspect);
  return QRectF(QPointF((width() - box.width()) / 2, (height() - box.height()) / 2), box);
}

// The same camera as the shader: a screen point (sx, sy) in [-1, 1]^2 looks along
// forward - sx * tan(fov/2) * left + sy * tan(fov/2) / aspect * up.
std::optional<SphericalAngles> PanoramaView::direction_at(const QPointF& widget_point) const {
  if (equirect_mode_) {
    const QRectF box = image_box();
    if (!box.contains(widget_point)) return std::nullopt;
    const QPointF f = widget_point - box.topLeft();
    return equirect_to_angles({f.x() / box.width() * 1000.0, f.y() / box.height() * 500.0}, 1000, 500);
  }
  const double aspect = std::max(1, width()) / static_cast<double>(std::max(1, height()));
  const Eigen::Vector3d forward = angles_to_bearing({azimuth_, elevation_});
  const Eigen::Vector3d left = angles_to_bearing({azimuth_ - M_PI / 2, 0.0});
  const Eigen::Vector3d up = forward.cross(left).normalized();
  const double t = std::tan(0.5 * fov_);
  const double sx = 2.0 * widget_point.x() / std::max(1, width()) - 1.0;
  const double sy = 1.0 - 2.0 * widget_point.y() / std::max(1, height());
  return bearing_to_angles(forward - sx * t * left + sy * t / aspect * up);
}

std::optional<QPointF> PanoramaView::widget_point_of(const SphericalAngles& direction) const {
  if (equirect_mode_) {
    const QRectF box = image_box();
    const Eigen::Vector2d px = angles_to_equirect(direction, 1000, 500);
    return box.topLeft() + QPointF(px.x() / 1000.0 * box.width(), px.y() / 500.0 * box.height());
  }
  const double aspect = std::max(1, width()) / static_cast<double>(std::max(1, height()));
  const Eigen::Vector3d d = angles_to_bearing(direction);
  const Eigen::Vector3d forward = angles_to_bearing({azimuth_, elevation_});
  const Eigen::Vector3d left = angles_to_bearing({azimuth_ - M_PI / 2, 0.0});
  const Eigen::Vector3d up = forward.cross(left).normalized();
  const double z = d.dot(forward);
  if (z <= 1e-3) return std::nullopt;
  const double t = std::tan(0.5 * fov_);
  const double sx = -d.dot(left) / z / t;
  const double sy = d.dot(up) / z / (t / aspect);
  return QPointF((sx * 0.5 + 0.5) * width(), (0.5 - sy * 0.5) * height());
}

// A round brush of 2.5 deg on the sphere: wider in the equirect image away from the horizon, across the seam.
void PanoramaView::paint_at(const QPointF& widget_point) {
  // A fast drag skips: fill in the line from the last point in steps of a few pixels.
  if (!stroke_points_.empty()) {
    const QPointF from = stroke_points_.back(), step = widget_point - from;
    const int steps = static_cast<int>(std::hypot(step.x(), step.y()) / 3.0);
    for (int i = 1; i < steps; ++i) paint_dab(from + step * (double(i) / steps));
  }
  paint_dab(widget_point);
  stroke_points_.push_back(widget_point);
  update();
}

void PanoramaView::paint_dab(const QPointF& widget_point) {
  const std::optional<SphericalAngles> direction = direction_at(widget_point);
  if (!direction || stroke_.isNull()) return;
  const int w = stroke_.width(), h = stroke_.height();
  const Eigen::Vector2d centre = angles_to_equirect(*direction, w, h);
  const double radius = 2.5 / 360.0 * w;
  const double stretch = 1.0 / std::max(0.1, std::cos(direction->elevation));
  QPainter painter(&stroke_);
  painter.setRenderHint(QPainter::Antialiasing, false);
  painter.setPen(Qt::NoPen);
  painter.setBrush(Qt::white);
  for (int shift : {-w, 0, w})
    painter.drawEllipse(QPointF(centre.x() + shift, centre.y()), radius * stretch, radius);
}

void PanoramaView::mousePressEvent(QMouseEvent* event) {
  last_mouse_ = event->pos();
  if (comparing() && event->button() == Qt::LeftButton && (event->modifiers() & Qt::ControlModifier) &&
      comparison_size_.isValid()) {
    paint_value_ = (event->modifiers() & Qt::ShiftModifier) ? kCleanPlateKeep : kCleanPlateRemove;
    stroke_ = QImage(comparison_size_, QImage::Format_Grayscale8);
    stroke_.fill(0);
    stroke_points_.clear();
    paint_at(event->pos());
    return;
  }
  if (comparing() && event->button() == Qt::LeftButton &&
      std::abs(event->pos().x() - split_ * width()) <= 8) {
    dragging_split_ = true;
    return;
  }
  hotspots_->mouse_press(event);
}

void PanoramaView::mouseReleaseEvent(QMouseEvent* event) {
  if (paint_value_) {
    const int value = paint_value_;
    paint_value_ = 0;
    stroke_points_.clear();
    emit stroke_painted(comparison_position_, stroke_, value);
    update();
    return;
  }
  if (dragging_split_) {
    dragging_split_ = false;
    return;
  }
  if (!hotspots_->mouse_release(event)) QOpenGLWidget::mouseReleaseEvent(event);
}

void PanoramaView::mouseDoubleClickEvent(QMouseEvent* event) {
  if (!hotspots_->mouse_double_click(event)) mousePressEvent(event);
}

void PanoramaView::mouseMoveEvent(QMouseEvent* event) {
  if (paint_value_) {
    paint_at(event->pos());
    return;
  }
  if (dragging_split_) {
    set_comparison_split(event->pos().x() / static_cast<double>(std::max(1, width())));
    return;
  }
  if (hotspots_->mouse_move(event)) return;
  if (!(event->buttons() & Qt::LeftButton) || equirect_mode_) return;
  const QPoint delta = event->pos() - last_mouse_;
  last_mouse_ = event->pos();
  // Grab-and-drag: the scene follows the mouse, so dragging right looks left.
  const double radians_per_pixel = fov_ / std::max(1, width());
  set_look(azimuth_ - delta.x() * radians_per_pixel, elevation_ + delta.y() * radians_per_pixel, fov_);
}

void PanoramaView::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  set_look(azimuth_, elevation_, fov_ * std::pow(0.9, steps));
}

void PanoramaView::keyPressEvent(QKeyEvent* event) {
  if (hotspots_->key_press(event)) return;
  switch (event->key()) {
    case Qt::Key_Right:
    case Qt::Key_PageDown:
      document_.step(event->modifiers() & Qt::ShiftModifier ? 10 : 1);
      break;
    case Qt::Key_Left:
    case Qt::Key_PageUp:
      document_.step(event->modifiers() & Qt::ShiftModifier ? -10 : -1);
      break;
    case Qt::Key_Home:
      document_.set_current_position(0);
      break;
    case Qt::Key_End:
      document_.set_current_position(document_.frame_count() - 1);
      break;
    case Qt::Key_E:
      set_equirect_mode(!equirect_mode_);
      break;
    case Qt::Key_Escape:
      if (comparing())
        clear_comparison();
      else
        QOpenGLWidget::keyPressEvent(event);
      break;
    default:
      QOpenGLWidget::keyPressEvent(event);
  }
}

}  // namespace plenopath::widgets
