// An MP4 file with H.264 video and, optionally, the speech as AAC audio, written frame by frame
// (FFmpeg's libavformat and libavcodec). The file appears only when finish() succeeds: frames go to
// a temporary next to it, which the destructor removes if finish() was never reached.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

namespace performer::video {

struct VideoSettings {
  int width = 640;   // even
  int height = 480;  // even
  int fps = 30;
  int crf = 20;  // x264's constant rate factor: lower is better and bigger
};

struct AudioTrack {
  int sample_rate = 0;                    // Hz
  std::span<const std::int16_t> samples;  // mono PCM, starting with the first video frame
};

class VideoWriter {
 public:
  // Throws std::invalid_argument for bad settings (odd or tiny sizes, fps outside 1..240, an empty
  // or absurd audio rate) and std::runtime_error naming `path` when FFmpeg cannot open the encoders
  // or the temporary file.
  VideoWriter(const std::filesystem::path& path, const VideoSettings& settings, const AudioTrack* audio = nullptr);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // One frame: width * height * 3 bytes of RGB, rows top first. The audio up to the frame's end
  // goes in alongside.
  void write_frame(std::span<const std::uint8_t> rgb);
  // Flushes the encoders (and any audio left past the last frame, so the sound is heard to its
  // end), writes the trailer and moves the file into place.
  void finish();
  std::int64_t frames_written() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace performer::video
