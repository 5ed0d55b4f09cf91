#pragma once
// The view window's Dear ImGui panel: preset picker, playback (play, pause, scrub, loop, speed),
// camera reset, feedback (per-pass GPU ms as a rolling graph, wall ms, accumulated frames, GPU
// memory, triangles, the frame plan), the debug view, saving (screenshot PNG / EXR, preset), and
// every registry parameter (app/view/view_param_widgets.h).
#include <deque>
#include <map>
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
};

/// What the window tells the panel about the last frame.
struct ViewFeedback {
  ViewSession::Frame frame;
  std::size_t triangles = 0;  ///< sampled a few times a second (counting stalls the GPU)
  std::string debugNote;      ///< why the debug view shows the final image instead
  std::string status;         ///< the last save or load: "wrote x.png", or its error
  bool statusIsError = false;
};

class ViewPanel {
 public:
  /// Adds the frame to the rolling timing graph.
  void record(const ViewSession::Frame& frame);
  /// Builds the panel (between ImGuiLayer::beginFrame and endFrame) for a window of width × height;
  /// edits act on `session` and `debug`, file requests go to `requests`. Returns a status line to
  /// show (a load's error) or "".
  std::string draw(ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback, ViewRequests& requests,
                   int width, int height);
  /// Pixels from the window's left edge to the panel's right edge (0 when collapsed or moved away
  /// from the left edge): where debug views should not put what matters.
  int coveredLeft() const { return coveredLeft_; }

 private:
  std::string drawPreset(ViewSession& session);
  void drawPlayback(ViewSession& session);
  void drawFeedback(const ViewSession& session, const ViewFeedback& feedback);
  void drawTimingGraph();
  void drawDebugView(const ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback);
  void drawSave(const ViewSession& session, ViewRequests& requests);

  ParamWidgets params_;
  /// GPU ms of each pass over the last kHistory frames (NaN where it did not run), in first-seen order.
  std::vector<std::string> passNames_;
  std::map<std::string, std::deque<float>> history_;
  std::deque<float> wallHistory_;
  std::string saveBase_;
  std::string savedFor_;  ///< the preset saveBase_ was named after
  int coveredLeft_ = 0;
};

}  // namespace tallow::app
