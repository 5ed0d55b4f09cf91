#include "app/view/view_command.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "app/commands/capture_command.h"
#include "app/commands/frame_stats.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/playback/scene_controls.h"
#include "app/playback/view_script.h"
#include "app/view/view_mouse.h"
#include "app/view/view_panel.h"
#include "app/view/view_session.h"
#include "gpu/atomic_file.h"
#include "gpu/image_io.h"
#include "gpu/imgui_layer.h"
#include "gpu/readback.h"
#include "sss/debug_view_pass.h"

namespace tallow::app {

namespace {
/// Renders of the one frame that `view` without a display captures: a still frame is what a user
/// looks at, so the progressive methods accumulate as in a paused window instead of showing one
/// frame's noise (the candle's maps restart every frame while it melts).
constexpr int kFallbackAccumulate = 16;

using Clock = std::chrono::steady_clock;
/// Seconds between two counts of the triangles (the count waits for the GPU).
constexpr double kTriangleSampleS = 0.25;

void checkScreenshotName(const std::string& file, const std::string& option) {
  checkOutputFile(option, file, {".png", ".exr"});
}

/// Everything the command line names, checked before a window opens: one line and no window.
struct CheckedInputs {
  std::optional<Script> script;
  std::optional<gpu::Image> reference;
  sss::DebugView debug;
  int width = 0, height = 0;
};

CheckedInputs checkInputs(const ViewOptions& options) {
  if (options.frames < 0) throw InputError("--frames: must not be negative");
  if (!(options.fps >= 0.0) || !std::isfinite(options.fps)) throw InputError("--fps: must be a positive number");
  if (options.timeS) checkTime("--time", *options.timeS);
  CheckedInputs in;
  const LoadedScene loaded = loadScene(options.scene);  // the preset's and --set's errors, first
  in.width = loaded.config.render.width;
  in.height = loaded.config.render.height;
  for (const std::string& s : options.screenshots) checkScreenshotName(s, "--screenshot");
  if (!options.savePreset.empty()) checkOutputFile("--save-preset", options.savePreset);
  if (!options.stats.empty()) checkOutputFile("--stats", options.stats);
  if (!options.debugView.empty()) {
    try {
      in.debug = sss::parseDebugView(options.debugView);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--debug-view: ") + e.what());
    }
  }
  if (!options.script.empty()) {
    in.script = loadScript(options.script, parameterRegistry(loaded.materials));
    for (const ScriptCommand& c : in.script->commands) {
      if (options.frames > 0 && c.frame >= options.frames)
        throw InputError(c.where + ": frame " + std::to_string(c.frame) + " is beyond --frames " +
                         std::to_string(options.frames));
      if (c.action == ScriptAction::Screenshot) checkScreenshotName(c.path, c.where + ": screenshot");
      if (c.action == ScriptAction::SavePreset) checkOutputFile(c.where + ": save-preset", c.path);
    }
  }
  if (!options.reference.empty()) {
    try {
      in.reference = gpu::readExr(options.reference);
    } catch (const std::exception& e) {
      throw InputError(std::string("--reference: ") + e.what());
    }
    if (in.reference->width != in.width || in.reference->height != in.height)
      throw InputError("--reference: " + options.reference + " is " + std::to_string(in.reference->width) + "x" +
                       std::to_string(in.reference->height) + ", the image " + std::to_string(in.width) + "x" +
                       std::to_string(in.height) + " (give --size " + std::to_string(in.reference->width) + "x" +
                       std::to_string(in.reference->height) + ")");
  }
  return in;
}

/// Writes the window (.png, as shown) or the radiance (.exr) of the frame just drawn.
void saveScreenshot(const std::string& file, const ViewSession& session, int width, int height) {
  if (std::filesystem::path(file).extension() == ".exr") session.saveRadiance(file);
  else gpu::writePngRgb8(file, width, height, gpu::readWindowRgb8(width, height));
}

}  // namespace

int runView(const ViewOptions& options) {
  CheckedInputs inputs = checkInputs(options);
  if (!gpu::displayAvailable()) {
    // What only a window makes (its screenshots, its stats, a scripted session) cannot fall back.
    const char* needsWindow = !options.screenshots.empty() ? "--screenshot"
                              : !options.savePreset.empty() ? "--save-preset"
                              : !options.script.empty()     ? "--script"
                              : !options.stats.empty()      ? "--stats"
                                                            : nullptr;
    if (needsWindow)
      throw InputError(std::string("no display: ") + needsWindow +
                       " needs the window (run under a display or Xvfb; tallow capture writes frames headless)");
    std::fprintf(stderr, "tallow: no display; capturing %s into %s/ instead\n",
                 options.scene.preset.empty() ? defaultPresetName().c_str() : options.scene.preset.c_str(),
                 options.fallbackOutDir.c_str());
    CaptureOptions capture;
    capture.scene = options.scene;
    capture.outDir = options.fallbackOutDir;
    capture.accumulate = kFallbackAccumulate;
    return runCapture(capture);
  }

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::GlBackend::Glfw;
  contextOptions.windowWidth = inputs.width;
  contextOptions.windowHeight = inputs.height;
  contextOptions.title = "Tallow — " + (options.scene.preset.empty() ? defaultPresetName() : options.scene.preset);
  auto context = gpu::GlContext::create(contextOptions);
  GLFWwindow* window = context->window();
  const gpu::ShaderLibrary shaders = makeShaderLibrary(options.scene.shaderDir);
  ViewSession session(options.scene, shaders);
  gpu::ImGuiLayer imgui(window);
  sss::DebugViewPass debugPass(shaders);
  if (inputs.reference) debugPass.setReference(*inputs.reference);
  sss::DebugView debug = inputs.debug;
  ViewPanel panel;
  ViewFeedback feedback;
  if (options.scene.explain)
    for (const auto& p : sss::Renderer::plan(session.config().scene, session.config().render))
      std::printf("pass %-20s %s\n", p.name.c_str(), p.reason.c_str());

  if (options.timeS) session.playback().seek(*options.timeS);
  if (options.paused) session.playback().pause();
  int generation = session.generation();
  int clockFrame = 0;  // frames on this scene's clock (--fps)

  RunRecord run;
  run.command = "view";
  run.backend = context->backend();
  run.gl = context->info();
  run.plan = sss::Renderer::plan(session.config().scene, session.config().render);
  run.parameters = session.registry().snapshot(session.config());
  nlohmann::json parameters = run.parameters;

  auto last = Clock::now();
  auto lastTriangles = last - std::chrono::hours(1);
  int width = 0, height = 0;
  for (int frame = 0; !glfwWindowShouldClose(window) && (options.frames == 0 || frame < options.frames); ++frame) {
    glfwPollEvents();
    if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS && !imgui.wantsKeyboard()) break;
    glfwGetFramebufferSize(window, &width, &height);
    if (width == 0 || height == 0) {  // minimised
      --frame;
      glfwWaitEvents();
      continue;
    }
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    if (session.generation() != generation) {  // the panel loaded another preset
      generation = session.generation();
      clockFrame = 0;
    }
    if (options.fps > 0.0) session.playback().setFrame(clockFrame, options.fps);
    else if (frame > 0) session.playback().advance(dt);
    ++clockFrame;

    // The script's commands for this frame, then the panel and the mouse: all take effect in the
    // frame rendered next.
    ViewRequests requests;
    std::string scriptWhere;
    bool quit = false;
    if (inputs.script)
      for (const ScriptCommand* c : inputs.script->at(frame)) {
        if (applyScriptCommand(*c, session.config(), session.registry(), session.playback())) {
          scriptWhere = c->where;
          continue;
        }
        if (c->action == ScriptAction::Debug) debug = c->debug;
        if (c->action == ScriptAction::Screenshot) requests.screenshots.push_back(c->path);
        if (c->action == ScriptAction::SavePreset) requests.presets.push_back(c->path);
        if (c->action == ScriptAction::Quit) quit = true;
      }
    if (quit) break;
    imgui.beginFrame();
    if (!options.hidePanel) {
      const std::string status = panel.draw(session, debug, feedback, requests, width, height);
      if (!status.empty()) {
        feedback.status = status;
        feedback.statusIsError = true;
      }
      if (session.generation() != generation) {  // a preset was loaded: start its clock as asked
        generation = session.generation();
        clockFrame = 0;
        feedback.status = "loaded " + session.presetName();
        feedback.statusIsError = false;
      }
    }
    mouseCamera(session, height);
    // A size set in the panel or script resizes the window (the next frame renders at it).
    const Config& c = session.config();
    if (c.render.width != width || c.render.height != height) glfwSetWindowSize(window, c.render.width, c.render.height);

    feedback.frame = session.render(width, height);
    if (!feedback.frame.refused.empty() && !scriptWhere.empty())
      throw InputError(scriptWhere + ": " + feedback.frame.refused);
    panel.record(feedback.frame);
    feedback.debugNote = debugPass.render(debug, session.renderer(), session.config().scene, session.config().render, 0,
                                          width, height, options.hidePanel ? 0 : panel.coveredLeft());
    imgui.endFrame();
    if (now - lastTriangles > std::chrono::duration<double>(kTriangleSampleS)) {
      feedback.triangles = session.renderer().triangleCount();
      lastTriangles = now;
    }

    if (options.frames > 0 && frame == options.frames - 1) {
      for (const std::string& s : options.screenshots) requests.screenshots.push_back(s);
      if (!options.savePreset.empty()) requests.presets.push_back(options.savePreset);
    }
    for (const std::string& file : requests.screenshots) {
      try {
        saveScreenshot(file, session, width, height);
        feedback.status = "wrote " + file;
        feedback.statusIsError = false;
      } catch (const std::exception& e) {
        if (!inputs.script && options.frames == 0) {  // interactive: say it in the panel
          feedback.status = e.what();
          feedback.statusIsError = true;
        } else {
          throw;
        }
      }
    }
    for (const std::string& file : requests.presets) {
      try {
        session.savePreset(file);
        feedback.status = "wrote " + file;
        feedback.statusIsError = false;
      } catch (const std::exception& e) {
        if (!inputs.script && options.frames == 0) {
          feedback.status = e.what();
          feedback.statusIsError = true;
        } else {
          throw;
        }
      }
    }

    if (!options.stats.empty()) {
      FrameRecord record;
      record.index = frame;
      record.timeS = feedback.frame.timeS;
      record.wallMs = feedback.frame.wallMs;
      record.gpu = feedback.frame.gpu;
      nlohmann::json now = session.registry().snapshot(session.config());
      record.changed = changedParameters(parameters, now);
      parameters = std::move(now);
      record.sss = mapsRecord(session.renderer());
      run.frames.push_back(std::move(record));
    }
    glfwSwapBuffers(window);
  }

  if (!options.stats.empty()) {
    run.presetName = session.presetName();
    run.presetPath = session.presetPath().string();
    run.width = width;
    run.height = height;
    run.gpuBytes = session.renderer().gpuBytes();
    run.triangles = session.renderer().triangleCount();
    gpu::writeTextFileAtomically(options.stats, toJson(run).dump(2) + "\n");
  }
  return 0;
}

}  // namespace tallow::app
