#pragma once
// A small project made in code for the studio tests: an 8 m x 5 m room split by a half wall, a straight
// 30-frame path through it, and 256 x 128 frames rendered by the synthetic camera (so every frame is a real
// equirectangular view whose pixels the tests can check).
#include <QString>

#include "model/project.h"

namespace plenopath::test {

struct TestProject {
  QString folder;        // temporary folder holding everything
  QString project_file;  // folder/test.plenopath
  Project project;       // as saved
};

// Made once per process (frames rendered once) and reused; `name` picks a separate copy.
const TestProject& test_project(const QString& name = "default");

}  // namespace plenopath::test
