#pragma once
// Frames of the document's capture for the views, decoded off the GUI thread through processing's
// FrameCache (frame_source.h, frame_cache.h: byte-bounded LRU, prefetch around the play head in the
// direction of travel); the last few converted images are kept here too. Requests are latest-wins: while one
// frame decodes, only the most recent request waits, so scrubbing and playback never queue up work.
#include <QFutureWatcher>
#include <QImage>
#include <QList>
#include <QObject>
#include <QString>
#include <memory>
#include <utility>

namespace plenopath {
class FrameCache;
class FrameSource;
}  // namespace plenopath

namespace plenopath::widgets {

class ProjectDocument;

class FrameProvider : public QObject {
  Q_OBJECT
 public:
  explicit FrameProvider(ProjectDocument& document, QObject* parent = nullptr);
  ~FrameProvider() override;

  // Asks for the frame at path position `position`; frame_ready follows (at once when cached).
  void request(int position);
  // The frame if cached, else a null image.
  QImage cached(int position) const;
  // Why the capture cannot be shown ("" when it can).
  const QString& error() const { return error_; }
  bool has_source() const { return source_ != nullptr; }

 signals:
  void frame_ready(int position, const QImage& image);
  void frame_failed(int position, const QString& message);

 private:
  void reopen();
  void start(int position);
  void on_decoded();
  int source_index_of(int position) const;

  ProjectDocument& document_;
  std::shared_ptr<FrameSource> source_;
  std::shared_ptr<FrameCache> frame_cache_;
  int last_position_ = 0;
  QString error_;
  QList<std::pair<int, QImage>> cache_;  // most recent first
  qint64 cache_bytes_ = 0;
  QFutureWatcher<std::pair<QImage, QString>> watcher_;
  int decoding_ = -1;        // position being decoded, -1 when idle
  int waiting_ = -1;         // latest request made while decoding
  unsigned generation_ = 0;  // bumps when the source changes; stale decodes are dropped
  unsigned decoding_generation_ = 0;
};

}  // namespace plenopath::widgets
