#include "tests/widgets/test_project.h"

#include <QDir>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "model/project_io.h"
#include "rig/synthetic_camera.h"

namespace plenopath::test {

namespace {

FloorPlan room_plan() {
  FloorPlan plan;
  plan.layers.push_back({"WALLS", 7, true, true, 5});
  plan.layers.push_back({"FURNITURE", 3, true, false, 4});
  auto wall = [&](double ax, double ay, double bx, double by) {
    plan.segments.push_back({{ax, ay}, {bx, by}, "WALLS", true});
  };
  wall(0, 0, 8, 0);
  wall(8, 0, 8, 5);
  wall(8, 5, 0, 5);
  wall(0, 5, 0, 0);
  wall(4, 0, 4, 2.5);  // half wall: what is seen changes along the path
  // A desk that does not block sight.
  const std::vector<Eigen::Vector2d> desk{{1.5, 0.8}, {2.7, 0.8}, {2.7, 1.4}, {1.5, 1.4}};
  for (std::size_t i = 0; i < desk.size(); ++i)
    plan.segments.push_back({desk[i], desk[(i + 1) % desk.size()], "FURNITURE", false});
  plan.outlines.push_back({desk, "FURNITURE", true});
  return plan;
}

TestProject make(const QString& name) {
  static std::vector<std::unique_ptr<QTemporaryDir>> dirs;  // removed at exit
  dirs.push_back(std::make_unique<QTemporaryDir>(QDir::temp().filePath("plenopath-studio-test-XXXXXX")));
  TestProject t;
  t.folder = dirs.back()->path();
  const QDir dir(t.folder);
  dir.mkpath("frames");

  Project& p = t.project;
  p.plan = room_plan();
  p.tour.title = "Studio test " + name.toStdString();
  const int n = 30;
  for (int i = 0; i < n; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 1.0 + 6.0 * i / (n - 1);
    f.y = 3.5;
    f.heading = 0.0;
    f.file = QString("frames/%1.png").arg(i, 6, 10, QChar('0')).toStdString();
    p.path.frames.push_back(f);
  }
  SceneOptions scene_options;
  scene_options.texture_size = 256;
  const SyntheticScene scene = build_synthetic_scene(p.plan, scene_options);
  RenderOptions render;
  render.width = 256;
  render.height = 128;
  render.depth = false;
  for (const PathFrame& f : p.path.frames) {
    const RenderedPanorama pano = render_panorama(scene, f, render);
    cv::imwrite(dir.filePath(QString::fromStdString(f.file)).toStdString(), pano.rgb);
    p.capture.frame_names.push_back(f.file.substr(std::string("frames/").size()));
  }
  p.capture.kind = CaptureKind::kImageFolder;
  p.capture.source = dir.filePath("frames").toStdString();
  p.capture.frame_count = n;
  p.capture.width = render.width;
  p.capture.height = render.height;
  p.capture.frame_rate = 10.0;
  // A hotspot in frame 0: azimuth -20..+20 deg, elevation -10..+20 deg.
  Hotspot h;
  h.id = "poster";
  h.title = "Poster";
  h.frame = 0;
  h.kind = HotspotKind::kEvent;
  h.action = HotspotAction::kShowText;
  for (const auto& [az, el] :
       std::vector<std::pair<double, double>>{{-20, -10}, {20, -10}, {20, 20}, {-20, 20}})
    h.image_corners.push_back({az * M_PI / 180.0, el * M_PI / 180.0});
  p.hotspots.push_back(h);
  t.project_file = dir.filePath("test.plenopath");
  save_project(p, t.project_file.toStdString());
  t.project = load_project(t.project_file.toStdString());  // paths as the studio will see them
  return t;
}

}  // namespace

const TestProject& test_project(const QString& name) {
  static std::map<QString, TestProject> made;
  auto it = made.find(name);
  if (it == made.end()) it = made.emplace(name, make(name)).first;
  return it->second;
}

}  // namespace plenopath::test
