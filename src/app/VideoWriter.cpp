#include "app/VideoWriter.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr::app {
namespace {

namespace fs = std::filesystem;

std::string shellQuoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The container and codec arguments for an output extension.
std::string formatArguments(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // yuv420p: what players expect of H.264 and VP9; it needs even sizes, hence the padding.
  const std::string even = " -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p";
  if (ext == ".mp4") return "-f mp4 -c:v libx264 -crf 18 -movflags +faststart" + even;
  if (ext == ".mov") return "-f mov -c:v libx264 -crf 18" + even;
  if (ext == ".mkv") return "-f matroska -c:v libx264 -crf 18" + even;
  if (ext == ".webm") return "-f webm -c:v libvpx-vp9 -b:v 0 -crf 30" + even;
  if (ext == ".avi") return "-f avi -c:v mpeg4 -q:v 2" + even;
  if (ext == ".gif") return "-f gif";
  throw Error("--video " + path +
              ": give a video file name ending in .mp4, .mov, .mkv, .webm, .avi or .gif");
}

// SIGPIPE ignored while frames go to ffmpeg, so that an ffmpeg that stopped is an error to
// report rather than a signal that ends mfadvr.
struct PipeSignalIgnored {
  void (*previous)(int) = std::signal(SIGPIPE, SIG_IGN);
  ~PipeSignalIgnored() { std::signal(SIGPIPE, previous); }
};

}  // namespace

std::string findFfmpeg() {
  if (const char* env = std::getenv("MFADVR_FFMPEG"); env && *env)
    return ::access(env, X_OK) == 0 ? std::string(env) : std::string();
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::path(dir) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  const std::string format = formatArguments(path);
  const std::string ffmpeg = findFfmpeg();
  if (ffmpeg.empty())
    throw Error(
        "--video needs ffmpeg, which is not on the PATH (Debian: apt-get install ffmpeg; "
        "or set MFADVR_FFMPEG to its path); -o 'frame_%03d.png' writes the frames as "
        "PNG files instead");
  file_ = std::make_unique<AtomicFileWriter>(path);
  std::ostringstream command;
  command << shellQuoted(ffmpeg) << " -nostdin -hide_banner -loglevel error -y -f rawvideo"
          << " -pix_fmt rgb24 -s " << width << "x" << height << " -framerate " << fps << " -i - "
          << format << " " << shellQuoted(file_->temporaryPath().string());
  pipe_ = ::popen(command.str().c_str(), "w");
  if (!pipe_) throw Error("--video: cannot start " + ffmpeg);
}

VideoWriter::~VideoWriter() {
  if (pipe_) ::pclose(pipe_);  // an unfinished video: ffmpeg ends, the temporary file goes
}

void VideoWriter::add(const Image8& frame) {
  if (!pipe_) throw Error("--video " + path_ + ": the video is already finished");
  if (frame.width != width_ || frame.height != height_)
    throw Error("--video: every frame must be " + std::to_string(width_) + "x" +
                std::to_string(height_));
  const PipeSignalIgnored ignored;
  row_.resize(static_cast<size_t>(width_) * 3);
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* in = frame.data.data() + static_cast<size_t>(y) * width_ * frame.channels;
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < 3; ++c)
        row_[3 * size_t(x) + size_t(c)] = char(in[x * frame.channels + c]);
    if (std::fwrite(row_.data(), 1, row_.size(), pipe_) != row_.size())
      throw Error("--video " + path_ + ": ffmpeg stopped taking frames (its message is above)");
  }
}

void VideoWriter::finish() {
  if (!pipe_) return;
  const PipeSignalIgnored ignored;
  const int status = ::pclose(pipe_);
  pipe_ = nullptr;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error("--video " + path_ + ": ffmpeg failed (its message is above)");
  file_->commit();
}

}  // namespace mfadvr::app
