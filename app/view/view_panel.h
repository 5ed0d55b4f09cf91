#pragma once
// The view window's Dear ImGui panel, along the window's left edge at full height, its width
// dragged at its right edge (the image keeps the rest of the window, app/view/view_layout.h):
// preset picker, playback (play, pause, scrub, loop, speed), camera reset, undo and redo, the
// hotkeys, feedback (per-pass GPU ms and the frame's wall time over the last seconds on a log
// scale, accumulated frames, GPU memory, triangles, the frame plan), the debug view, saving
// (numbered screenshots PNG / EXR, preset), and every registry parameter
// (app/view/view_param_widgets.h).
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/view/view_param_widgets.h"
#include "app/view/view_session.h"
#include "sss/debug_view.h"

namespace tallow::app {

/// Files the panel (or a script) asked for, written by the window after the frame is drawn.
struct ViewRequests {
  std::vector<std::string> screenshots;  ///< .png: the window; .exr: the radiance
  std::vector<std::string> presets;
  bool undo = false, redo = false;  ///< the panel's undo and redo buttons
};

/// What the window tells the panel about the last frame.
struct ViewFeedback {
  ViewSession::Frame frame;
  /// Sampled a few times a second once the GPU has the count (nothing before the first).
  std::optional<std::size_t> triangles;
  std::string debugNote;      ///< why the debug view shows the final image instead
  std::string status;         ///< the last save, load or undo: "wrote x.png", or its error
  bool statusIsError = false;
  double stepFps = 30.0;      ///< frames per second of ← and →
  /// Playing by wall time with frames longer than --max-step: the share of real time the animation
  /// plays at (the clock's step over the frame's wall time, < 1); 1 when not behind.
  double realTimeShare = 1.0;
  /// The camera or a widget moved this frame: a preview that holds the progressive passes.
  bool preview = false;
};

/// The radiosity maps' accumulation while it runs: frames done of sss.frames, and an estimate of
/// the time left from the frames' wall time (`frameMs`, the last frame's); nothing once complete, or
/// where the method keeps no maps.
struct AccumulationProgress {
  int done = 0, total = 0;
  double secondsLeft = -1.0;  ///< negative: no estimate yet (no frame timed)
  /// "accumulating 5 of 64 frames, about 4 min 05 s left".
  std::string text() const;
};
std::optional<AccumulationProgress> accumulationProgress(const ViewSession& session, double frameMs);

/// The base name the panel saves under by default: "tallow-<preset>" (numbered: -0001.png, …).
std::string defaultSaveBase(const std::string& presetName);

class ViewPanel {
 public:
  /// The panel's width when the window opens, in pixels, and its bounds when dragged.
  static constexpr float kDefaultWidth = 420.0f;
  static constexpr float kMinWidth = 260.0f;
  /// At most this share of the window: the image keeps the rest.
  static constexpr float kMaxShare = 0.7f;

  /// Adds the frame to the timing graph.
  void record(const ViewSession::Frame& frame);
  /// Builds the panel (between ImGuiLayer::beginFrame and endFrame) in a window of width × height
  /// pixels; edits act on `session` and `debug`, file and undo requests go to `requests`. Returns a
  /// status line to show (a load's error) or "".
  std::string draw(ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback, ViewRequests& requests,
                   int width, int height);
  /// The panel's width after the last draw (the user may have dragged it), in pixels.
  int width() const { return width_; }
  /// Where saved files go ("tallow-<preset>" until the user types another), numbered on saving.
  const std::string& saveBase(const std::string& presetName);

 private:
  std::string drawPreset(ViewSession& session);
  void drawPlayback(ViewSession& session, ViewRequests& requests, const ViewFeedback& feedback);
  void drawFeedback(const ViewSession& session, const ViewFeedback& feedback);
  void drawTimingGraph();
  void drawDebugView(const ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback);
  void drawSave(const ViewSession& session, ViewRequests& requests);

  ParamWidgets params_;
  /// The timing graph's frames: when each was recorded (seconds on a steady clock) and its wall
  /// time; GPU ms of each pass (NaN where it did not run), passes in first-seen order.
  std::deque<double> times_;
  std::deque<float> wallHistory_;
  std::vector<std::string> passNames_;
  std::map<std::string, std::deque<float>> history_;
  std::string saveBase_;
  std::string savedFor_;  ///< the preset saveBase_ was named after
  int width_ = static_cast<int>(kDefaultWidth);
};

}  // namespace tallow::app
