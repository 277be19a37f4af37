#include "processing/stills/candidate_fit.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "model/error.h"

namespace plenopath {

void CandidateFitOptions::check() const {
  fit.check();
  if (max_stills_per_piece < 1) throw Error("CandidateFitOptions.max_stills_per_piece must be >= 1");
  if (max_candidates < 1) throw Error("CandidateFitOptions.max_candidates must be >= 1");
  if (!(max_fit_px > 0)) throw Error("CandidateFitOptions.max_fit_px must be > 0");
}

CandidateFitReport rerank_by_still_fit(RegistrationResult* result, const CameraPath& path,
                                       const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                       const CandidateFitOptions& options, Progress& progress) {
  options.check();
  CandidateFitReport report;
  report.fits_px.resize(result->pieces.size());
  for (std::size_t k = 0; k < result->pieces.size(); ++k) {
    PieceRegistration& piece = result->pieces[k];
    if (!piece.ok || piece.candidates.empty()) continue;
    progress.checkpoint(static_cast<double>(k) / result->pieces.size(),
                        "checking piece " + std::to_string(k + 1) + "'s placements against its stills");
    std::vector<const PathFrame*> frames;
    for (const PathFrame& f : path.frames)
      if (f.piece == piece.piece) frames.push_back(&f);
    if (frames.empty()) continue;
    const int use = std::min<int>(options.max_stills_per_piece, static_cast<int>(frames.size()));
    const int scored = std::min<int>(options.max_candidates, static_cast<int>(piece.candidates.size()));
    std::vector<double> fit(static_cast<std::size_t>(scored), 0.0);
    for (int s = 0; s < use; ++s) {
      const PathFrame& f = *frames[static_cast<std::size_t>(s * static_cast<int>(frames.size()) / use)];
      std::vector<Eigen::Vector3d> poses;
      for (int c = 0; c < scored; ++c) {
        const Similarity2& t = piece.candidates[static_cast<std::size_t>(c)].transform;
        const Eigen::Vector2d p = t.apply(f.position());
        poses.emplace_back(p.x(), p.y(), (f.heading + t.rotation) * 180.0 / M_PI);
      }
      const std::vector<double> fits = still_fits_px(read(f.index), plan, poses, options.fit);
      for (int c = 0; c < scored; ++c)
        fit[static_cast<std::size_t>(c)] += fits[static_cast<std::size_t>(c)] / use;
    }
    report.fits_px[k] = fit;
    ++report.pieces_scored;
    const double best_fit = *std::min_element(fit.begin(), fit.end());
    if (!(best_fit <= options.max_fit_px)) {
      char why[200];
      std::snprintf(
          why, sizeof why,
          "its points fit the plan, but what its stills see does not (best fit %.2f px, at most %.2f)",
          best_fit, options.max_fit_px);
      piece.ok = false;
      piece.message = why;
      ++report.pieces_refused;
      continue;
    }
    std::vector<int> order(static_cast<std::size_t>(scored));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return fit[a] < fit[b]; });
    if (order.front() == 0) continue;
    std::vector<RegistrationCandidate> reordered;
    for (int c : order) reordered.push_back(piece.candidates[static_cast<std::size_t>(c)]);
    for (std::size_t c = static_cast<std::size_t>(scored); c < piece.candidates.size(); ++c)
      reordered.push_back(piece.candidates[c]);
    piece.candidates = std::move(reordered);
    std::vector<double> fit_sorted;
    for (int c : order) fit_sorted.push_back(fit[static_cast<std::size_t>(c)]);
    report.fits_px[k] = fit_sorted;
    ++report.pieces_reordered;
    char note[160];
    std::snprintf(note, sizeof note, "chosen by what the stills see (fit %.2f px against %.2f px)",
                  fit_sorted.front(), fit[0]);
    piece.message += (piece.message.empty() ? "" : "; ") + std::string(note);
  }
  progress.report(1.0);
  return report;
}

}  // namespace plenopath
