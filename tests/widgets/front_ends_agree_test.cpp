// The command line and the studio are two faces of one pipeline (issue 17): on the office sample
// (`plenopath make-sample`, its capture rendered by `plenopath render`) `plenopath track`, `visibility`,
// `sample` and `export` and the studio's Track, Compute visibility, sampling and Export tour give the same
// bytes: the path file and its points, the project file (path, cells, keyframes), and every entry of the
// exported package. Each face starts from its own copy of the same project file; the truth is that two
// independent front ends agree, so any difference is a bug (a hidden default, a thread count, a format).
#include <gtest/gtest.h>

#include <QDir>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "app/studio/studio_tasks.h"
#include "model/path_io.h"
#include "processing/pipeline/sample_step.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

const std::string kCli = PLENOPATH_BINARY_DIR "/app/plenopath";

// Runs the command line; false (and a failure naming the command) when it fails.
bool run(const std::string& arguments) {
  const std::string command = kCli + " " + arguments;
  const int code = std::system(command.c_str());
  EXPECT_EQ(code, 0) << command;
  return code == 0;
}

// A path for the shell (the test's folder has no quote in it).
std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

std::string bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  EXPECT_TRUE(in.good()) << file;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every file under `dir`, by its path relative to it, with its bytes.
std::map<std::string, std::string> package(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).generic_string()] = bytes(e.path());
  return out;
}

// Runs one studio task to its end as the studio does (worker thread, one undo step).
void run_task(widgets::TaskRunner& runner, const QString& title, widgets::TaskFunction task) {
  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  QSignalSpy finished(&runner, &widgets::TaskRunner::finished);
  ASSERT_TRUE(runner.start(title, std::move(task))) << title.toStdString();
  runner.wait();
  ASSERT_EQ(failed.count(), 0) << title.toStdString() << ": " << failed.at(0).at(1).toString().toStdString();
  ASSERT_EQ(finished.count(), 1) << title.toStdString();
}

TEST(FrontEndsAgree, OnTheOfficeSample) {
  QTemporaryDir tmp(QDir::tempPath() + "/plenopath_front_ends_XXXXXX");
  ASSERT_TRUE(tmp.isValid());
  const fs::path dir = tmp.path().toStdString();
  const fs::path s = dir / "s";
  ASSERT_TRUE(run("make-sample --out " + quoted(s) + " --frames 60 > /dev/null"));
  ASSERT_TRUE(run("render --plan " + quoted(s / "office.dxf") + " --path " + quoted(s / "office_path.json") +
                  " --size 512x256 --depth --out " + quoted(s / "capture") + " --quiet"));
  fs::copy_file(s / "office.plenopath", s / "cli.plenopath");
  fs::copy_file(s / "office.plenopath", s / "studio.plenopath");

  // The command line.
  const std::string cli_project = quoted(s / "cli.plenopath");
  ASSERT_TRUE(run("track --project " + cli_project + " --out " + quoted(dir / "cli_path.json") +
                  " --quiet > /dev/null"));
  ASSERT_TRUE(run("visibility --project " + cli_project + " --save --json > /dev/null"));
  ASSERT_TRUE(run("sample --project " + cli_project +
                  " --method visibility --ratio 10 --save --json > /dev/null 2>&1"));
  ASSERT_TRUE(
      run("export --project " + cli_project + " --out " + quoted(dir / "cli_tour") + " > /dev/null 2>&1"));

  // The studio: its tasks on its document; sampling as the sampling panel runs it (the pipeline's step on a
  // snapshot, applied as one undo step).
  widgets::ProjectDocument document;
  document.load(QString::fromStdString((s / "studio.plenopath").string()));
  widgets::TaskRunner runner(document);
  run_task(runner, "Track", studio::track_path_task());
  write_path_file(document.project().path, (dir / "studio_path.json").string());
  write_path_points_file(document.project().path_points, (dir / "studio_path.points.json").string());
  run_task(runner, "Compute visibility", studio::compute_visibility_task());
  pipeline::SampleStepOptions sampling;
  sampling.request.parameters.method = SamplingMethod::kVisibility;
  sampling.request.parameters.ratio = 10.0;
  const pipeline::SampleStepResult sampled = pipeline::run_sample(document.snapshot(), sampling);
  document.undo_stack()->push(
      new widgets::ReplacePartsCommand(document, "Sample keyframes", sampled.project, sampled.changed));
  document.save(QString::fromStdString((s / "studio.plenopath").string()));
  run_task(runner, "Export tour", studio::export_tour_task((dir / "studio_tour").string()));
  EXPECT_EQ(document.undo_stack()->count(), 3);  // track, visibility, sampling; an export changes nothing

  // The path file and the tracker's points beside it.
  EXPECT_EQ(bytes(dir / "cli_path.json"), bytes(dir / "studio_path.json")) << "the path files differ";
  EXPECT_EQ(bytes(dir / "cli_path.points.json"), bytes(dir / "studio_path.points.json"))
      << "the points files differ";
  EXPECT_EQ(bytes(s / "cli.points.json"), bytes(s / "studio.points.json")) << "the projects' points differ";
  // The project files, part by part, then whole.
  const nlohmann::json cli = nlohmann::json::parse(bytes(s / "cli.plenopath"));
  const nlohmann::json studio = nlohmann::json::parse(bytes(s / "studio.plenopath"));
  for (const char* part : {"capture", "path", "visibility", "keyframes", "anchors"})
    EXPECT_EQ(cli.value(part, nlohmann::json()).dump(), studio.value(part, nlohmann::json()).dump())
        << "the projects' " << part << " differ";
  EXPECT_FALSE(studio["visibility"].dump().size() < 40) << "no cells: " << studio["visibility"].dump();
  EXPECT_EQ(bytes(s / "cli.plenopath"), bytes(s / "studio.plenopath")) << "the project files differ";
  // The package: the same entries with the same bytes.
  const auto cli_package = package(dir / "cli_tour");
  const auto studio_package = package(dir / "studio_tour");
  ASSERT_FALSE(cli_package.empty());
  std::string names_cli, names_studio;
  for (const auto& [name, content] : cli_package) names_cli += name + "\n";
  for (const auto& [name, content] : studio_package) names_studio += name + "\n";
  ASSERT_EQ(names_cli, names_studio) << "the packages hold different files";
  int differing = 0;
  for (const auto& [name, content] : cli_package)
    if (content != studio_package.at(name)) {
      ADD_FAILURE() << "package entry " << name << " differs (" << content.size() << " and "
                    << studio_package.at(name).size() << " bytes)";
      ++differing;
    }
  std::printf(
      "front ends agree: %zu package entries compared, %d differ; path of %zu frames, %zu keyframes\n",
      cli_package.size(), differing, document.project().path.size(),
      document.project().keyframes.indices.size());
}

}  // namespace
}  // namespace plenopath
