#pragma once
// The per-frame curves of the timeline: the envelope area at each path position (from the visibility index
// of the current plan) and the depth volume of each frame's depth map (processing/sampling/depth_volume.h).
// Computed off the GUI thread whenever the path, the plan's index or the capture changes; a newer request
// makes an older run stop early and its result is dropped.
#include <QFutureWatcher>
#include <QObject>
#include <QVector>
#include <atomic>
#include <memory>

namespace plenopath::widgets {
class ProjectDocument;
class TimelineStrip;
}  // namespace plenopath::widgets

namespace plenopath::studio {

class EnvelopeService;

struct Profiles {
  QVector<double> envelope_area;  // m^2 per path position (empty when unknown)
  QVector<double> depth_volume;   // m^3 per path position (empty when the capture has no depth)
};

class ProfileService : public QObject {
  Q_OBJECT
 public:
  ProfileService(widgets::ProjectDocument& document, EnvelopeService& envelopes,
                 widgets::TimelineStrip& strip, QObject* parent = nullptr);
  ~ProfileService() override;
  const Profiles& profiles() const { return profiles_; }
  bool busy() const { return watcher_.isRunning() || again_; }

 signals:
  void updated();

 private:
  void recompute();
  widgets::ProjectDocument& document_;
  EnvelopeService& envelopes_;
  widgets::TimelineStrip& strip_;
  Profiles profiles_;
  QFutureWatcher<Profiles> watcher_;
  std::shared_ptr<std::atomic<bool>> stop_;
  bool again_ = false;
};

}  // namespace plenopath::studio
