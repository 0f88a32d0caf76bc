#pragma once
// `render --times ... --video OUT.mp4`: frames piped to ffmpeg (Debian's ffmpeg package), which
// codes them into a video file. The file appears whole or not at all: ffmpeg writes a temporary
// file beside the target, renamed over it once ffmpeg has finished without error.
#include <cstdio>
#include <memory>
#include <string>

#include "core/image/Image.h"
#include "core/util/AtomicFile.h"

namespace mfadvr::app {

// ffmpeg's path: $MFADVR_FFMPEG, else `ffmpeg` on the PATH; empty when that is no program.
std::string findFfmpeg();

class VideoWriter {
 public:
  // Throws mfadvr::Error when ffmpeg is missing (with how to get it), when the extension is not
  // one of .mp4 .mov .mkv .webm .avi .gif, or when ffmpeg cannot be started. `fps` frames per
  // second; frames of `width` x `height` pixels (odd sizes are padded by one pixel for the
  // codecs that need even ones).
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // An RGB or RGBA frame of the size given (alpha dropped). Throws mfadvr::Error when ffmpeg
  // stopped (its own message is on stderr).
  void add(const Image8& frame);
  // Waits for ffmpeg and publishes the file; throws mfadvr::Error when ffmpeg failed.
  void finish();

 private:
  std::string path_;
  int width_, height_;
  std::unique_ptr<AtomicFileWriter> file_;
  FILE* pipe_ = nullptr;
  std::string row_;
};

}  // namespace mfadvr::app
