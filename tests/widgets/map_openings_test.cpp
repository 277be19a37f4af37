// The map shows the gaps in the outer walls that visibility closes (windows drawn as gaps), as glass-blue
// lines across them. Truths: the windows' places, by hand.
#include <gtest/gtest.h>

#include <QImage>

#include "tests/processing/plan/plan_oracle.h"
#include "tests/widgets/test_studio.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"

namespace plenopath {
namespace {

bool is_glass_colour(QRgb c) { return qBlue(c) > 180 && qRed(c) < 120 && qGreen(c) > 90 && qGreen(c) < 190; }

TEST(MapOpenings, WindowsDrawnAsGapsAreShownClosed) {
  Project project;
  project.plan.layers = {{"WALLS", 7, true, true, 0}};
  // A 10 x 6 m hall, walls 0.2 m thick; windows x 2.2-3.8 and 6.2-7.8 in the south wall.
  test::add_thick_wall(&project.plan, {0, 0}, {2.1, 0}, 0.2);
  test::add_thick_wall(&project.plan, {3.9, 0}, {6.1, 0}, 0.2);
  test::add_thick_wall(&project.plan, {7.9, 0}, {10, 0}, 0.2);
  test::add_thick_wall(&project.plan, {10, 0}, {10, 6}, 0.2);
  test::add_thick_wall(&project.plan, {10, 6}, {0, 6}, 0.2);
  test::add_thick_wall(&project.plan, {0, 6}, {0, 0}, 0.2);
  test::TestStudio s;
  s.window.document().reset(project, QString());
  widgets::MapView* map = s.window.map_view();
  map->reset_camera();
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  if (qEnvironmentVariableIsSet("PLENOPATH_TEST_SAVE")) image.save("/tmp/map_openings.png");
  const QPoint inside = map->widget_pixel_of({5.0, 3.0});
  ASSERT_GT(image.width(), 0);
  for (const double x : {3.0, 7.0})
    EXPECT_GT(test::count_near(image, map->widget_pixel_of({x, 0.0}), 4, is_glass_colour), 6)
        << "window at x " << x;
  EXPECT_EQ(test::count_near(image, map->widget_pixel_of({1.0, 0.0}), 3, is_glass_colour), 0) << "a wall";
  EXPECT_EQ(test::count_near(image, inside, 10, is_glass_colour), 0) << "the hall";
}

}  // namespace
}  // namespace plenopath
