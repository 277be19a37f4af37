#pragma once
// The synthetic surround camera: renders RGB + depth equirectangular panoramas of a FloorPlan extruded to
// 2.5-D (walls and pillars to the ceiling, furniture as low boxes, a floor and a ceiling), with exact depth.
// It is the project's test bench: every pose it renders is ground truth.
//
// Geometry (all metres, plan frame X right, Y up, Z up):
// - walls: every occluder segment (and every segment on a columns layer) is a double-sided vertical
//   rectangle from z = 0 to wall_height;
// - furniture: every closed outline on a furniture layer is a prism from z = 0 to its layer's height with a
//   flat top; its sides are its outline's edges;
// - floor z = 0 and ceiling z = wall_height cover the plan's extents grown by `floor_margin`; rays that
//   leave that rectangle without hitting anything have no hit (depth 0, sky colour);
// - people (RenderOptions::people) are vertical cylinders with a flat top.
// The panorama follows rig/spherical.h: centre column = heading, azimuth grows clockwise seen from above.
// Speed: one 2-D ray cast per panorama column (through a uniform grid over the faces) collects the faces the
// column can see, then every pixel of the column walks that short list with its own elevation; both passes
// run on OpenCV's thread pool. A tilted camera (RenderOptions' pitch and roll) intersects each pixel's own
// ray with the faces its two neighbouring columns collected. Texturing is most of the cost: the trilinear
// mip sampler runs on SSE2 lanes (exactly the scalar arithmetic), and a row's floor pixels share one log2.
// tests/bench/bench_render.cpp measures it: 67-74 ms of CPU per 2048x1024 RGB + depth frame on one thread
// (69af694, load 4 on 2 cores; 124-128 ms before, same run).
//
// What a real trolley capture has besides the scene (RenderOptions, all off by default): sensor noise,
// exposure drift and sudden auto-exposure steps, people walking, pitch and roll wobble from an uneven floor,
// the trolley (mast, frame, handle) and its operator in every frame; plain painted walls (SceneOptions).
// Where the code lives: synthetic_scene.cpp (building), ray_casting.cpp, surface_shading.cpp (texturing),
// scene_people.cpp, capture_nuisances.cpp (tilt, exposure, noise), trolley_rig.cpp (operator and trolley),
// panorama_render.cpp (the render loops), auto_walk.cpp, office_sample.cpp.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"

namespace plenopath {

// How walls and pillars look.
enum class WallFinish : std::uint8_t {
  kTextured = 0,  // plaster and concrete with marks at every scale (corners everywhere)
  kPlainPaint,    // one near-uniform paint with faint noise (a painted corridor: few corners)
};

struct SceneOptions {
  double wall_height = 2.8;    // metres; also the ceiling height
  double camera_height = 1.6;  // metres above the floor (the nodal point of the rig)
  // Layers to use; empty = every visible layer of the plan.
  std::vector<std::string> layers;
  // Closed outlines (and segments) on these layers become full-height pillars. Empty = guess: layer names
  // containing COL or PILLAR (any case).
  std::vector<std::string> column_layers;
  // Closed outlines on these layers become furniture boxes. Empty = guess: names containing FURN, DESK,
  // TABLE or EQUIP (any case).
  std::vector<std::string> furniture_layers;
  double furniture_height = 0.75;                         // metres, for furniture layers not listed below
  std::map<std::string, double> furniture_layer_heights;  // per-layer override, metres
  double floor_margin = 1.0;       // metres the floor and ceiling extend beyond the plan's extents
  std::uint32_t texture_seed = 1;  // every surface's texture is a deterministic function of this and its id
  int texture_size = 1024;         // texels per side of each procedural texture (power of two)
  double texels_per_metre = 256.0;
  bool use_grid = true;  // cast rays through a uniform grid over the faces (off = test every face)
  WallFinish wall_finish = WallFinish::kTextured;
  bool posters = true;  // framed posters on some of the longer walls

  void check() const;  // throws Error naming the bad field
};

// The kind of surface a ray hit (also used for shading and by tests).
enum class SurfaceKind : std::uint8_t {
  kNone = 0,
  kWall,
  kPillar,
  kFurnitureSide,
  kFurnitureTop,
  kFloor,
  kCeiling,
  kPerson,
  kOperator,  // the person pushing the trolley (RenderOptions::operator_person)
  kTrolley    // the trolley's mast, frame and handle (RenderOptions::trolley)
};

// One vertical face of the scene: a plan segment extruded from z = 0 to `top`.
struct SceneFace {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  double top = 0.0;  // metres
  SurfaceKind kind = SurfaceKind::kWall;
  int footprint = -1;       // index into SyntheticScene::footprints for furniture sides, -1 otherwise
  int material = 0;         // which procedural texture
  double u_offset = 0.0;    // texture offset along the face, metres (per-surface seed)
  cv::Vec3f tint{1, 1, 1};  // per-surface colour multiplier (BGR)
  float shade = 1.0f;       // diffuse lighting factor (ambient + a few directional lights)
  int poster_begin = 0, poster_end = 0;  // posters on this face: SyntheticScene::posters[begin, end)
};

// A closed outline with a flat top (furniture).
struct SceneFootprint {
  std::vector<Eigen::Vector2d> points;
  double top = 0.0;
  int material = 0;
  cv::Vec3f tint{1, 1, 1};
  Eigen::Vector2d texture_offset = Eigen::Vector2d::Zero();  // metres
};

// A framed poster on a wall face: a rectangle in the face's (u along a->b, z) coordinates.
struct ScenePoster {
  double u0 = 0, u1 = 0, z0 = 0, z1 = 0;  // metres
  int image = 0;                          // index into the scene's poster images
};

struct SceneTextures;  // procedural texture pyramids (internal)
struct SceneGrid;      // uniform grid over faces for 2-D ray casting (internal)

class SyntheticScene {
 public:
  SceneOptions options;
  std::vector<SceneFace> faces;
  std::vector<SceneFootprint> footprints;
  std::vector<ScenePoster> posters;
  Eigen::Vector2d floor_min = Eigen::Vector2d::Zero(),
                  floor_max = Eigen::Vector2d::Zero();  // floor rectangle
  std::shared_ptr<const SceneTextures> textures;
  std::shared_ptr<const SceneGrid> grid;
};

// Throws Error when the options are bad or the plan has nothing to render.
SyntheticScene build_synthetic_scene(const FloorPlan& plan, const SceneOptions& options = {});

struct RenderOptions {
  int width = 2048;   // equirectangular width, pixels (any size >= 8)
  int height = 1024;  // equirectangular height, pixels
  bool depth = true;  // also fill RenderedPanorama::depth
  int threads = 0;    // 1 = only the calling thread; otherwise OpenCV's thread pool (all cores)
  // Realism switches, all off by default.
  double noise_sigma = 0.0;  // Gaussian sensor noise, in 8-bit grey levels; seeded by noise_seed and frame
  std::uint32_t noise_seed = 7;
  double exposure_drift = 0.0;  // relative amplitude of a slow gain drift over frames (e.g. 0.15)
  double exposure_period_frames = 240.0;
  int people = 0;  // moving people (textured cylinders)
  std::uint32_t people_seed = 11;
  double frame_rate = 30.0;  // frames per second: a frame's time is index / frame_rate (people move)
  int jpeg_quality = 92;     // used by writers of the frames (rig/ itself encodes nothing)
  // Auto-exposure steps: the gain jumps to a new level (exp(u * exposure_jump), u uniform in [-1, 1]) at
  // jittered frames, on average every exposure_jump_frames frames, on top of the slow drift. 0 = none.
  double exposure_jump = 0.0;
  double exposure_jump_frames = 60.0;
  std::uint32_t exposure_seed = 13;
  // Pitch and roll of the camera (an uneven floor rocks the trolley), a deterministic function of the frame
  // index: a smooth random walk (standard deviation tilt_wobble_deg per axis, changing over about
  // tilt_wobble_frames frames), plus bumps (a jolt of up to bump_deg that rings down over a few frames, on
  // average bumps_per_100_frames of them), plus a constant pitch_deg / roll_deg. The heading (the
  // horizontal direction of the centre column) and the position are the pose's: tilt never changes them.
  double tilt_wobble_deg = 0.0;
  double tilt_wobble_frames = 20.0;
  double bump_deg = 0.0;
  double bumps_per_100_frames = 3.0;
  double pitch_deg = 0.0;  // > 0: the forward direction (centre column) points up
  double roll_deg = 0.0;   // > 0: the camera's left (azimuth -90) side up, its right side down
  std::uint32_t tilt_seed = 5;
  // The camera's height rides up and down (a hand-held camera, a monopod carried along), a deterministic
  // function of the frame index: a smooth random walk of standard deviation height_wobble_m changing over
  // about height_wobble_frames frames, added to SceneOptions::camera_height. A trolley or tripod keeps 0.
  double height_wobble_m = 0.0;
  double height_wobble_frames = 40.0;
  // The trolley in every frame: a mast under the lens, a base frame near the floor with a box on it, and
  // a push handle behind the camera, all rigid with the camera (they tilt with it).
  bool trolley = false;
  // The operator in every frame: a person standing operator_distance_m behind the lens, hands on the
  // handle, upright (level) and turning with the camera's heading.
  bool operator_person = false;
  double operator_distance_m = 0.7;

  void check() const;  // throws Error naming the bad field
};

// The camera's tilt at a frame (RenderOptions' wobble, bumps and constant pitch/roll), radians.
struct CameraTilt {
  double pitch = 0.0;  // rotation about the camera's left axis (+y): > 0 raises the forward direction
  double roll = 0.0;   // rotation about the forward axis (+x): > 0 raises the left side
  bool any() const { return pitch != 0.0 || roll != 0.0; }
};
CameraTilt camera_tilt_at_frame(const RenderOptions& options, int frame_index);
// The camera's height above SceneOptions::camera_height at a frame (RenderOptions::height_wobble_m), metres.
double camera_height_offset_at_frame(const RenderOptions& options, int frame_index);
// world_from_camera = Rz(heading) * Ry(-pitch) * Rx(roll): camera-frame bearings (rig/spherical.h) to the
// plan frame. With no tilt it is world_from_camera_rotation(heading).
Eigen::Matrix3d world_from_tilted_camera(double heading, const CameraTilt& tilt);
// The exposure gain at a frame (drift times steps); 1 when both are off.
double exposure_gain_at_frame(const RenderOptions& options, int frame_index);

struct RenderedPanorama {
  cv::Mat rgb;    // CV_8UC3, BGR
  cv::Mat depth;  // CV_32F, metres along the ray, 0 = no hit (empty when RenderOptions::depth is false)
};

// Renders the panorama seen from (pose.x, pose.y, camera_height + camera_height_offset_at_frame(options,
// pose.index)) with heading pose.heading, tilted by camera_tilt_at_frame(options, pose.index). The result is
// a deterministic function of the scene, the pose (including pose.index, which times people, noise, exposure
// and tilt) and the options; thread count does not change it. Depth includes the trolley and the operator
// when they are on.
RenderedPanorama render_panorama(const SyntheticScene& scene, const PathFrame& pose,
                                 const RenderOptions& options);
// Same, reusing `out`'s buffers when their size fits (saves page faults when rendering many frames).
void render_panorama(const SyntheticScene& scene, const PathFrame& pose, const RenderOptions& options,
                     RenderedPanorama& out);

// One ray, for rigs and tests: origin and direction in the plan frame (direction need not be unit).
struct RayHit {
  double distance = 0.0;  // metres along the unit ray, 0 = no hit
  SurfaceKind kind = SurfaceKind::kNone;
  cv::Vec3b bgr{0, 0, 0};
};
// Casts one ray; `frame_index` places the people (as for a pose with that index). The scene only: no
// trolley or operator (they need a camera pose), no exposure gain.
RayHit trace_ray(const SyntheticScene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 const RenderOptions& options, int frame_index = 0);

// Renders an image whose pixel (u, v) looks from `origin` along directions(v, u) (CV_64FC3, plan frame, need
// not be unit): pinhole heads, cube faces. `pixel_angle` (radians) is the angular size of a pixel, for
// texture filtering. Depth is the distance along the ray (0 = no hit). The scene only (as trace_ray), with
// the exposure gain and noise of `frame_index`; the directions carry any tilt.
RenderedPanorama render_directions(const SyntheticScene& scene, const Eigen::Vector3d& origin,
                                   const cv::Mat& directions, double pixel_angle,
                                   const RenderOptions& options, int frame_index = 0);

// Where the people are at a frame (centre, radius, height), for tests and overlays.
struct PersonPose {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.25;
  double height = 1.75;
  int id = 0;
};
std::vector<PersonPose> people_at_frame(const SyntheticScene& scene, const RenderOptions& options,
                                        int frame_index);

// ---- automatic walk
struct AutoWalkOptions {
  double step = 0.08;               // metres between frames on average
  double step_wobble = 0.25;        // relative variation of the step (a hand-pushed trolley)
  double heading_wobble_deg = 2.0;  // amplitude of the heading wobble around the path tangent
  double clearance = 0.33;          // metres kept from walls and furniture (less than half a doorway)
  double room_spacing = 2.5;        // metres between waypoints (about one per room)
  int max_frames = 0;               // 0 = the whole walk
  std::uint32_t seed = 3;
  std::string frame_pattern = "frames/%06d.jpg";  // PathFrame::file of each frame (empty = none)
  SceneOptions scene;  // which layers block the trolley (walls, pillars, furniture)

  void check() const;  // throws Error naming the bad field
};
// A smooth walk visiting every reachable room of the plan through its doorways. Throws Error when the plan
// has no free space big enough for the trolley.
CameraPath auto_walk(const FloorPlan& plan, const AutoWalkOptions& options = {});

// ---- the sample plan
// The office sample (about 25 m x 15 m: rooms, a corridor, doorways with swing arcs, pillars, furniture,
// labels), built in code so tests need no DXF importer. See rig/office_sample.h for its CAD primitives.
FloorPlan make_office_sample_plan();

}  // namespace plenopath
