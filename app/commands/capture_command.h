#pragma once
// `tallow capture`: renders frames headless and writes DIR/frame_NNNN.png (tone-mapped sRGB),
// DIR/frame_NNNN.exr (linear) and DIR/stats.json. Bad input is found before the first frame (one
// line, nothing written); then each frame is written as soon as it is done, stats.json rewritten
// after it, so memory does not grow with the frame count. SIGINT or SIGTERM ends the run after the
// frame in hand, with every file whole and the exit status 130 or 143 (app/commands/interrupt.h).
// Each file is written whole or not at all.
#include <optional>
#include <string>

#include "app/config/setup.h"

namespace tallow::app {

/// Upper bound of capture --accumulate (a guard against a typo that would run for hours).
inline constexpr int kMaxAccumulate = 4096;

struct CaptureOptions {
  SceneOptions scene;
  std::string gl = "osmesa";
  std::string outDir;
  int frames = 1;
  std::optional<double> timeS;  ///< animation time of the first frame; unset: the preset's start_s
  double fps = 30.0;
  bool exrFloat = false;  ///< 32-bit float EXR channels instead of half
  std::string script;     ///< timed parameter changes (app/playback/view_script.h); empty: none
  std::string video;      ///< also encode the frames into this video with ffmpeg; empty: none
  /// Renders per written frame, all at its time: the progressive methods accumulate over them as
  /// in a paused window, and the last is written (1: every render is written, the sequence as played).
  int accumulate = 1;
  /// --reference REF.exr (REF_stderr.exr beside it): each frame's error against it in stats.json
  /// (`reference_error`); empty: none.
  std::string reference;
};

/// Returns the process exit code (0; 130 or 143 when a signal stopped it); throws InputError /
/// ContextError / ShaderError / runtime_error with one line on failure (the frames before it stay,
/// with stats.json saying where the run stopped).
int runCapture(const CaptureOptions& options);

}  // namespace tallow::app
