#pragma once
// `capture --video FILE`: the captured sequence as a video, encoded by ffmpeg (a separate program,
// found on PATH, or $TALLOW_FFMPEG), fed raw 8-bit sRGB frames on a pipe as they are rendered — the
// same tone-mapped pixels as the PNG frames — so that no frame waits in memory. ffmpeg writes a
// temporary file that becomes FILE only when it finished cleanly. ffmpeg runs in a process group of
// its own, so that a Ctrl-C at the terminal reaches Tallow alone, which then closes the video with
// the frames it has.
#include <signal.h>
#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/atomic_file.h"

namespace tallow::app {

/// The ffmpeg the encoder will run: $TALLOW_FFMPEG if set, else `ffmpeg` on PATH; empty if none.
std::filesystem::path findFfmpeg();

/// Checks, before anything is rendered, that ffmpeg is installed and that the file's extension is a
/// container we encode (.mp4, .mov, .mkv: H.264; .webm: VP9). Throws InputError with one line.
void checkVideoOutput(const std::filesystem::path& file);

/// One video being encoded. Odd sizes are padded by one black row or column (H.264 needs even
/// ones). Errors throw std::runtime_error `cannot write FILE: <ffmpeg's last error line>`.
class VideoEncoder {
 public:
  /// Starts ffmpeg for frames of width × height at `fps` frames per second.
  VideoEncoder(const std::filesystem::path& file, int width, int height, double fps);
  /// Without finish(): stops ffmpeg and removes its temporary file (no partial video is left).
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// One frame: RGB bytes, top row first (toneMappedRgb8), width × height × 3 of them.
  void add(std::span<const std::uint8_t> rgb);
  /// Closes the stream, waits for ffmpeg and renames the video onto its name.
  void finish();
  int frames() const { return frames_; }

 private:
  int wait();
  void abort();

  std::filesystem::path file_, log_;
  std::unique_ptr<gpu::PendingFile> output_;
  std::size_t frameBytes_ = 0;
  pid_t pid_ = -1;
  int pipe_ = -1;
  struct sigaction previousSigpipe_ {};
  bool fed_ = true;
  int frames_ = 0;
};

}  // namespace tallow::app
