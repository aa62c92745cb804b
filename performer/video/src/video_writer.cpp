#include "performer/video/video_writer.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/channel_layout.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace performer::video {

namespace {

std::string av_message(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

struct CodecContextDeleter {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameDeleter {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketDeleter {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
using CodecContext = std::unique_ptr<AVCodecContext, CodecContextDeleter>;
using Frame = std::unique_ptr<AVFrame, FrameDeleter>;
using Packet = std::unique_ptr<AVPacket, PacketDeleter>;

}  // namespace

struct VideoWriter::State {
  std::filesystem::path path, temporary;
  VideoSettings settings;
  std::vector<std::int16_t> audio;
  int sample_rate = 0;
  AVFormatContext* format = nullptr;
  CodecContext video, sound;
  AVStream* video_stream = nullptr;
  AVStream* sound_stream = nullptr;
  Frame picture, samples;
  Packet packet;
  SwsContext* scaler = nullptr;
  std::int64_t frames = 0;
  std::size_t audio_sent = 0;  // samples handed to the AAC encoder so far
  bool finished = false;

  ~State() {
    sws_freeContext(scaler);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    if (!finished && !temporary.empty()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
    }
  }

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw std::runtime_error(path.string() + ": " + what + (code < 0 ? ": " + av_message(code) : std::string()));
  }

  // Sends `frame` (null: flush) to `codec` and writes every packet that comes out.
  void encode(AVCodecContext* codec, AVStream* stream, AVFrame* frame) {
    int r = avcodec_send_frame(codec, frame);
    if (r < 0) fail("encoding", r);
    while (true) {
      r = avcodec_receive_packet(codec, packet.get());
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("encoding", r);
      av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      r = av_interleaved_write_frame(format, packet.get());
      if (r < 0) fail("writing", r);
    }
  }

  // AAC frames of the speech up to sample `until` (the last one padded with silence when `all`).
  void send_audio(std::size_t until, bool all) {
    if (!sound) return;
    const auto frame_size = static_cast<std::size_t>(sound->frame_size);
    until = std::min(until, audio.size());
    while (audio_sent + frame_size <= until || (all && audio_sent < audio.size())) {
      int r = av_frame_make_writable(samples.get());
      if (r < 0) fail("audio frame", r);
      auto* out = reinterpret_cast<float*>(samples->data[0]);
      for (std::size_t i = 0; i < frame_size; ++i) {
        const std::size_t s = audio_sent + i;
        out[i] = s < audio.size() ? static_cast<float>(audio[s]) / 32768.0f : 0.0f;
      }
      samples->pts = static_cast<std::int64_t>(audio_sent);
      encode(sound.get(), sound_stream, samples.get());
      audio_sent += frame_size;
    }
  }
};

VideoWriter::VideoWriter(const std::filesystem::path& path, const VideoSettings& settings, const AudioTrack* audio)
    : state_(std::make_unique<State>()) {
  if (settings.width < 16 || settings.height < 16 || settings.width > 8192 || settings.height > 8192 ||
      settings.width % 2 != 0 || settings.height % 2 != 0)
    throw std::invalid_argument("video size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                                ": H.264 needs even sizes from 16x16 to 8192x8192");
  if (settings.fps < 1 || settings.fps > 240) throw std::invalid_argument("video fps must be 1 to 240");
  if (audio && (audio->sample_rate < 8000 || audio->sample_rate > 96000))
    throw std::invalid_argument("audio sample rate " + std::to_string(audio->sample_rate) + " outside 8000..96000 Hz");
  // FFmpeg's own chatter (x264's statistics) stays off the performer's one-line-per-event log;
  // failures come back as exceptions instead.
  av_log_set_level(AV_LOG_ERROR);
  State& s = *state_;
  s.path = path;
  s.settings = settings;
  s.temporary = path;
  s.temporary += ".partial";
  s.packet.reset(av_packet_alloc());

  int r = avformat_alloc_output_context2(&s.format, nullptr, "mp4", nullptr);
  if (r < 0 || !s.format) s.fail("no MP4 muxer", r);

  const AVCodec* h264 = avcodec_find_encoder(AV_CODEC_ID_H264);
  if (!h264) s.fail("no H.264 encoder in this FFmpeg", 0);
  s.video.reset(avcodec_alloc_context3(h264));
  s.video->width = settings.width;
  s.video->height = settings.height;
  s.video->time_base = AVRational{1, settings.fps};
  s.video->framerate = AVRational{settings.fps, 1};
  s.video->pix_fmt = AV_PIX_FMT_YUV420P;
  s.video->gop_size = settings.fps * 2;
  if (s.format->oformat->flags & AVFMT_GLOBALHEADER) s.video->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(s.video->priv_data, "preset", "veryfast", 0);
  av_opt_set(s.video->priv_data, "crf", std::to_string(settings.crf).c_str(), 0);
  r = avcodec_open2(s.video.get(), h264, nullptr);
  if (r < 0) s.fail("opening the H.264 encoder", r);
  s.video_stream = avformat_new_stream(s.format, nullptr);
  s.video_stream->time_base = s.video->time_base;
  avcodec_parameters_from_context(s.video_stream->codecpar, s.video.get());

  if (audio && !audio->samples.empty()) {
    s.audio.assign(audio->samples.begin(), audio->samples.end());
    s.sample_rate = audio->sample_rate;
    const AVCodec* aac = avcodec_find_encoder(AV_CODEC_ID_AAC);
    if (!aac) s.fail("no AAC encoder in this FFmpeg", 0);
    s.sound.reset(avcodec_alloc_context3(aac));
    s.sound->sample_fmt = AV_SAMPLE_FMT_FLTP;
    s.sound->sample_rate = audio->sample_rate;
    av_channel_layout_default(&s.sound->ch_layout, 1);
    s.sound->bit_rate = 96000;
    s.sound->time_base = AVRational{1, audio->sample_rate};
    if (s.format->oformat->flags & AVFMT_GLOBALHEADER) s.sound->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    r = avcodec_open2(s.sound.get(), aac, nullptr);
    if (r < 0) s.fail("opening the AAC encoder", r);
    s.sound_stream = avformat_new_stream(s.format, nullptr);
    s.sound_stream->time_base = s.sound->time_base;
    avcodec_parameters_from_context(s.sound_stream->codecpar, s.sound.get());
    s.samples.reset(av_frame_alloc());
    s.samples->format = AV_SAMPLE_FMT_FLTP;
    s.samples->sample_rate = audio->sample_rate;
    av_channel_layout_copy(&s.samples->ch_layout, &s.sound->ch_layout);
    s.samples->nb_samples = s.sound->frame_size;
    r = av_frame_get_buffer(s.samples.get(), 0);
    if (r < 0) s.fail("audio frame", r);
  }

  r = avio_open(&s.format->pb, s.temporary.c_str(), AVIO_FLAG_WRITE);
  if (r < 0) s.fail("cannot write " + s.temporary.string(), r);
  r = avformat_write_header(s.format, nullptr);
  if (r < 0) s.fail("writing the MP4 header", r);

  s.picture.reset(av_frame_alloc());
  s.picture->format = AV_PIX_FMT_YUV420P;
  s.picture->width = settings.width;
  s.picture->height = settings.height;
  r = av_frame_get_buffer(s.picture.get(), 0);
  if (r < 0) s.fail("video frame", r);
  s.scaler = sws_getContext(settings.width, settings.height, AV_PIX_FMT_RGB24, settings.width, settings.height,
                            AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!s.scaler) s.fail("no RGB to YUV converter", 0);
}

VideoWriter::~VideoWriter() = default;

void VideoWriter::write_frame(std::span<const std::uint8_t> rgb) {
  State& s = *state_;
  if (s.finished) throw std::logic_error("VideoWriter: frame after finish()");
  const auto w = static_cast<std::size_t>(s.settings.width), h = static_cast<std::size_t>(s.settings.height);
  if (rgb.size() != w * h * 3)
    throw std::invalid_argument("VideoWriter: " + std::to_string(rgb.size()) + " bytes for a " + std::to_string(w) +
                                "x" + std::to_string(h) + " RGB frame");
  int r = av_frame_make_writable(s.picture.get());
  if (r < 0) s.fail("video frame", r);
  const std::uint8_t* source[1] = {rgb.data()};
  const int stride[1] = {static_cast<int>(w * 3)};
  sws_scale(s.scaler, source, stride, 0, static_cast<int>(h), s.picture->data, s.picture->linesize);
  s.picture->pts = s.frames++;
  s.encode(s.video.get(), s.video_stream, s.picture.get());
  // The speech up to this frame's end.
  if (s.sound) s.send_audio(static_cast<std::size_t>(s.frames * s.sample_rate / s.settings.fps), false);
}

void VideoWriter::finish() {
  State& s = *state_;
  if (s.finished) return;
  s.encode(s.video.get(), s.video_stream, nullptr);
  if (s.sound) {
    s.send_audio(s.audio.size(), true);
    s.encode(s.sound.get(), s.sound_stream, nullptr);
  }
  int r = av_write_trailer(s.format);
  if (r < 0) s.fail("writing the MP4 trailer", r);
  avio_closep(&s.format->pb);
  std::error_code error;
  std::filesystem::rename(s.temporary, s.path, error);
  if (error)
    throw std::runtime_error(s.path.string() + ": cannot move the finished video into place: " + error.message());
  s.finished = true;
}

std::int64_t VideoWriter::frames_written() const { return state_->frames; }

}  // namespace performer::video
