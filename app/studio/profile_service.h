#pragma once
// The per-frame curves of the timeline: the envelope area at each path position (from the document's
// shared visibility index of the current plan) and the depth volume of each frame's depth map
// (processing/sampling/depth_volume.h). Computed off the GUI thread whenever the path, the plan or the
// capture changes; the newest request wins: an older run stops early and its result is dropped
// (widgets/coalescing_runner.h).
#include <QObject>
#include <QVector>

namespace plenopath::widgets {
class CoalescingRunner;
class ProjectDocument;
class TimelineStrip;
}  // namespace plenopath::widgets

namespace plenopath::studio {

struct Profiles {
  QVector<double> envelope_area;  // m^2 per path position (empty when unknown)
  QVector<double> depth_volume;   // m^3 per path position (empty when the capture has no depth)
};

class ProfileService : public QObject {
  Q_OBJECT
 public:
  ProfileService(widgets::ProjectDocument& document, widgets::TimelineStrip& strip,
                 QObject* parent = nullptr);
  ~ProfileService() override;
  const Profiles& profiles() const { return profiles_; }
  bool busy() const;

 signals:
  void updated();

 private:
  void recompute();
  widgets::ProjectDocument& document_;
  widgets::TimelineStrip& strip_;
  Profiles profiles_;
  widgets::CoalescingRunner* runner_;
};

}  // namespace plenopath::studio
