// The sampling panel's visibility and depth methods: a clear message until visibility is computed; then
// switching to visibility resamples (on the worker), meets the budget, shows the loss, is one undo step,
// and a slider drag stays one undo step.
#include "widgets/sampling_panel.h"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QDir>
#include <QSlider>
#include <QTemporaryDir>
#include <QUndoStack>
#include <opencv2/imgcodecs.hpp>

#include "app/studio/studio_tasks.h"
#include "processing/sampling/uniform_sampling.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/wait_until.h"
#include "widgets/project_document.h"

namespace plenopath {
namespace {

using widgets::SamplingPanel;

int expected_budget(const SamplingPanel& panel, int frames) {
  SamplingParameters p;
  p.ratio = SamplingPanel::ratio_of_slider(panel.budget_slider()->value());
  return keyframe_budget(p, frames);
}

void select(SamplingPanel& panel, const char* data) {
  panel.method_box()->setCurrentIndex(panel.method_box()->findData(data));
}

TEST(SamplingPanel, VisibilityNeedsTheCellsFirst) {
  Project project = test::test_project().project;
  project.visibility = {};
  widgets::ProjectDocument document;
  document.reset(project, QString());
  SamplingPanel panel(document);
  select(panel, "uniform");
  const int steps = document.undo_stack()->count();
  select(panel, "visibility");
  panel.wait();
  EXPECT_TRUE(panel.statistics_text().contains("Compute visibility"))
      << panel.statistics_text().toStdString();
  EXPECT_EQ(document.undo_stack()->count(), steps);
  select(panel, "depth");  // the test capture has no depth maps
  EXPECT_TRUE(panel.statistics_text().contains("depth")) << panel.statistics_text().toStdString();
  EXPECT_EQ(document.undo_stack()->count(), steps);
}

TEST(SamplingPanel, SwitchingToVisibilityResamplesWithinTheBudgetAndUndoes) {
  Project project = test::test_project().project;
  project.visibility = VisibilityIndex(project.plan).cells_along_path(project.path);
  ASSERT_FALSE(project.visibility.empty());
  widgets::ProjectDocument document;
  document.reset(project, QString());
  SamplingPanel panel(document);
  QUndoStack* stack = document.undo_stack();

  select(panel, "uniform");
  panel.budget_slider()->setValue(SamplingPanel::slider_of_ratio(4.0));
  const Keyframes uniform = document.project().keyframes;
  ASSERT_EQ(static_cast<int>(uniform.indices.size()), expected_budget(panel, 30));
  const int steps = stack->count();

  select(panel, "visibility");
  ASSERT_TRUE(test::wait_until([&] { return !panel.busy(); }, 60000));
  const Keyframes visibility = document.project().keyframes;
  EXPECT_EQ(visibility.parameters.method, SamplingMethod::kVisibility);
  EXPECT_EQ(static_cast<int>(visibility.indices.size()), expected_budget(panel, 30));
  EXPECT_EQ(visibility.indices.front(), 0);
  EXPECT_EQ(visibility.indices.back(), 29);
  EXPECT_EQ(visibility.rank.size(), visibility.indices.size());
  EXPECT_EQ(stack->count(), steps + 1);
  // The statistics show the loss of these keyframes (measured on the worker).
  ASSERT_TRUE(test::wait_until([&] { return panel.statistics_text().contains("geometric loss"); }, 60000))
      << panel.statistics_text().toStdString();
  EXPECT_TRUE(panel.statistics_text().contains("max gap"));

  stack->undo();
  EXPECT_EQ(document.project().keyframes, uniform);
  stack->redo();
  EXPECT_EQ(document.project().keyframes, visibility);

  // The seed's cell rule, then a drag of the budget: one more undo step each, budgets met.
  select(panel, "visibility:cells");
  ASSERT_TRUE(test::wait_until([&] { return !panel.busy(); }, 60000));
  EXPECT_EQ(static_cast<int>(document.project().keyframes.indices.size()), expected_budget(panel, 30));
  EXPECT_TRUE(panel.exponent_slider()->isEnabled());
  // The document records the rule, so another panel on it (a reopened project) shows the cell rule.
  EXPECT_EQ(document.project().keyframes.parameters.method, SamplingMethod::kVisibility);
  EXPECT_EQ(document.project().keyframes.parameters.rule, VisibilityRule::cell_rule);
  EXPECT_FALSE(document.project().keyframes.sampler.refinement.applied);
  {
    widgets::ProjectDocument reopened;
    reopened.reset(document.project(), QString());
    SamplingPanel shown(reopened);
    EXPECT_EQ(shown.method_box()->currentData().toString(), "visibility:cells");
    shown.wait();
  }
  EXPECT_EQ(visibility.parameters.rule, VisibilityRule::expected_loss);
  EXPECT_TRUE(visibility.sampler.refinement.applied);
  const int before_drag = stack->count();
  QSlider* slider = panel.budget_slider();
  slider->setSliderDown(true);
  for (double r : {6.0, 8.0, 10.0}) {
    slider->setValue(SamplingPanel::slider_of_ratio(r));
    QCoreApplication::processEvents();
  }
  slider->setSliderDown(false);
  ASSERT_TRUE(test::wait_until([&] { return !panel.busy(); }, 60000));
  EXPECT_EQ(stack->count(), before_drag + 1);
  EXPECT_EQ(static_cast<int>(document.project().keyframes.indices.size()), expected_budget(panel, 30));
}

// Depth sampling once the capture has depth maps (rendered here as 16-bit PNG in millimetres).
TEST(SamplingPanel, DepthSamplingWithDepthMaps) {
  Project project = test::test_project().project;
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const SyntheticScene scene = build_synthetic_scene(project.plan);
  RenderOptions render;  // the frames' size: depth maps must match them
  render.width = project.capture.width;
  render.height = project.capture.height;
  for (const PathFrame& f : project.path.frames) {
    cv::Mat depth_mm;
    render_panorama(scene, f, render).depth.convertTo(depth_mm, CV_16U, 1000.0);
    const std::string name = QString("%1.png").arg(f.index, 6, 10, QChar('0')).toStdString();
    ASSERT_TRUE(cv::imwrite(QDir(dir.path()).filePath(QString::fromStdString(name)).toStdString(), depth_mm));
  }
  project.capture.depth_folder = dir.path().toStdString();
  widgets::ProjectDocument document;
  document.reset(project, QString());
  SamplingPanel panel(document);
  select(panel, "uniform");
  const int steps = document.undo_stack()->count();
  select(panel, "depth");
  ASSERT_TRUE(test::wait_until([&] { return !panel.busy(); }, 60000));
  const Keyframes k = document.project().keyframes;
  EXPECT_EQ(k.parameters.method, SamplingMethod::kDepth) << panel.statistics_text().toStdString();
  EXPECT_EQ(static_cast<int>(k.indices.size()), expected_budget(panel, 30));
  EXPECT_EQ(document.undo_stack()->count(), steps + 1);
  document.undo_stack()->undo();
  EXPECT_EQ(document.project().keyframes.parameters.method, SamplingMethod::kUniform);
}

}  // namespace
}  // namespace plenopath
