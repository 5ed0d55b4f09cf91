#include "app/commands/video_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "app/config/input_error.h"
#include "gpu/atomic_file.h"

extern char** environ;

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

bool executable(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

/// The last non-empty line of a text file (ffmpeg's error), or "".
std::string lastLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
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

std::filesystem::path findFfmpeg() {
  if (const char* env = std::getenv("TALLOW_FFMPEG"); env && *env) return executable(env) ? env : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / "ffmpeg";
    if (executable(candidate)) return candidate;
  }
  return {};
}

void checkVideoOutput(const std::filesystem::path& file) {
  if (!containerOf(file))
    throw InputError("--video: " + file.string() + ": unknown video container (use .mp4, .mov, .mkv or .webm)");
  if (findFfmpeg().empty())
    throw InputError("--video: ffmpeg is not installed (apt-get install ffmpeg, or set TALLOW_FFMPEG to its path)");
}

void writeVideo(const std::filesystem::path& file, int width, int height, double fps, int count,
                const std::function<std::vector<std::uint8_t>(int)>& frame) {
  checkVideoOutput(file);
  const Container& container = *containerOf(file);
  const std::string ffmpeg = findFfmpeg().string();
  gpu::writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    const std::filesystem::path log = tmp.string() + ".log";
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.17g", fps);
    std::vector<std::string> args = {ffmpeg, "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                                     "-f", "rawvideo", "-pix_fmt", "rgb24",
                                     "-s", std::to_string(width) + "x" + std::to_string(height),
                                     "-r", rate, "-i", "pipe:0",
                                     "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"};
    args.insert(args.end(), container.codec.begin(), container.codec.end());
    args.insert(args.end(), {"-f", container.format, tmp.string()});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0) throw std::runtime_error("cannot write " + file.string() + ": pipe: " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[0], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipeFds[0]);
    if (spawned != 0) {
      ::close(pipeFds[1]);
      throw std::runtime_error("cannot write " + file.string() + ": cannot run " + ffmpeg + ": " + std::strerror(spawned));
    }
    // A dying ffmpeg must not kill us with SIGPIPE: the failed write is reported instead.
    struct sigaction ignore {}, previous {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ignore, &previous);
    bool fed = true;
    const auto finish = [&] {
      ::close(pipeFds[1]);
      sigaction(SIGPIPE, &previous, nullptr);
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return status;
    };
    int status = 0;
    try {
      for (int i = 0; i < count && fed; ++i) {
        const std::vector<std::uint8_t> rgb = frame(i);
        fed = writeAll(pipeFds[1], rgb.data(), rgb.size());
      }
    } catch (...) {
      ::kill(pid, SIGTERM);
      finish();
      std::error_code ec;
      std::filesystem::remove(log, ec);
      throw;
    }
    status = finish();
    const std::string error = lastLine(log);
    std::error_code ec;
    std::filesystem::remove(log, ec);
    if (!fed || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error("cannot write " + file.string() + ": ffmpeg failed" + (error.empty() ? "" : ": " + error));
  });
}

}  // namespace tallow::app
