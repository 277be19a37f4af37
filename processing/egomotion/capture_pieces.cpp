// Where the images of a capture stop connecting (EgomotionTracker::finish(), before the geometry). Frames
// are connected by KLT tracks continuing from one to the next. Where they stop (the camera through a wall,
// a recording stopped and restarted elsewhere, a dark stretch, a blur), the two sides are tried hard before
// the capture is declared broken (a ring image registers with anything, so it connects nothing): the
// described frames nearest both sides are matched by descriptors (wide baseline, no turn prior) and
// verified by two-view geometry — a verified match joins the sides, and the global refinement ties the
// matched points. Only when nothing connects does a new piece start.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "processing/egomotion/egomotion_steps.h"

namespace plenopath::egomotion_steps {
namespace {

struct Segment {
  int first = 0, last = 0;
};

}  // namespace

CapturePieces find_capture_pieces(const std::vector<FrameTrackStats>& stats, const TrackerMeasurements& m,
                                  std::mt19937& rng) {
  const EgomotionOptions& opt = *m.options;
  const PieceOptions& po = opt.pieces;
  const int n = static_cast<int>(stats.size());
  CapturePieces out;
  if (n == 0) return out;
  // Runs of frames each connected to the one before by enough tracks.
  std::vector<Segment> segments;
  int start = 0;
  for (int f = 1; f < n; ++f) {
    if (stats[f].tracked >= po.min_link_tracks) continue;
    segments.push_back({start, f - 1});
    start = f;
  }
  segments.push_back({start, n - 1});
  // Only runs long enough, and not all textureless, can stand as pieces; the frames of the others go with
  // the piece around them (bridged).
  std::vector<Segment> solid;
  for (const Segment& s : segments) {
    if (s.last - s.first + 1 < po.min_piece_frames) continue;
    int textured = 0;
    for (int f = s.first; f <= s.last; ++f) textured += !m.textureless[f];
    if (textured >= po.min_piece_frames) solid.push_back(s);
  }
  out.pieces.push_back({0, n - 1, ""});
  if (solid.size() < 2) return out;

  // Described frames by frame index.
  auto described_at = [&](int f) {
    const int i = m.described->find(f);
    return i >= 0 && m.described->has_descriptors(i);
  };
  auto load = [&](int f) { return m.described->load(m.described->find(f)); };
  auto bearing = [&](int t, int frame) { return m.view->bearing(t, frame); };

  for (std::size_t k = 1; k < solid.size(); ++k) {
    const int a = solid[k - 1].last, b = solid[k].first;
    // Descriptor matches between the frames nearest both sides, nearest pairs first.
    std::vector<int> before, after;
    for (int f = a; f >= std::max(solid[k - 1].first, a - po.join_search_frames); --f)
      if (described_at(f)) before.push_back(f);
    for (int f = b; f <= std::min(solid[k].last, b + po.join_search_frames); ++f)
      if (described_at(f)) after.push_back(f);
    std::vector<std::pair<int, int>> pairs;
    for (int fa : before)
      for (int fb : after) pairs.emplace_back(fa, fb);
    std::stable_sort(pairs.begin(), pairs.end(), [&](const auto& l, const auto& r) {
      return (a - l.first) + (l.second - b) < (a - r.first) + (r.second - b);
    });
    if (static_cast<int>(pairs.size()) > po.join_max_pairs)
      pairs.resize(static_cast<std::size_t>(po.join_max_pairs));
    // Each pair verified on its own; a join needs two pairs that agree: the turn across the stretch seen from
    // one pair, carried to the other by the tracked turns on each side, must match the other's.
    std::vector<CaptureJoin> verified;
    bool joined = false;
    for (const auto& [fa, fb] : pairs) {
      LoopMatch match;
      double direction = std::numeric_limits<double>::quiet_NaN();
      if (!verify_frame_match(load(fa), load(fb), bearing, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity(), po.join_min_inliers, opt.loop.ratio,
                              m.two_view, rng, &match, &direction)) {
        continue;
      }
      CaptureJoin join{fa, fb, match.turn, direction, std::move(match.track_pairs)};
      for (const CaptureJoin& other : verified) {
        const double carried = other.turn + (m.heading[fb] - m.heading[other.frame_b]) -
                               (m.heading[fa] - m.heading[other.frame_a]);
        if (std::abs(std::remainder(carried - join.turn, 2 * M_PI)) > po.join_agreement_deg * M_PI / 180.0)
          continue;
        // The pair nearer the stretch is the join; the other's matches tie points too.
        CaptureJoin best = other.frame_b - other.frame_a <= join.frame_b - join.frame_a ? other : join;
        out.joins.push_back(std::move(best));
        joined = true;
        break;
      }
      if (joined) break;
      verified.push_back(std::move(join));
    }
    if (joined) continue;
    // Nothing connects: the piece before ends where the next solid run starts.
    std::ostringstream why;
    why << "no image connects frame " << b << " to frame " << a << ": ";
    if (b - a - 1 > 0)
      why << b - a - 1 << " frame" << (b - a - 1 == 1 ? "" : "s") << " between without enough tracks";
    else
      why << "fewer than " << po.min_link_tracks << " tracks continue";
    why << "; descriptor matching of " << pairs.size() << " frame pair" << (pairs.size() == 1 ? "" : "s")
        << " across found no verified match";
    out.pieces.back().last = b - 1;
    out.pieces.push_back({b, n - 1, why.str()});
  }
  return out;
}

}  // namespace plenopath::egomotion_steps
