#include "widgets/walk_view.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLBuffer>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "widgets/frame_provider.h"
#include "widgets/fullscreen_triangle.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {
namespace {

constexpr int kTextureCache = 8;

// ray maps (ndc.x, ndc.y, 1) to a world direction (plan frame, z up). A keyframe with heading h sees world
// angle phi at azimuth h - phi (rig/spherical.h), i.e. at texture u = (h - phi + pi) / 2pi.
const char* kFragmentShader = R"(#version 150
uniform mat3 ray;
uniform sampler2D current_image;
uniform sampler2D previous_image;
uniform float current_heading;
uniform float previous_heading;
uniform float fade;
in vec2 ndc;
out vec4 colour;
const float PI = 3.14159265358979;
vec4 equirect(sampler2D image, float heading, vec3 d) {
  float phi = atan(d.y, d.x);
  float elevation = atan(d.z, length(d.xy));
  return texture(image, vec2(fract((heading - phi + PI) / (2.0 * PI)), (0.5 * PI - elevation) / PI));
}
void main() {
  vec3 d = ray * vec3(ndc, 1.0);
  colour = vec4(mix(equirect(previous_image, previous_heading, d).rgb,
                    equirect(current_image, current_heading, d).rgb, fade), 1.0);
}
)";

}  // namespace

WalkView::WalkView(ProjectDocument& document, FrameProvider& frames, QWidget* parent)
    : QOpenGLWidget(parent),
      document_(document),
      frames_(frames),
      navigator_(document.project().path, document.project().keyframes) {
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(480, 320);
  setWindowTitle(tr("Walk — Plenopath Studio"));
  for (const WalkKeyframe& k : navigator_.keyframes())
    position_of_keyframe_.push_back(document_.position_of_frame_index(k.frame));
  connect(&frames_, &FrameProvider::frame_ready, this, [this](int position, const QImage& image) {
    for (int k = 0; k < static_cast<int>(position_of_keyframe_.size()); ++k)
      if (position_of_keyframe_[k] == position) images_.insert(k, image);
    update();
    request_images();
  });
  timer_.setInterval(8);  // ~120 Hz ticks; paints are vsync-limited
  connect(&timer_, &QTimer::timeout, this, &WalkView::tick);
  clock_.start();
  fps_clock_.start();
  request_images();
}

WalkView::~WalkView() {
  if (context()) {
    makeCurrent();
    release_gl();
    doneCurrent();
  }
}

void WalkView::release_gl() {
  for (unsigned t : textures_) glDeleteTextures(1, &t);
  textures_.clear();
  texture_order_.clear();
  quad_.reset();
  vao_.reset();
  program_.reset();
}

// Asks the frame provider for the images the walk needs next: the current keyframe, then its neighbours.
void WalkView::request_images() {
  const int current = navigator_.current_keyframe();
  for (int k : {current, current + 1, current - 1}) {
    if (k < 0 || k >= static_cast<int>(position_of_keyframe_.size()) || images_.contains(k)) continue;
    const QImage cached = frames_.cached(position_of_keyframe_[k]);
    if (!cached.isNull()) {
      images_.insert(k, cached);
      continue;
    }
    frames_.request(position_of_keyframe_[k]);  // latest-wins: one at a time, the next after frame_ready
    return;
  }
}

unsigned WalkView::texture_for(int keyframe) {
  auto it = textures_.find(keyframe);
  if (it == textures_.end()) {
    const auto image = images_.find(keyframe);
    if (image == images_.end()) return 0;
    const QImage rgba = image->convertToFormat(QImage::Format_RGBA8888);
    unsigned texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, rgba.width(), rgba.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 rgba.constBits());
    it = textures_.insert(keyframe, texture);
    images_.remove(keyframe);  // the GPU copy is enough now
  }
  texture_order_.removeAll(keyframe);
  texture_order_.append(keyframe);
  while (texture_order_.size() > kTextureCache) {
    const int old = texture_order_.takeFirst();
    unsigned t = textures_.take(old);
    glDeleteTextures(1, &t);
  }
  return it.value();
}

void WalkView::initializeGL() {
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
  program_->link();
  vao_ = std::make_unique<QOpenGLVertexArrayObject>();
  vao_->create();
  vao_->bind();
  quad_ = std::make_unique<QOpenGLBuffer>(QOpenGLBuffer::VertexBuffer);
  quad_->create();
  quad_->bind();
  const float corners[] = {-1, -1, 3, -1, -1, 3};
  quad_->allocate(corners, sizeof corners);
  program_->enableAttributeArray(0);
  program_->setAttributeBuffer(0, GL_FLOAT, 0, 2);
  vao_->release();
}

void WalkView::paintGL() {
  glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const int current = navigator_.current_keyframe();
  const int previous = navigator_.previous_keyframe();
  unsigned current_texture = texture_for(current);
  unsigned previous_texture = texture_for(previous);
  const bool have_current = current_texture != 0;
  if (!previous_texture) previous_texture = current_texture;
  if (have_current && program_ && program_->isLinked()) {
    // Camera basis in the plan frame: forward f, right r, up u for the world yaw and the pitch.
    const double yaw = navigator_.yaw(), cp = std::cos(pitch_), sp = std::sin(pitch_);
    const QVector3D f(cp * std::cos(yaw), cp * std::sin(yaw), sp);
    const QVector3D r(std::sin(yaw), -std::cos(yaw), 0);
    const QVector3D u = QVector3D::crossProduct(r, f);
    const float ty = std::tan(fov_ / 2), tx = ty * width() / std::max(1, height());
    QMatrix3x3 ray;
    for (int i = 0; i < 3; ++i) {
      ray(i, 0) = r[i] * tx;
      ray(i, 1) = u[i] * ty;
      ray(i, 2) = f[i];
    }
    program_->bind();
    program_->setUniformValue("ray", ray);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, current_texture);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, previous_texture);
    program_->setUniformValue("current_image", 0);
    program_->setUniformValue("previous_image", 1);
    program_->setUniformValue("current_heading", float(navigator_.keyframes()[current].heading));
    program_->setUniformValue("previous_heading", float(navigator_.keyframes()[previous].heading));
    program_->setUniformValue("fade", float(previous_texture == current_texture ? 1.0 : navigator_.fade()));
    vao_->bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    vao_->release();
    program_->release();
    glActiveTexture(GL_TEXTURE0);
  }

  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  const WalkKeyframe& k = navigator_.keyframes()[current];
  const QString status =
      tr("Keyframe %1 of %2 · frame %3 · %4 m of %5 m   (W/S walk · drag to look · Esc closes)")
          .arg(current + 1)
          .arg(navigator_.keyframes().size())
          .arg(k.frame)
          .arg(navigator_.s(), 0, 'f', 1)
          .arg(navigator_.path_length(), 0, 'f', 1);
  painter.fillRect(QRect(10, 10, painter.fontMetrics().horizontalAdvance(status) + 16, 26),
                   QColor(0, 0, 0, 150));
  painter.setPen(Qt::white);
  painter.drawText(QRect(18, 10, width(), 26), Qt::AlignVCenter, status);
  if (!have_current) painter.drawText(rect(), Qt::AlignCenter, tr("Loading keyframe %1…").arg(k.frame));
  draw_map(painter);

  ++frames_drawn_;
  if (fps_clock_.elapsed() >= 1000) {
    fps_ = frames_drawn_ * 1000.0 / fps_clock_.restart();
    frames_drawn_ = 0;
  }
}

QRectF WalkView::map_rect() const {
  const double w = std::clamp(width() * 0.3, 180.0, 420.0), h = w * 0.75;
  return {width() - w - 12, height() - h - 12, w, h};
}

QPointF WalkView::map_point(const Eigen::Vector2d& p) const {
  const PlanExtents e = document_.project().plan.extents();
  Eigen::Vector2d lo = e.valid ? e.min : Eigen::Vector2d(0, 0), hi = e.valid ? e.max : Eigen::Vector2d(1, 1);
  for (const WalkKeyframe& k : navigator_.keyframes()) {
    lo = lo.cwiseMin(k.position);
    hi = hi.cwiseMax(k.position);
  }
  lo.array() -= 0.5;
  hi.array() += 0.5;
  const QRectF r = map_rect();
  const double scale = std::min(r.width() / (hi.x() - lo.x()), r.height() / (hi.y() - lo.y()));
  const double ox = r.left() + (r.width() - scale * (hi.x() - lo.x())) / 2;
  const double oy = r.top() + (r.height() - scale * (hi.y() - lo.y())) / 2;
  return {ox + scale * (p.x() - lo.x()), oy + scale * (hi.y() - p.y())};
}

Eigen::Vector2d WalkView::plan_point(const QPointF& q) const {
  // Invert map_point from two reference points (it is an axis-aligned scale and offset).
  const QPointF o = map_point({0, 0}), x = map_point({1, 0}), y = map_point({0, 1});
  return {(q.x() - o.x()) / (x.x() - o.x()), (q.y() - o.y()) / (y.y() - o.y())};
}

void WalkView::draw_map(QPainter& painter) {
  const QRectF r = map_rect();
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(250, 250, 250, 235));
  painter.drawRoundedRect(r, 6, 6);
  painter.save();
  painter.setClipRect(r);
  const Project& project = document_.project();
  for (const PlanSegment& s : project.plan.segments) {
    painter.setPen(QPen(s.occluder ? QColor(30, 30, 30) : QColor(150, 150, 150), s.occluder ? 2.0 : 1.0));
    painter.drawLine(map_point(s.a), map_point(s.b));
  }
  QPainterPath path;
  for (std::size_t i = 0; i < project.path.frames.size(); ++i) {
    const QPointF p = map_point(project.path.frames[i].position());
    if (i == 0)
      path.moveTo(p);
    else
      path.lineTo(p);
  }
  painter.setPen(QPen(QColor(42, 111, 219), 2));
  painter.setBrush(Qt::NoBrush);
  painter.drawPath(path);
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(240, 140, 0));
  for (const WalkKeyframe& k : navigator_.keyframes()) painter.drawEllipse(map_point(k.position), 3, 3);
  // The viewer and a view cone of the horizontal field of view.
  const QPointF here = map_point(navigator_.position_at(navigator_.s()));
  const double hfov = 2 * std::atan(std::tan(fov_ / 2) * width() / std::max(1, height()));
  QPainterPath cone;
  cone.moveTo(here);
  const double degrees_per_radian = 180.0 / M_PI;
  cone.arcTo(QRectF(here.x() - 40, here.y() - 40, 80, 80), (navigator_.yaw() - hfov / 2) * degrees_per_radian,
             hfov * degrees_per_radian);
  cone.closeSubpath();
  painter.setBrush(QColor(220, 40, 40, 70));
  painter.drawPath(cone);
  painter.setBrush(QColor(210, 30, 30));
  painter.drawEllipse(here, 5, 5);
  painter.restore();
}

void WalkView::tick() {
  const double dt = clock_.restart() / 1000.0;
  const bool busy = navigator_.advance(dt);
  if (navigator_.current_keyframe() != last_emitted_keyframe_) {
    last_emitted_keyframe_ = navigator_.current_keyframe();
    emit keyframe_changed(navigator_.keyframes()[last_emitted_keyframe_].frame);
    request_images();
  }
  update();
  if (!busy) timer_.stop();
}

void WalkView::keyPressEvent(QKeyEvent* event) {
  const double step = 5.0 * M_PI / 180.0;
  switch (event->key()) {
    case Qt::Key_W:
    case Qt::Key_Up:
      navigator_.step(+1);
      break;
    case Qt::Key_S:
    case Qt::Key_Down:
      navigator_.step(-1);
      break;
    case Qt::Key_A:
    case Qt::Key_Left:
      navigator_.set_yaw(navigator_.yaw() + step);
      break;
    case Qt::Key_D:
    case Qt::Key_Right:
      navigator_.set_yaw(navigator_.yaw() - step);
      break;
    case Qt::Key_PageUp:
      pitch_ = std::min(1.45, pitch_ + step);
      break;
    case Qt::Key_PageDown:
      pitch_ = std::max(-1.45, pitch_ - step);
      break;
    case Qt::Key_Plus:
    case Qt::Key_Equal:
      fov_ = std::max(0.35, fov_ / 1.1);
      break;
    case Qt::Key_Minus:
      fov_ = std::min(2.0, fov_ * 1.1);
      break;
    case Qt::Key_F11:
      isFullScreen() ? showNormal() : showFullScreen();
      break;
    case Qt::Key_Escape:
      close();
      return;
    default:
      QOpenGLWidget::keyPressEvent(event);
      return;
  }
  clock_.restart();
  timer_.start();
  update();
}

void WalkView::mousePressEvent(QMouseEvent* event) {
  last_mouse_ = press_mouse_ = event->pos();
  map_drag_ = map_rect().contains(event->pos());
  if (map_drag_) {
    navigator_.walk_to(navigator_.nearest_s(plan_point(event->pos())));
    clock_.restart();
    timer_.start();
  }
}

void WalkView::mouseMoveEvent(QMouseEvent* event) {
  if (!(event->buttons() & Qt::LeftButton)) return;
  if (map_drag_) {
    navigator_.walk_to(navigator_.nearest_s(plan_point(event->pos())));
    timer_.start();
    return;
  }
  const double per_pixel = fov_ / std::max(1, height());
  const QPoint d = event->pos() - last_mouse_;
  navigator_.set_yaw(navigator_.yaw() + d.x() * per_pixel);
  pitch_ = std::clamp(pitch_ + d.y() * per_pixel, -1.45, 1.45);
  last_mouse_ = event->pos();
  update();
}

void WalkView::mouseReleaseEvent(QMouseEvent*) { map_drag_ = false; }

void WalkView::wheelEvent(QWheelEvent* event) {
  if (event->modifiers() & Qt::ControlModifier)
    fov_ = std::clamp(fov_ * (event->angleDelta().y() < 0 ? 1.08 : 1 / 1.08), 0.35, 2.0);
  else
    navigator_.step(event->angleDelta().y() > 0 ? +1 : -1);
  clock_.restart();
  timer_.start();
  update();
}

}  // namespace plenopath::widgets
