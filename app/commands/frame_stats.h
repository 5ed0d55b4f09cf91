#pragma once
// stats.json: what ran, on which GL, how long each pass took, and every parameter's value; where it
// came from (provenance.h) and whether the run is complete. The JSON of one frame, of the run and of
// the frames' summary; app/commands/stats_writer.h writes them as the run goes.
#include <nlohmann/json.hpp>

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "app/config/config.h"
#include "gpu/gl_context.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"
#include "sss/renderer.h"

namespace tallow::app {

struct FrameRecord {
  int index = 0;
  double timeS = 0.0;
  /// CPU wall time of the frame: capture, from its start to the next frame's (rendering overlaps
  /// the writing of the frame before); the window, the render call's.
  double wallMs = 0.0;
  sss::FrameTimings gpu;
  /// gpu::relativeChange of the receivers' radiance against the frame before (NaN: first frame).
  double receiverChange = std::numeric_limits<double>::quiet_NaN();
  /// The same over the translucent objects' pixels (NaN: first frame, or none in view).
  double translucentChange = std::numeric_limits<double>::quiet_NaN();
  /// The frame against capture's --reference (referenceErrorRecord; null without one).
  nlohmann::json reference;
  std::vector<glm::vec3> pointLights;  ///< where the point lights stood (flames move with their candle)
  std::vector<glm::vec3> pointLightIntensities;  ///< and their intensity [W/sr] (a flame's flickers)
  /// Parameters whose value changed since the frame before (--script, the view's panel), {key: value}.
  nlohmann::json changed = nlohmann::json::object();
  /// The radiosity maps after this frame (null when none): K, F accumulated, their bytes.
  nlohmann::json sss;
  /// The process's resident memory after the frame (residentBytes; 0: not measured).
  std::size_t rssBytes = 0;
  /// The view window's layout and state (app/view/view_layout.h); null for capture.
  nlohmann::json view;
  /// What the image files cannot hold as it is (pixelsRecord; null when not counted).
  nlohmann::json pixels;
  /// Render targets read back for the frame (gpu::targetReads; −1: not counted).
  std::int64_t targetReads = -1;
};

/// The process's resident set now, in bytes (/proc/self/statm; 0 where it cannot be read).
std::size_t residentBytes();

/// stats.json's per-frame "reference_error" against a reference (gpu::imageError over the pixels the
/// reference's standard-error image marks): {"rel_rmse", "mean_ratio", "upper_mean_ratio",
/// "lower_mean_ratio" (the object's upper and lower rows; null when it spans one row), "fireflies"
/// and "reference_fireflies" (gpu::fireflyCount of the image and of the reference),
/// "fireflies_not_in_reference" (the image's fireflies at pixels where the reference has none, at most
/// 32: {"x", "y", "channel", "over_median": the channel over its 5×5 median, "reference_over_median":
/// the reference's own ratio there, "over_reference": image / reference in that channel}), "pixels",
/// "non_finite": {"image", "reference": object pixels with a NaN or infinite channel, "left_out": those
/// not compared (with options.skipNonFinite)}}. With non-finite pixels compared the errors are null.
nlohmann::json referenceErrorRecord(const gpu::Image& image, const gpu::Image& reference, const gpu::Image& standardError,
                                    const gpu::ImageErrorOptions& options = {});


/// stats.json's per-frame "pixels": {"non_finite": NaN or ±Inf pixels, "beyond_half": finite
/// pixels beyond half-float's range, "exr": "half" or "float", the channels the EXR was written
/// with: float when asked for, or when a pixel is beyond half's range (gpu::writeExr)}.
nlohmann::json pixelsRecord(const gpu::PixelCensus& census, bool floatAsked);

/// The translucent objects' pixels (`translucent`, a mask from Renderer::translucentMask) and how
/// many of them the tone map shows near white, all three channels ≥ 0.98 (`translucent_clipped`):
/// a lit wax that reads as clipped white rather than warm (issue 16, point 5).
nlohmann::json clippedRecord(const gpu::Image& image, const std::vector<std::uint8_t>& translucent,
                             const gpu::ToneMapSettings& toneMap);

/// The radiosity maps' state after a frame, for FrameRecord::sss (null when the renderer has none).
nlohmann::json mapsRecord(const sss::Renderer& renderer);
/// {key: new value} of every parameter whose value differs between two registry snapshots.
nlohmann::json changedParameters(const nlohmann::json& before, const nlohmann::json& after);

struct RunRecord {
  std::string command;
  std::string presetName, presetPath;
  gpu::GlBackend backend = gpu::GlBackend::OsMesa;
  gpu::GlInfo gl;
  nlohmann::json glLimits;  ///< glLimitsJson() of the run's context (null: not recorded)
  int width = 0, height = 0;
  std::size_t triangles = 0;
  std::size_t gpuBytes = 0;
  std::vector<sss::PlannedPass> plan;
  int framesWritten = 0;  ///< the frames recorded so far (StatsWriter counts them)
  int accumulate = 1;  ///< renders per frame at its time (capture --accumulate); timings sum them
  nlohmann::json parameters;
  nlohmann::json sss;  ///< radiosity maps of the last frame (null when the method does not run)
  int framesRequested = 0;  ///< frames asked for (capture --frames; view --frames, 0: until closed)
  /// "running" (frames remain), "complete", "interrupted" (SIGINT, SIGTERM or SIGHUP; the frames
  /// listed are written whole) or "failed" (stopReason says why).
  std::string state = "complete";
  std::string stopReason;  ///< interrupted: the signal's name; failed: the error's line
};

double median(std::vector<double> values);

/// One entry of stats.json's "frames" (a line of the run's frames.jsonl while it runs).
nlohmann::json frameJson(const FrameRecord& frame);

/// stats.json without its "frames" and "summary": the command, its state, provenance, GL, the plan,
/// the parameters and the maps.
nlohmann::json runJson(const RunRecord& run);

/// stats.json's "summary", built from the frames' JSON one at a time (medians of the wall, GPU, CPU
/// and thread times, in total and per pass; the receivers' mean change).
class FrameSummary {
 public:
  void add(const nlohmann::json& frame);
  nlohmann::json json();

 private:
  std::size_t frames_ = 0;
  std::vector<double> wall_, gpuTotal_, cpuTotal_, threadTotal_, changes_;
  std::map<std::string, std::vector<double>> perPass_, perPassCpu_, perPassThread_;
  /// Per pass, per pipeline counter (vertex, geometry, primitives, fragment, compute): each frame's count.
  std::map<std::string, std::map<std::string, std::vector<double>>> invocations_;
  nlohmann::json invocationMedians();
};

}  // namespace tallow::app
