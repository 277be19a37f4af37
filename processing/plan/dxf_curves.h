#pragma once
// The curves DXF entities are made of, kept exact until the units (and so the chord tolerance in drawing
// units) are known, then turned into chords. Points are 3-D in the entity's own coordinate system;
// `to_parent` maps them to the coordinate system of the block (or model space) that holds the entity.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace plenopath {

struct DxfCurve {
  enum class Kind { polyline, arc, ellipse, spline, path };
  Kind kind = Kind::polyline;
  bool closed = false;
  bool whole = true;  // kept as an outline (everything but LINE)

  // polyline: vertices; bulge[i] bends the span from vertex i to i + 1 (tan of a quarter of its angle);
  // widths[i] (start, end) of that span when the polyline is drawn wide (empty = no width).
  std::vector<Eigen::Vector3d> points;
  std::vector<double> bulges;
  std::vector<Eigen::Vector2d> widths;

  // arc: centre, radius, start angle and signed sweep (radians, counter-clockwise positive)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double start = 0.0;
  double sweep = 0.0;

  // ellipse: centre (above), point = centre + cos(t) major + sin(t) minor, t from `start` by `sweep`
  Eigen::Vector3d major = Eigen::Vector3d::Zero();
  Eigen::Vector3d minor = Eigen::Vector3d::Zero();

  // spline: homogeneous control points (x w, y w, z w, w), knot vector, degree
  std::vector<Eigen::Vector4d> control;
  std::vector<double> knots;
  int degree = 3;

  // path: pieces joined end to end (a HATCH boundary made of edges), in this curve's coordinates
  std::vector<DxfCurve> pieces;

  Eigen::Affine3d to_parent = Eigen::Affine3d::Identity();
};

// The curve as chords no further than `tolerance` from it (in the units of `world_from_curve`'s output),
// mapped by `world_from_curve` and flattened onto XY. A closed curve does not repeat its first point.
// A wide polyline comes back as its outline (closed). `arcs` counts curved pieces tessellated.
std::vector<Eigen::Vector2d> tessellate(const DxfCurve& curve, const Eigen::Affine3d& world_from_curve,
                                        double tolerance, bool* closed, int* arcs);

// The arbitrary axis algorithm of the DXF reference: the object coordinate system of extrusion `normal`.
Eigen::Affine3d world_from_ocs(const Eigen::Vector3d& normal);

}  // namespace plenopath
