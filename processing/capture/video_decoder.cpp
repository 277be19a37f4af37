#include "processing/capture/video_decoder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/avutil.h>
#include <libswscale/swscale.h>
}

#include "model/error.h"

namespace plenopath {
namespace {

std::string av_message(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, text, sizeof text);
  return text;
}

// FFmpeg prints warnings (deprecated pixel formats, timestamps) at its default level; keep errors only, as
// OpenCV's FFmpeg backend does.
void quiet_ffmpeg_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (av_log_get_level() > AV_LOG_ERROR) av_log_set_level(AV_LOG_ERROR);
  });
}

// The time stamp that identifies a decoded frame: its PTS, else FFmpeg's best guess (from the DTS).
int64_t frame_stamp(const AVFrame* frame) {
  return frame->pts != AV_NOPTS_VALUE ? frame->pts : frame->best_effort_timestamp;
}

struct IndexEntry {
  int64_t pts = 0;
  int64_t seek_ts = 0;  // where to seek to start decoding at this frame (keyframes only)
  bool key = false;
};

}  // namespace

struct VideoDecoder::Impl {
  std::string path;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = nullptr;
  AVFrame* frame = nullptr;  // the decoder's latest output
  SwsContext* sws = nullptr;
  int stream = -1;
  AVRational time_base{1, 1};
  double nominal_rate = 0.0;
  long long container_count = 0;
  bool packets_end_early = false;
  bool by_decoding = false;

  std::vector<int64_t> pts;           // per frame in presentation order: strictly increasing
  std::vector<int> keys;              // frames decoding may start at, ascending
  std::vector<int64_t> key_seek;      // per entry of keys: the time stamp to seek to
  int64_t start_ts = AV_NOPTS_VALUE;  // the first packet's DTS: seek target for the beginning

  // Where the decoder is: the frame it is expected to give next (-1: unknown), and a decoded frame not yet
  // returned (a read that found its frame missing keeps the next one here).
  int next = -1;
  int held = -1;
  bool input_ended = false;
  VideoDecoderStats stats;

  ~Impl() {
    sws_freeContext(sws);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }

  Error error(const std::string& what) const { return file_error(path, what); }

  void open() {
    quiet_ffmpeg_once();
    int r = avformat_open_input(&format, path.c_str(), nullptr, nullptr);
    if (r < 0) {
      format = nullptr;
      throw error("cannot open video (not a video, or a container/codec FFmpeg cannot read): " +
                  av_message(r));
    }
    r = avformat_find_stream_info(format, nullptr);
    if (r < 0) throw error("cannot read the video's stream information: " + av_message(r));
    const AVCodec* decoder = nullptr;
    stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
    if (stream >= 0 && (format->streams[stream]->disposition & AV_DISPOSITION_ATTACHED_PIC)) {
      stream = -1;  // a cover picture, not the footage: take another video stream
      for (unsigned s = 0; s < format->nb_streams; ++s) {
        const AVStream* st = format->streams[s];
        if (st->codecpar->codec_type == AVMEDIA_TYPE_VIDEO &&
            !(st->disposition & AV_DISPOSITION_ATTACHED_PIC)) {
          stream = static_cast<int>(s);
          decoder = avcodec_find_decoder(st->codecpar->codec_id);
          break;
        }
      }
    }
    if (stream < 0) throw error("cannot open video (the file holds no video stream)");
    AVStream* st = format->streams[stream];
    if (!decoder) {
      const AVCodecDescriptor* d = avcodec_descriptor_get(st->codecpar->codec_id);
      throw error(std::string("cannot decode the video's codec (") + (d ? d->name : "unknown") +
                  "): FFmpeg has no decoder for it");
    }
    for (unsigned s = 0; s < format->nb_streams; ++s)
      if (static_cast<int>(s) != stream) format->streams[s]->discard = AVDISCARD_ALL;
    codec = avcodec_alloc_context3(decoder);
    packet = av_packet_alloc();
    frame = av_frame_alloc();
    if (!codec || !packet || !frame) throw error("out of memory opening the video");
    r = avcodec_parameters_to_context(codec, st->codecpar);
    if (r < 0) throw error("cannot set up the video decoder: " + av_message(r));
    codec->thread_count = 0;  // as many as FFmpeg sees fit; frame threading stays bit-exact
    codec->thread_type = FF_THREAD_FRAME | FF_THREAD_SLICE;
    codec->pkt_timebase = st->time_base;
    r = avcodec_open2(codec, decoder, nullptr);
    if (r < 0) throw error(std::string("cannot open the ") + decoder->name + " decoder: " + av_message(r));
    time_base = st->time_base;
    if (time_base.num <= 0 || time_base.den <= 0) throw error("the video stream has no valid time base");
    const AVRational rate = av_guess_frame_rate(format, st, nullptr);
    if (rate.num > 0 && rate.den > 0) nominal_rate = av_q2d(rate);
    container_count = st->nb_frames > 0 ? st->nb_frames : 0;
    if (!index_by_packets()) index_by_decoding();
  }

  // The stream's packets in file order: their PTS (presentation order = sorted PTS) and keyframe flags.
  // False when PTS are missing or repeat, so that only decoding can tell the frames apart.
  bool index_by_packets() {
    std::vector<IndexEntry> entries;
    bool first = true;
    bool usable = true;
    long long packets = 0;  // shown or not
    for (;;) {
      const int r = av_read_frame(format, packet);
      if (r < 0) {
        // A read error, or fewer packets than the container's sample table lists: a file cut short.
        packets_end_early = r != AVERROR_EOF || (container_count > 0 && packets < container_count);
        break;
      }
      if (packet->stream_index == stream) {
        ++packets;
        if (first) {
          start_ts = packet->dts != AV_NOPTS_VALUE ? packet->dts : packet->pts;
          first = false;
        }
        // A packet the container's edit list cuts away is decoded (others may refer to it) but never shown.
        if (!(packet->flags & AV_PKT_FLAG_DISCARD)) {
          if (packet->pts == AV_NOPTS_VALUE) usable = false;
          IndexEntry e;
          e.pts = packet->pts;
          e.key = packet->flags & AV_PKT_FLAG_KEY;
          e.seek_ts = packet->dts != AV_NOPTS_VALUE ? std::min(packet->dts, packet->pts) : packet->pts;
          entries.push_back(e);
        }
      }
      av_packet_unref(packet);
    }
    if (!usable || first) {
      rewind();
      return false;
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const IndexEntry& a, const IndexEntry& b) { return a.pts < b.pts; });
    for (std::size_t k = 1; k < entries.size(); ++k)
      if (entries[k].pts == entries[k - 1].pts) {
        rewind();
        return false;
      }
    set_index(entries);
    rewind();
    return true;
  }

  // Every frame decoded once: those that decode, with the time stamps the decoder gives them.
  void index_by_decoding() {
    rewind();
    std::vector<IndexEntry> entries;
    bool first = true;
    while (decode_next()) {
      IndexEntry e;
      e.pts = frame_stamp(frame);
      if (e.pts == AV_NOPTS_VALUE) continue;  // cannot be found again
      if (first && start_ts == AV_NOPTS_VALUE)
        start_ts = frame->pkt_dts != AV_NOPTS_VALUE ? frame->pkt_dts : e.pts;
      first = false;
      e.key = frame->key_frame || frame->pict_type == AV_PICTURE_TYPE_I;
      e.seek_ts = frame->pkt_dts != AV_NOPTS_VALUE ? std::min(frame->pkt_dts, e.pts) : e.pts;
      entries.push_back(e);
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const IndexEntry& a, const IndexEntry& b) { return a.pts < b.pts; });
    // A repeated time stamp cannot be told apart from its twin: keep the first.
    entries.erase(std::unique(entries.begin(), entries.end(),
                              [](const IndexEntry& a, const IndexEntry& b) { return a.pts == b.pts; }),
                  entries.end());
    set_index(entries);
    by_decoding = true;
    rewind();
  }

  void set_index(const std::vector<IndexEntry>& entries) {
    pts.clear();
    keys.clear();
    key_seek.clear();
    pts.reserve(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      pts.push_back(entries[k].pts);
      if (entries[k].key) {
        keys.push_back(static_cast<int>(k));
        key_seek.push_back(entries[k].seek_ts);
      }
    }
  }

  // Back to the first packet; the decoder is emptied and gives frame 0 next.
  void rewind() {
    seek(start_ts);
    next = 0;
  }

  void seek(int64_t ts) {
    int r = -1;
    if (ts != AV_NOPTS_VALUE) {
      r = av_seek_frame(format, stream, ts, AVSEEK_FLAG_BACKWARD);
      if (r < 0) r = avformat_seek_file(format, stream, std::numeric_limits<int64_t>::min(), ts, ts, 0);
    }
    if (r < 0) r = av_seek_frame(format, -1, 0, AVSEEK_FLAG_BYTE);  // streams without time stamps
    if (r < 0) throw error("cannot seek in the video: " + av_message(r));
    avcodec_flush_buffers(codec);
    input_ended = false;
    held = -1;
    next = -1;
    ++stats.seeks;
  }

  // The decoder's next frame in presentation order, into `frame`; false at the end of the stream.
  bool decode_next() {
    int errors = 0;
    for (;;) {
      int r = avcodec_receive_frame(codec, frame);
      if (r == 0) {
        ++stats.frames_decoded;
        return true;
      }
      if (r == AVERROR_EOF) return false;
      if (r != AVERROR(EAGAIN) && ++errors > 1000) return false;  // a damaged stream that never recovers
      if (input_ended) {
        if (r == AVERROR(EAGAIN)) return false;  // drained
        continue;
      }
      r = av_read_frame(format, packet);
      if (r < 0) {
        input_ended = true;
        avcodec_send_packet(codec, nullptr);  // drain the frames still held for reordering
        continue;
      }
      if (packet->stream_index == stream) avcodec_send_packet(codec, packet);  // bad data: the frame is lost
      av_packet_unref(packet);
    }
  }

  // The index of the decoded frame in `frame`, -1 if the index does not know its time stamp.
  int index_of_decoded() const {
    const int64_t t = frame_stamp(frame);
    const auto it = std::lower_bound(pts.begin(), pts.end(), t);
    return it != pts.end() && *it == t ? static_cast<int>(it - pts.begin()) : -1;
  }

  // Position in `keys` of the last keyframe at or before frame i; -1 if none (start of stream).
  int key_before(int i) const {
    const auto it = std::upper_bound(keys.begin(), keys.end(), i);
    return static_cast<int>(it - keys.begin()) - 1;
  }

  cv::Mat convert(int i) {
    if (frame->width <= 0 || frame->height <= 0) throw error("frame " + std::to_string(i) + " has no size");
    sws = sws_getCachedContext(sws, frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
                               frame->width, frame->height, AV_PIX_FMT_BGR24, SWS_BICUBIC, nullptr, nullptr,
                               nullptr);
    if (!sws) throw error("frame " + std::to_string(i) + ": cannot convert its pixel format to BGR");
    cv::Mat out(frame->height, frame->width, CV_8UC3);
    uint8_t* planes[4] = {out.data, nullptr, nullptr, nullptr};
    int strides[4] = {static_cast<int>(out.step[0]), 0, 0, 0};
    sws_scale(sws, frame->data, frame->linesize, 0, frame->height, planes, strides);
    return out;
  }

  cv::Mat read(int i) {
    if (i < 0 || i >= static_cast<int>(pts.size()))
      throw error("frame " + std::to_string(i) + " does not exist");
    if (held == i) {
      held = -1;
      next = i + 1;
      return convert(i);
    }
    // Decoding on is right when frame i lies ahead and no keyframe sits between here and it; else seek.
    const int key = key_before(i);
    const int key_frame = key >= 0 ? keys[key] : 0;
    if (held >= 0 && held < i) next = held + 1;
    const bool decode_on = next >= 0 && next <= i && held < i && key_frame <= next;
    held = -1;
    // Where to start: here (if decoding on), the keyframe before i, the keyframe before that, the start.
    // A container indexes its keyframes by PTS (Matroska) or DTS (MP4): seeking to the keyframe's PTS lands
    // on it in both, or after it in a DTS index when the reordering delay exceeds the GOP; then its DTS does.
    std::vector<int64_t> starts;
    if (key >= 0) starts.push_back(pts[keys[key]]);
    if (key >= 0 && key_seek[key] != pts[keys[key]]) starts.push_back(key_seek[key]);
    if (key >= 1) starts.push_back(key_seek[key - 1]);
    starts.push_back(start_ts);
    std::size_t attempt = 0;
    if (!decode_on) seek(starts[attempt++]);
    for (;;) {
      bool before_i = false;  // this attempt has given a frame before i
      for (;;) {
        if (!decode_next()) {
          next = -1;
          throw error("frame " + std::to_string(i) + " could not be decoded (the stream ends before it)");
        }
        const int got = index_of_decoded();
        if (got < 0) continue;
        if (got < i) {
          before_i = true;
          continue;
        }
        if (got == i) {
          next = i + 1;
          return convert(i);
        }
        break;  // past frame i
      }
      // Started too late (a container that seeks past the keyframe asked for): start earlier. Started before
      // frame i and went past it: the stream has no such frame.
      if (before_i || attempt >= starts.size()) {
        held = index_of_decoded();
        next = held;
        throw error("frame " + std::to_string(i) + " could not be decoded");
      }
      seek(starts[attempt++]);
    }
  }
};

VideoDecoder::VideoDecoder(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->open();
}
VideoDecoder::~VideoDecoder() = default;

const std::string& VideoDecoder::path() const { return impl_->path; }
int VideoDecoder::frame_count() const { return static_cast<int>(impl_->pts.size()); }
int VideoDecoder::width() const { return impl_->codec->width; }
int VideoDecoder::height() const { return impl_->codec->height; }
double VideoDecoder::frame_rate() const { return impl_->nominal_rate; }
double VideoDecoder::time_s(int frame) const {
  if (frame < 0 || frame >= frame_count())
    throw impl_->error("frame " + std::to_string(frame) + " does not exist");
  return static_cast<double>(impl_->pts[frame] - impl_->pts[0]) * impl_->time_base.num / impl_->time_base.den;
}
long long VideoDecoder::container_frame_count() const { return impl_->container_count; }
bool VideoDecoder::packets_end_early() const { return impl_->packets_end_early; }
bool VideoDecoder::indexed_by_decoding() const { return impl_->by_decoding; }
void VideoDecoder::index_by_decoding() { impl_->index_by_decoding(); }
cv::Mat VideoDecoder::read(int frame) { return impl_->read(frame); }
const VideoDecoderStats& VideoDecoder::stats() const { return impl_->stats; }

}  // namespace plenopath
