#pragma once
// The frame plan: the passes a frame runs, in order — the field objects' isosurfaces, the shadow
// maps, the frame's translucency method's passes, the camera pass, a candle's flame over it — each
// with why this scene needs it. The objects live as long as the plan and keep what they track between frames.
#include <memory>
#include <string>
#include <vector>

#include "sss/flame_pass.h"
#include "sss/frame_passes.h"
#include "sss/translucency_method.h"

namespace tallow::sss {

/// A pass as the plan lists it (stats.json "plan", `--explain`).
struct PlannedPass {
  std::string name;    ///< as in stats.json: "shadow.directional", "surface", …
  std::string reason;  ///< why this scene needs it
  PassIo io;           ///< what it reads and writes
};

/// The plan as `--explain` prints it: per pass "<prefix>pass NAME  REASON", then its reads (and
/// the inputs that pace it) and writes on an indented line.
std::string formatPlan(const std::vector<PlannedPass>& plan, const std::string& prefix = "");

/// One object of each translucency method, in a fixed order (the camera pass's texture units
/// follow it). A new method is one more line here.
std::vector<std::unique_ptr<TranslucencyMethod>> makeTranslucencyMethods();

class FramePlan {
 public:
  FramePlan();  ///< no GL: the plan can be listed before a context exists

  /// The method `state.settings.sss.method` selects.
  TranslucencyMethod& method(const FrameState& state);
  /// The passes of a frame in `state`, in the order they run.
  std::vector<Pass*> passes(const FrameState& state);
  /// passes(state) with their reasons.
  std::vector<PlannedPass> describe(const FrameState& state);

 private:
  FieldSamplePass fieldSample_;
  FieldExtractPass fieldExtract_;
  DirectionalShadowPass directionalShadow_;
  PointShadowPass pointShadow_;
  std::vector<std::unique_ptr<TranslucencyMethod>> methods_;
  CameraPass camera_;
  FlamePass flame_;
  StillAveragePass still_;
  BloomPass bloom_;
  LocalExposurePass localExposure_;
};

}  // namespace tallow::sss
