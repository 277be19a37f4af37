// Step 1b of EgomotionTracker::finish(): frame-to-frame turns from the KLT tracks. The rings are coarse
// indoors (parallax of near walls biases them by degrees, and they drift); the tracks between consecutive
// frames give each turn to a few hundredths of a degree: the median azimuth change (exact for a turn on the
// spot), refined by planar two-view geometry when the frames moved enough. Frames without enough tracks keep
// the ring's turn.
#include <Eigen/Dense>
#include <cmath>

#include "processing/egomotion/egomotion_steps.h"
#include "processing/egomotion/planar_two_view.h"
#include "processing/util/statistics.h"

namespace plenopath::egomotion_steps {
namespace {
constexpr double kLongStepParallax = 0.04;  // radians of median parallax (~2.3 deg): a long step
// A track moving less than this many pixels is still; the others' median turn this many times that: a turn
// no scene point stays still through (but within 12 deg of the zenith or nadir).
constexpr double kStillPixels = 3.0;
constexpr double kStillTurnFactor = 5.0;
constexpr double kStillShare = 0.1;  // ... and the still tracks are at least this share of them
}  // namespace

void measure_frame_turns(const std::vector<double>& ring_headings, std::mt19937& rng,
                         TrackerMeasurements* m) {
  const TrackView& view = *m->view;
  const int n = view.frame_count();
  m->heading.assign(n, 0.0);
  // Per frame: the share of the tracks continued from the previous frame that move against the static
  // scene (off the epipolar geometry of the step, or of a pure turn when the step has no parallax); -1 when
  // the step could not be solved. Tracks on people walking by, a passing door or the operator: the
  // refinement rejects them, but a frame where they are many is worth flagging.
  m->moving_share.assign(n, -1.0);
  PlanarTwoViewOptions step_options = m->two_view;
  step_options.iterations = 32;
  // A scanned turn replaces the tracks' median only when clearly better: where few tracks fit any turn (a
  // shaking camera, 15 of 52), one or two more would move it by a degree or more (POV-Ray corner, 1.5 deg).
  step_options.turn_scan_margin = 1.3;
  const double max_disagreement = m->options->max_step_turn_disagreement_deg * M_PI / 180.0;
  for (int f = 1; f < n; ++f) {
    const double ring_turn = ring_headings[f] - ring_headings[f - 1];
    // Tracks that stay put in the image while the others turn are on what the camera carries along (the
    // trolley, the operator, where the static mask missed them); a scene point cannot stay put in a turn.
    // Left in, they pull the median turn towards none (POV-Ray `people` every 2nd frame, 19 deg a frame
    // round a corner: a third of the tracks, turns 15 instead of 18 deg).
    const double still = kStillPixels * m->pixel_angle;
    std::vector<double> moving_turns;
    int continued = 0;
    for (int t : view.frame_tracks(f)) {
      if (!view.seen(t, f - 1)) continue;
      ++continued;
      const Eigen::Vector3d a = view.bearing(t, f - 1), b = view.bearing(t, f);
      if (std::atan2(a.cross(b).norm(), a.dot(b)) >= still)
        moving_turns.push_back(std::remainder(std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x()), 2 * M_PI));
    }
    // (A few still tracks right above or below the camera are the scene's: only a rig's many are left out.)
    const bool skip_still = m->options->turns_ignore_still_tracks &&
                            static_cast<int>(moving_turns.size()) >= m->two_view.min_inliers &&
                            continued - static_cast<int>(moving_turns.size()) >= kStillShare * continued &&
                            std::abs(median(moving_turns)) > kStillTurnFactor * still;
    std::vector<Eigen::Vector3d> ba, bb;
    std::vector<double> azimuth_change;
    for (int t : view.frame_tracks(f)) {
      if (!view.seen(t, f - 1)) continue;
      const Eigen::Vector3d a = view.bearing(t, f - 1), b = view.bearing(t, f);
      if (skip_still && std::atan2(a.cross(b).norm(), a.dot(b)) < still) continue;
      azimuth_change.push_back(std::remainder(std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x()), 2 * M_PI));
      // A spread subset is plenty for the two-view turn (tracks are in detection order, i.e. spread).
      if (ba.size() < 240 && (azimuth_change.size() % 2 == 1 || view.frame_tracks(f).size() < 480)) {
        ba.push_back(a);
        bb.push_back(b);
      }
    }
    double turn = ring_turn;
    if (static_cast<int>(azimuth_change.size()) >= m->two_view.min_inliers) {
      turn = median(azimuth_change);
      const PlanarRelativePose rel = estimate_planar_relative_pose(ba, bb, turn, step_options, rng);
      // The median azimuth change is the turn only while the step is short against the scene; across a
      // long step (frames dropped, subsampled video) parallax biases it by degrees, and the two-view turn
      // (scanned around the median) is the better one even when few tracks fit it: turning a corner at 26 cm
      // steps on plain walls with a tilting camera, 16 of 100 tracks, the median 16 deg for a 22 deg turn
      // (bench_nuisances corridor_like).
      const bool long_step = rel.median_parallax > kLongStepParallax;
      const bool solved = rel.valid && (std::abs(rel.turn - turn) < max_disagreement || long_step);
      if (solved) turn = rel.turn;
      if (solved || rel.median_parallax < m->two_view.min_parallax) {
        int moving = 0, total = 0;
        for (int t : view.frame_tracks(f)) {
          if (!view.seen(t, f - 1)) continue;
          const Eigen::Vector3d a = view.bearing(t, f - 1), b = view.bearing(t, f);
          const Eigen::Vector3d turned = rotate_z(a, -turn);
          const double error = solved ? std::abs(planar_epipolar_error(a, b, rel.turn, rel.direction))
                                      : std::atan2(turned.cross(b).norm(), turned.dot(b));
          moving += error > 3.0 * m->two_view.threshold;
          ++total;
        }
        m->moving_share[f] = double(moving) / total;
      }
    }
    m->heading[f] = m->heading[f - 1] + turn;
  }
}

}  // namespace plenopath::egomotion_steps
