// The trolley and its operator, in every frame of a trolley capture: simple solids (capsules and boxes)
// fixed to the camera (the trolley tilts with it) or to its level, heading-aligned frame (the operator
// stands upright behind it). Their look is fixed in their own frame (texture and lighting), so they cover
// the same pixels with the same colours in every frame, up to the tilt (the operator) and the exposure.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath::render_detail {
namespace {

RigSolid capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r, bool level, SurfaceKind kind,
                 cv::Vec3f colour, int material = -1) {
  RigSolid s;
  s.shape = RigSolid::kCapsule;
  s.a = a;
  s.b = b;
  s.radius = r;
  s.level = level;
  s.kind = kind;
  s.colour = colour;
  s.material = material;
  s.centre = 0.5 * (a + b);
  s.bound = 0.5 * (b - a).norm() + r;
  return s;
}

RigSolid box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, bool level, SurfaceKind kind,
             cv::Vec3f colour, int material = -1) {
  RigSolid s;
  s.shape = RigSolid::kBox;
  s.a = lo;
  s.b = hi;
  s.level = level;
  s.kind = kind;
  s.colour = colour;
  s.material = material;
  s.centre = 0.5 * (lo + hi);
  s.bound = 0.5 * (hi - lo).norm();
  return s;
}

struct SolidHit {
  double t = -1.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double u = 0.0, v = 0.0;  // texture coordinates on the surface, metres
};

// Ray from the origin along the unit d.
SolidHit intersect(const RigSolid& s, const Eigen::Vector3d& d) {
  SolidHit hit;
  const double along = s.centre.dot(d);
  if (along < -s.bound || s.centre.squaredNorm() - along * along > s.bound * s.bound) return hit;
  if (s.shape == RigSolid::kBox) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0.0) {
        if (0.0 < s.a[k] || 0.0 > s.b[k]) return hit;
        continue;
      }
      double ta = s.a[k] / d[k], tb = s.b[k] / d[k];
      if (ta > tb) std::swap(ta, tb);
      if (ta > t0) {
        t0 = ta;
        axis = k;
      }
      t1 = std::min(t1, tb);
      if (t0 > t1) return hit;
    }
    if (axis < 0) return hit;  // the origin is inside (never, by construction)
    hit.t = t0;
    hit.normal = Eigen::Vector3d::Zero();
    hit.normal[axis] = d[axis] > 0 ? -1.0 : 1.0;
    const Eigen::Vector3d p = t0 * d - s.a;
    hit.u = p[(axis + 1) % 3];
    hit.v = p[(axis + 2) % 3];
    return hit;
  }
  // Capsule (Inigo Quilez's formulation), a sphere when a == b.
  const Eigen::Vector3d ba = s.b - s.a, oa = -s.a;
  const double baba = ba.dot(ba), r = s.radius;
  auto sphere = [&](const Eigen::Vector3d& centre) {
    const Eigen::Vector3d oc = -centre;
    const double b = d.dot(oc), c = oc.dot(oc) - r * r, h = b * b - c;
    return h > 0 ? -b - std::sqrt(h) : -1.0;
  };
  double t = -1.0;
  if (baba < 1e-12) {
    t = sphere(s.a);
  } else {
    const double bard = ba.dot(d), baoa = ba.dot(oa), rdoa = d.dot(oa), oaoa = oa.dot(oa);
    const double qa = baba - bard * bard, qb = baba * rdoa - baoa * bard,
                 qc = baba * oaoa - baoa * baoa - r * r * baba;
    const double h = qb * qb - qa * qc;
    if (h >= 0 && qa > 1e-15) {
      const double tc = (-qb - std::sqrt(h)) / qa;
      const double y = baoa + tc * bard;
      if (y > 0 && y < baba)
        t = tc;
      else
        t = sphere(y <= 0 ? s.a : s.b);
    } else if (h >= 0) {  // ray parallel to the axis: only the caps
      const double ta = sphere(s.a), tb = sphere(s.b);
      t = ta > 0 && (tb <= 0 || ta < tb) ? ta : tb;
    }
  }
  if (!(t > 0)) return hit;
  hit.t = t;
  const Eigen::Vector3d p = t * d;
  const double along_axis = baba > 1e-12 ? std::clamp((p - s.a).dot(ba) / baba, 0.0, 1.0) : 0.0;
  const Eigen::Vector3d q = s.a + along_axis * ba;
  hit.normal = (p - q).normalized();
  // Around the axis: an angle measured from a fixed perpendicular.
  const Eigen::Vector3d axis =
      baba > 1e-12 ? Eigen::Vector3d(ba / std::sqrt(baba)) : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d e1 =
      (std::abs(axis.z()) < 0.9 ? axis.cross(Eigen::Vector3d::UnitZ()) : axis.cross(Eigen::Vector3d::UnitX()))
          .normalized();
  const Eigen::Vector3d e2 = axis.cross(e1);
  hit.u = std::atan2(hit.normal.dot(e2), hit.normal.dot(e1)) * r;
  hit.v = baba > 1e-12 ? along_axis * std::sqrt(baba)
                       : std::acos(std::clamp(hit.normal.dot(axis), -1.0, 1.0)) * r;
  return hit;
}

}  // namespace

std::vector<RigSolid> rig_solids(const RenderOptions& o, double h) {
  std::vector<RigSolid> out;
  using V = Eigen::Vector3d;
  constexpr auto kT = SurfaceKind::kTrolley;
  constexpr auto kO = SurfaceKind::kOperator;
  if (o.trolley) {
    const cv::Vec3f metal(72, 74, 78), dark(32, 32, 36), rubber(24, 24, 26);
    out.push_back(capsule(V(0, 0, -0.08), V(0, 0, -(h - 0.18)), 0.02, false, kT, metal));    // mast
    out.push_back(box(V(-0.035, -0.035, -0.095), V(0.035, 0.035, -0.05), false, kT, dark));  // camera mount
    out.push_back(box(V(-0.045, 0.03, -0.40), V(0.045, 0.11, -0.25), false, kT, dark));      // recorder
    out.push_back(box(V(-0.32, -0.24, -h + 0.13), V(0.28, 0.24, -h + 0.17), false, kT,
                      cv::Vec3f(0.45f, 0.45f, 0.5f),
                      kMaterialFurnitureSide));  // base plate
    out.push_back(box(V(-0.20, -0.16, -h + 0.17), V(0.05, 0.14, -h + 0.42), false, kT,
                      cv::Vec3f(0.8f, 0.7f, 0.6f),
                      kMaterialFurnitureTop));  // a case on the base
    for (double y : {-0.22, 0.22})
      out.push_back(
          capsule(V(-0.30, y, -h + 0.17), V(-0.46, y, -h + 1.0), 0.016, false, kT, metal));  // uprights
    out.push_back(
        capsule(V(-0.46, -0.25, -h + 1.0), V(-0.46, 0.25, -h + 1.0), 0.018, false, kT, rubber));  // bar
    for (double x : {-0.26, 0.22})
      for (double y : {-0.23, 0.23})
        out.push_back(
            capsule(V(x, y - 0.015, -h + 0.065), V(x, y + 0.015, -h + 0.065), 0.065, false, kT, rubber));
  }
  if (o.operator_person) {
    const double d = o.operator_distance_m;
    const cv::Vec3f trousers(0.45f, 0.35f, 0.3f), shirt(0.95f, 0.55f, 0.35f), skin(110, 140, 190),
        shoes(30, 30, 34);
    const double hand_x = -0.47;
    for (double y : {-0.1, 0.1}) {
      out.push_back(
          capsule(V(-d, y, -h + 0.1), V(-d, y, -h + 0.86), 0.075, true, kO, trousers, kMaterialCloth));
      out.push_back(box(V(-d - 0.06, y - 0.05, -h), V(-d + 0.15, y + 0.05, -h + 0.09), true, kO, shoes));
    }
    out.push_back(capsule(V(-d, 0, -h + 1.0), V(-d, 0, -h + 1.33), 0.19, true, kO, shirt, kMaterialCloth));
    out.push_back(capsule(V(-d, 0, -h + 1.62), V(-d, 0, -h + 1.62), 0.11, true, kO, skin));  // head
    for (double y : {-0.21, 0.21}) {
      out.push_back(capsule(V(-d + 0.03, y, -h + 1.36), V(hand_x - 0.01, y, -h + 1.02), 0.045, true, kO,
                            shirt, kMaterialCloth));
      out.push_back(capsule(V(hand_x, y, -h + 1.0), V(hand_x, y, -h + 1.0), 0.045, true, kO, skin));  // hand
    }
  }
  return out;
}

RigHit hit_rig(const std::vector<RigSolid>& solids, const SceneTextures& textures,
               const Eigen::Vector3d& b_camera, const Eigen::Vector3d& b_level, double pixel_angle) {
  RigHit best;
  const RigSolid* nearest = nullptr;
  SolidHit nearest_hit;
  for (const RigSolid& s : solids) {
    const SolidHit h = intersect(s, s.level ? b_level : b_camera);
    if (h.t > 0 && (!nearest || h.t < nearest_hit.t)) {
      nearest = &s;
      nearest_hit = h;
    }
  }
  if (!nearest) return best;
  best.distance = nearest_hit.t;
  best.kind = nearest->kind;
  // Light from above and a little to the front, fixed in the solid's own frame.
  const Eigen::Vector3d light = Eigen::Vector3d(0.35, 0.25, 0.9).normalized();
  const float lit = static_cast<float>(0.5 + 0.5 * std::max(0.0, nearest_hit.normal.dot(light)));
  cv::Vec3f colour = nearest->colour;
  if (nearest->material >= 0) {
    const double tpm = textures.texels_per_metre;
    const double footprint = std::max(1e-3, nearest_hit.t * pixel_angle * tpm);
    colour = sample_texture(textures.materials[nearest->material], nearest_hit.u * tpm, nearest_hit.v * tpm,
                            footprint, true)
                 .mul(nearest->colour);
  }
  best.colour = colour * lit;
  return best;
}

}  // namespace plenopath::render_detail
