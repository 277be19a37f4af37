// Keyframe sampling on the office sample: geometric loss (mean and 95th percentile of 1 - IoU between a
// dropped frame's envelope and its stand-in's) of each sampler at 10x, 50x and 100x reduction, and the
// ratio visibility_mean / uniform_mean at 50x (target <= 0.8). Also: the cell rule's loss for several
// exponents on the sample and on random plans (which default exponent measures best), and timings.
// Ground truth: rig/synthetic_camera.h make_office_sample_plan + auto_walk with a 4 cm step (dense enough
// that 100x still keeps dozens of keyframes); depth maps from the synthetic renderer at 128 x 64 (the depth
// sampler sees them only, never the plan).
// Prints one JSON object.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "processing/sampling/depth_volume.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/sampling_loss.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/plan/plan_oracle.h"

using namespace plenopath;
using Clock = std::chrono::steady_clock;

namespace {

using test::add_wall;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A random office: a grid of rooms of random sizes, every inner wall with a 1 m door at a random place,
// and a few pillars.
FloorPlan random_plan(std::mt19937* rng) {
  FloorPlan plan;
  PlanLayer walls;
  walls.name = "WALLS";
  walls.occluder = true;
  plan.layers.push_back(walls);
  std::uniform_real_distribution<double> width(3.0, 7.0), unit(0.0, 1.0);
  std::uniform_int_distribution<int> rooms(2, 4);
  const int nx = rooms(*rng), ny = rooms(*rng);
  std::vector<double> xs{0.0}, ys{0.0};
  for (int i = 0; i < nx; ++i) xs.push_back(xs.back() + width(*rng));
  for (int j = 0; j < ny; ++j) ys.push_back(ys.back() + width(*rng) * 0.8);
  auto wall_with_door = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const double length = (b - a).norm();
    const double door = 0.3 + unit(*rng) * (length - 1.6);
    const Eigen::Vector2d dir = (b - a) / length;
    add_wall(&plan, a, a + dir * door);
    add_wall(&plan, a + dir * (door + 1.0), b);
  };
  add_wall(&plan, {xs.front(), ys.front()}, {xs.back(), ys.front()});
  add_wall(&plan, {xs.back(), ys.front()}, {xs.back(), ys.back()});
  add_wall(&plan, {xs.back(), ys.back()}, {xs.front(), ys.back()});
  add_wall(&plan, {xs.front(), ys.back()}, {xs.front(), ys.front()});
  for (int i = 1; i < nx; ++i)
    for (int j = 0; j < ny; ++j) wall_with_door({xs[i], ys[j]}, {xs[i], ys[j + 1]});
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) wall_with_door({xs[i], ys[j]}, {xs[i + 1], ys[j]});
  // A pillar in some rooms.
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      if (unit(*rng) < 0.5) continue;
      const Eigen::Vector2d c(xs[i] + (0.3 + 0.4 * unit(*rng)) * (xs[i + 1] - xs[i]),
                              ys[j] + (0.3 + 0.4 * unit(*rng)) * (ys[j + 1] - ys[j]));
      const double h = 0.2;
      const Eigen::Vector2d p[4] = {c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h),
                                    c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h)};
      for (int k = 0; k < 4; ++k) add_wall(&plan, p[k], p[(k + 1) % 4]);
    }
  return plan;
}

struct Scene {
  CameraPath path;
  std::unique_ptr<VisibilityIndex> index;
  VisibilityCells cells;
  PathEnvelopes envelopes;
};

Scene make_scene(const FloorPlan& plan, double step) {
  Scene scene;
  AutoWalkOptions walk;
  walk.step = step;
  scene.path = auto_walk(plan, walk);
  scene.index = std::make_unique<VisibilityIndex>(plan);
  scene.cells = scene.index->cells_along_path(scene.path);
  scene.envelopes = compute_path_envelopes(*scene.index, scene.path);
  return scene;
}

nlohmann::json loss_json(const GeometricLoss& loss) {
  return {{"mean", loss.mean},
          {"p95", loss.p95},
          {"max", loss.max},
          {"evaluated", loss.evaluated},
          {"inexact", loss.inexact}};
}

}  // namespace

int main(int argc, char** argv) {
  // --quick: 50x on the office sample only (for tuning).
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  nlohmann::json out;
  const auto t0 = Clock::now();
  const FloorPlan plan = make_office_sample_plan();
  const double step = 0.04;
  Scene office = make_scene(plan, step);
  out["ground_truth"] = {{"plan", "make_office_sample_plan"},  {"walk", "auto_walk, step 0.04 m"},
                         {"frames", office.path.size()},       {"length_m", office.path.length()},
                         {"cells", office.cells.cells.size()}, {"setup_s", seconds_since(t0)}};

  // Depth volumes from the renderer (no plan used by the depth sampler itself).
  const auto t_depth = Clock::now();
  const SyntheticScene synthetic = build_synthetic_scene(plan);
  RenderOptions render;
  render.width = 128;
  render.height = 64;
  std::vector<DepthVolume> volumes;
  PathEnvelopes depth_envelopes;  // eye level, from the depth maps alone
  RenderedPanorama panorama;
  for (const PathFrame& f : office.path.frames) {
    if (quick) break;
    render_panorama(synthetic, f, render, panorama);
    volumes.push_back(depth_volume(panorama.depth));
    depth_envelopes.frames.push_back(envelope_from_depth(panorama.depth, f));
  }
  out["ground_truth"]["depth_render_s"] = seconds_since(t_depth);

  SamplingInputs inputs;
  inputs.path = &office.path;
  inputs.index = office.index.get();
  inputs.cells = &office.cells;
  inputs.depth_volumes = &volumes;
  inputs.depth_envelopes = &depth_envelopes;
  inputs.envelopes = &office.envelopes;
  if (quick && argc > 3)
    inputs.visibility.refine_sweeps = std::atoi(argv[2]),
    inputs.visibility.raster_cell_m = std::atof(argv[3]);
  const EnvelopeRaster raster(office.envelopes, inputs.visibility.raster_cell_m);
  inputs.raster = &raster;

  struct Variant {
    std::string name;
    SamplingMethod method;
    VisibilityRule rule;
    double exponent;
    double boost;
  };
  std::vector<Variant> variants = {
      {"uniform", SamplingMethod::kUniform, VisibilityRule::expected_loss, 3.0, 1.0},
      {"visibility", SamplingMethod::kVisibility, VisibilityRule::expected_loss, 3.0, 1.0},
      {"visibility_density_only", SamplingMethod::kVisibility, VisibilityRule::expected_loss, 3.0, 1.0},
      {"visibility_cell_rule_e3", SamplingMethod::kVisibility, VisibilityRule::cell_rule, 3.0, 1.0},
      {"visibility_cell_rule_e3_no_boost", SamplingMethod::kVisibility, VisibilityRule::cell_rule, 3.0, 0.0},
      {"depth", SamplingMethod::kDepth, VisibilityRule::expected_loss, 1.0, 1.0},
      {"depth_cell_rule_only", SamplingMethod::kDepth, VisibilityRule::expected_loss, 1.0, 1.0},
      {"depth_cell_rule_only_e3", SamplingMethod::kDepth, VisibilityRule::expected_loss, 3.0, 1.0},
  };
  if (quick) variants.resize(variants.size() - 3);  // no depth
  std::map<std::string, double> mean_at_50;
  for (double ratio : quick ? std::vector<double>{50.0} : std::vector<double>{10.0, 50.0, 100.0}) {
    nlohmann::json at_ratio;
    for (const Variant& v : variants) {
      SamplingParameters p;
      p.method = v.method;
      p.rule = v.rule;
      p.ratio = ratio;
      p.exponent = v.exponent;
      p.transition_boost = v.boost;
      inputs.visibility.refine_by_loss = v.name != "visibility_density_only";
      inputs.depth.refine_by_loss = v.name.rfind("depth_cell_rule_only", 0) != 0;
      const auto t = Clock::now();
      const Keyframes k = sample_keyframes(inputs, p);
      const double sample_s = seconds_since(t);
      const GeometricLoss loss = geometric_loss(office.path, k, office.envelopes);
      nlohmann::json j = loss_json(loss);
      j["keyframes"] = k.indices.size();
      j["sample_s"] = sample_s;
      at_ratio[v.name] = j;
      if (ratio == 50.0) mean_at_50[v.name] = loss.mean;
    }
    out["reduction_" + std::to_string(static_cast<int>(ratio)) + "x"] = at_ratio;
  }
  out["visibility_over_uniform_mean_50x"] = mean_at_50["visibility"] / mean_at_50["uniform"];
  out["cell_rule_e3_over_uniform_mean_50x"] = mean_at_50["visibility_cell_rule_e3"] / mean_at_50["uniform"];
  out["depth_over_uniform_mean_50x"] = mean_at_50["depth"] / mean_at_50["uniform"];
  out["target_visibility_over_uniform"] = 0.8;

  // Progressive order: the prefixes of the 50x ranking (half, quarter, eighth of it) against sampling that
  // many keyframes directly, for each method.
  for (const Variant& v : variants) {
    SamplingParameters p;
    p.method = v.method;
    p.rule = v.rule;
    p.ratio = 50.0;
    p.exponent = v.exponent;
    p.transition_boost = v.boost;
    inputs.visibility.refine_by_loss = v.name != "visibility_density_only";
    inputs.depth.refine_by_loss = v.name.rfind("depth_cell_rule_only", 0) != 0;
    const Keyframes full = sample_keyframes(inputs, p);
    const std::vector<int> order = full.progressive_order();
    nlohmann::json j;
    for (int parts : {2, 4, 8}) {
      const int size = std::max(2, static_cast<int>(order.size()) / parts);
      Keyframes prefix;
      prefix.indices.assign(order.begin(), order.begin() + size);
      std::sort(prefix.indices.begin(), prefix.indices.end());
      p.count = size;
      const double direct = geometric_loss(office.path, sample_keyframes(inputs, p), office.envelopes).mean;
      const double from_prefix = geometric_loss(office.path, prefix, office.envelopes).mean;
      j[std::to_string(size)] = {{"prefix_mean", from_prefix}, {"direct_mean", direct}};
      p.count = 0;
      p.ratio = 50.0;
    }
    out["progressive_prefixes_of_50x"][v.name] = j;
  }

  if (quick) {
    std::cout << out.dump(1) << std::endl;
    return 0;
  }
  // Which exponent of the cell rule measures best: the office sample and random plans, 50x, boost 0 and 1.
  const std::vector<double> exponents = {0.0, 0.5, 1.0, 1.5, 2.0, 3.0};  // JSON keys "0.0" .. "3.0"
  auto sweep = [&](Scene& scene, nlohmann::json* into) {
    SamplingInputs in;
    in.path = &scene.path;
    in.index = scene.index.get();
    in.cells = &scene.cells;
    in.envelopes = &scene.envelopes;
    for (double boost : {0.0, 1.0})
      for (double e : exponents) {
        SamplingParameters p;
        p.method = SamplingMethod::kVisibility;
        p.rule = VisibilityRule::cell_rule;
        p.ratio = 50.0;
        p.exponent = e;
        p.transition_boost = boost;
        const double mean = geometric_loss(scene.path, sample_keyframes(in, p), scene.envelopes).mean;
        (*into)["boost_" + std::to_string(static_cast<int>(boost))][std::to_string(e).substr(0, 3)] = mean;
      }
    SamplingParameters p;
    p.ratio = 50.0;
    p.method = SamplingMethod::kUniform;
    (*into)["uniform"] = geometric_loss(scene.path, sample_keyframes(in, p), scene.envelopes).mean;
    p.method = SamplingMethod::kVisibility;
    p.rule = VisibilityRule::expected_loss;
    (*into)["expected_loss"] = geometric_loss(scene.path, sample_keyframes(in, p), scene.envelopes).mean;
  };
  nlohmann::json exponent_sweep;
  sweep(office, &exponent_sweep["office"]);
  std::mt19937 rng(2024);
  std::map<std::string, double> random_sum;
  const int random_plans = 5;
  for (int r = 0; r < random_plans; ++r) {
    Scene scene = make_scene(random_plan(&rng), 0.05);
    nlohmann::json j;
    sweep(scene, &j);
    j["frames"] = scene.path.size();
    exponent_sweep["random_" + std::to_string(r)] = j;
  }
  out["cell_rule_mean_loss_at_50x"] = exponent_sweep;
  // Summary: each setting's loss relative to uniform, averaged over the random plans, and the best exponent
  // on the sample and on the random plans.
  nlohmann::json summary;
  for (const std::string boost : {"boost_0", "boost_1"}) {
    std::string best_office, best_random;
    double best_office_value = 1e9, best_random_value = 1e9;
    for (auto& [e, office_value] : exponent_sweep["office"][boost].items()) {
      double relative = 0.0;
      for (int r = 0; r < random_plans; ++r) {
        const nlohmann::json& j = exponent_sweep["random_" + std::to_string(r)];
        relative += j[boost][e].get<double>() / j["uniform"].get<double>() / random_plans;
      }
      summary[boost]["random_mean_over_uniform"][e] = relative;
      const double office_relative =
          office_value.get<double>() / exponent_sweep["office"]["uniform"].get<double>();
      summary[boost]["office_over_uniform"][e] = office_relative;
      if (office_relative < best_office_value) best_office_value = office_relative, best_office = e;
      if (relative < best_random_value) best_random_value = relative, best_random = e;
    }
    summary[boost]["best_exponent_office"] = best_office;
    summary[boost]["best_exponent_random"] = best_random;
  }
  out["cell_rule_exponent_summary"] = summary;
  out["total_s"] = seconds_since(t0);
  std::cout << out.dump(1) << std::endl;
  return 0;
}
