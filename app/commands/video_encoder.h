#pragma once
// `capture --video FILE`: the captured sequence as a video, encoded by ffmpeg (a separate program,
// found on PATH, or $TALLOW_FFMPEG), fed raw 8-bit sRGB frames on a pipe — the same tone-mapped
// pixels as the PNG frames. The file is written atomically (temporary name, then renamed).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace tallow::app {

/// The ffmpeg the encoder will run: $TALLOW_FFMPEG if set, else `ffmpeg` on PATH; empty if none.
std::filesystem::path findFfmpeg();

/// Checks, before anything is rendered, that ffmpeg is installed and that the file's extension is a
/// container we encode (.mp4, .mov, .mkv: H.264; .webm: VP9). Throws InputError with one line.
void checkVideoOutput(const std::filesystem::path& file);

/// Encodes `count` frames of width × height at `fps`; `frame(i)` returns frame i as RGB bytes, top
/// row first (toneMappedRgb8). Odd sizes are padded by one black row or column (H.264 needs even
/// ones). Throws std::runtime_error `cannot write FILE: <ffmpeg's last error line>` on failure.
void writeVideo(const std::filesystem::path& file, int width, int height, double fps, int count,
                const std::function<std::vector<std::uint8_t>(int)>& frame);

}  // namespace tallow::app
