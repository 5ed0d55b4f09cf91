#include "app/commands/video_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "app/commands/subprocess.h"
#include "app/config/input_error.h"

namespace tallow::app {

namespace {

struct Container {
  const char* extension;
  const char* format;  ///< ffmpeg's -f (the temporary file has no telling extension)
  std::vector<std::string> codec;
};

const std::vector<Container>& containers() {
  // H.264 at CRF 18 ("visually lossless" in x264's documentation) in 4:2:0, which every player reads.
  static const std::vector<Container> list = {
      {".mp4", "mp4", {"-c:v", "libx264", "-crf", "18", "-pix_fmt", "yuv420p", "-movflags", "+faststart"}},
      {".mov", "mov", {"-c:v", "libx264", "-crf", "18", "-pix_fmt", "yuv420p"}},
      {".mkv", "matroska", {"-c:v", "libx264", "-crf", "18", "-pix_fmt", "yuv420p"}},
      {".webm", "webm", {"-c:v", "libvpx-vp9", "-crf", "30", "-b:v", "0", "-pix_fmt", "yuv420p"}},
  };
  return list;
}

const Container* containerOf(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  for (const Container& c : containers())
    if (ext == c.extension) return &c;
  return nullptr;
}

/// Writes all of `data` to `fd`; false when the reader went away (EPIPE) or another error.
bool writeAll(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::filesystem::path findFfmpeg() { return findExecutable("ffmpeg", "TALLOW_FFMPEG"); }

void checkVideoOutput(const std::filesystem::path& file) {
  if (!containerOf(file))
    throw InputError("--video: " + file.string() + ": unknown video container (use .mp4, .mov, .mkv or .webm)");
  if (findFfmpeg().empty())
    throw InputError("--video: ffmpeg is not installed (apt-get install ffmpeg, or set TALLOW_FFMPEG to its path)");
}

VideoEncoder::VideoEncoder(const std::filesystem::path& file, int width, int height, double fps) : file_(file) {
  checkVideoOutput(file);
  const Container& container = *containerOf(file);
  const std::string ffmpeg = findFfmpeg().string();
  frameBytes_ = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  output_ = std::make_unique<gpu::PendingFile>(file);
  log_ = output_->temporary().string() + ".log";
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.17g", fps);
  std::vector<std::string> args = {ffmpeg, "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgb24",
                                   "-s", std::to_string(width) + "x" + std::to_string(height),
                                   "-r", rate, "-i", "pipe:0",
                                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"};
  args.insert(args.end(), container.codec.begin(), container.codec.end());
  // "file:" so that ffmpeg takes the name as a local file whatever it looks like ("http:…", "pipe:…").
  args.insert(args.end(), {"-f", container.format, "file:" + std::filesystem::absolute(output_->temporary()).string()});
  args.erase(args.begin());  // argv[0]: spawnProgram puts the program's path there

  int pipeFds[2];
  if (::pipe2(pipeFds, O_CLOEXEC) != 0)
    throw std::runtime_error("cannot write " + file.string() + ": pipe: " + std::strerror(errno));
  SpawnOptions spawn;
  spawn.stdinFd = pipeFds[0];
  spawn.stderrFile = log_;
  try {
    pid_ = spawnProgram(ffmpeg, args, spawn);
  } catch (const std::exception& e) {
    ::close(pipeFds[0]);
    ::close(pipeFds[1]);
    pid_ = -1;
    std::error_code ec;
    std::filesystem::remove(log_, ec);
    throw std::runtime_error("cannot write " + file.string() + ": " + e.what());
  }
  ::close(pipeFds[0]);
  pipe_ = pipeFds[1];
  // A dying ffmpeg must not kill us with SIGPIPE: the failed write is reported instead.
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previousSigpipe_);
}

VideoEncoder::~VideoEncoder() { abort(); }

int VideoEncoder::wait() {
  if (pipe_ >= 0) {
    ::close(pipe_);
    sigaction(SIGPIPE, &previousSigpipe_, nullptr);
  }
  pipe_ = -1;
  int status = 0;
  if (pid_ > 0) status = waitProgram(pid_);
  pid_ = -1;
  return status;
}

void VideoEncoder::abort() {
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    wait();
  }
  std::error_code ec;
  if (!log_.empty()) std::filesystem::remove(log_, ec);
  output_.reset();  // removes ffmpeg's temporary unless committed
}

void VideoEncoder::add(std::span<const std::uint8_t> rgb) {
  if (rgb.size() != frameBytes_)
    throw std::runtime_error("cannot write " + file_.string() + ": a frame of another size than the video's");
  if (fed_) fed_ = writeAll(pipe_, rgb.data(), rgb.size());
  if (!fed_) {  // ffmpeg stopped reading: its error says why
    const int status = wait();
    const std::string error = lastMessageLine(log_);
    abort();
    (void)status;
    throw std::runtime_error("cannot write " + file_.string() + ": ffmpeg failed" + (error.empty() ? "" : ": " + error));
  }
  ++frames_;
}

void VideoEncoder::finish() {
  const int status = wait();
  const std::string error = lastMessageLine(log_);
  std::error_code ec;
  std::filesystem::remove(log_, ec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    abort();
    throw std::runtime_error("cannot write " + file_.string() + ": ffmpeg failed" + (error.empty() ? "" : ": " + error));
  }
  output_->commit();
  output_.reset();
  log_.clear();
}

}  // namespace tallow::app
