#include "app/view/view_command.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>
#include <tuple>

#include "app/commands/capture_command.h"
#include "app/commands/frame_stats.h"
#include "app/commands/interrupt.h"
#include "app/commands/provenance.h"
#include "app/commands/stats_writer.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/playback/scene_controls.h"
#include "app/playback/view_script.h"
#include "app/view/numbered_file.h"
#include "app/view/render_worker.h"
#include "app/view/view_canvas.h"
#include "app/view/view_hotkeys.h"
#include "app/view/view_layout.h"
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
/// With the render thread, the window redraws at least this often without input (the panel's
/// clock and graphs), and at once on input or a finished frame.
constexpr double kPanelRedrawS = 0.1;
/// Frames per second of the ← and → steps without --fps (capture's default rate).
constexpr double kStepFps = 30.0;
/// --max-step's largest value: a cap beyond a minute is a typo.
constexpr double kMaxStepLimitS = 60.0;
/// The window is at least this tall, so that the panel beside a small image has room.
constexpr int kMinWindowHeight = 480;
/// At most this share of the screen's work area, when the image and panel would be larger (the
/// image is then shown scaled down).
constexpr double kMaxScreenShare = 0.95;

/// The window's size for an image of width × height beside the panel (or alone), on this screen:
/// with the panel, as tall as the screen allows (the panel's parameters are a long list; a window
/// as short as a small image hid them a thousand pixels down), the image centred beside it.
std::pair<int, int> windowSizeFor(int width, int height, bool panel) {
  int w = width + (panel ? static_cast<int>(ViewPanel::kDefaultWidth) : 0);
  int h = std::max(height, panel ? kMinWindowHeight : 1);
  if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) {
    int x = 0, y = 0, areaW = 0, areaH = 0;
    glfwGetMonitorWorkarea(monitor, &x, &y, &areaW, &areaH);
    if (areaW > 0 && areaH > 0) {
      const int maxW = static_cast<int>(kMaxScreenShare * areaW), maxH = static_cast<int>(kMaxScreenShare * areaH);
      w = std::min(w, maxW);
      h = panel ? maxH : std::min(h, maxH);
    }
  }
  return {w, h};
}

/// A screenshot's folder is created when it is saved, as capture's --out is (issue 40).
void checkScreenshotName(const std::string& file, const std::string& option) {
  checkOutputFileInNewFolder(option, file, {".png", ".exr"});
}

/// The difference view compares with --reference: without it there is nothing to show.
void checkDebugViewHasReference(const sss::DebugView& view, const ViewOptions& options, const std::string& where) {
  if (view.kind == sss::DebugViewKind::Difference && options.reference.empty())
    throw InputError(where + ": the difference view needs --reference REF.exr (e.g. from `tallow reference`)");
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
  if (options.fps != 0.0) checkFps("--fps", options.fps);  // 0: not given (wall time)
  if (options.timeS) checkTime("--time", *options.timeS);
  if (!std::isfinite(options.maxStepS) || options.maxStepS < 0.0 || options.maxStepS > kMaxStepLimitS)
    throw InputError("--max-step: must be in [0, " + formatNumber(kMaxStepLimitS) + "] seconds (0: no cap)");
  CheckedInputs in;
  const LoadedScene loaded = loadScene(options.scene);  // the preset's and --set's errors, first
  in.width = loaded.config.render.width;
  in.height = loaded.config.render.height;
  for (const std::string& s : options.screenshots) checkScreenshotName(s, "--screenshot");
  if (!options.savePreset.empty()) checkOutputFile("--save-preset", options.savePreset);
  // Both are saved after the last of --frames: without it the window would run until closed and a
  // test waiting for the file would hang.
  if (options.frames == 0 && (!options.screenshots.empty() || !options.savePreset.empty()))
    throw InputError(std::string(options.screenshots.empty() ? "--save-preset" : "--screenshot") +
                     ": saved after the last frame, so it needs --frames N (the panel's Save and the S key save "
                     "from a window left open)");
  if (!options.stats.empty()) checkOutputFile("--stats", options.stats);
  if (!options.debugView.empty()) {
    try {
      in.debug = sss::parseDebugView(options.debugView);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--debug-view: ") + e.what());
    }
    checkDebugViewHasReference(in.debug, options, "--debug-view " + options.debugView);
  }
  if (!options.script.empty()) {
    in.script = loadScript(options.script, parameterRegistry(loaded.materials));
    for (const ScriptCommand& c : in.script->commands) {
      if (options.frames > 0 && c.frame >= options.frames)
        throw InputError(c.where + ": frame " + std::to_string(c.frame) + " is beyond --frames " +
                         std::to_string(options.frames));
      if (c.action == ScriptAction::Screenshot) checkScreenshotName(c.path, c.where + ": screenshot");
      if (c.action == ScriptAction::Debug) checkDebugViewHasReference(c.debug, options, c.where + ": debug");
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

/// The notice of the first frame, centred in the window (between ImGui's beginFrame and endFrame).
void drawFirstFrameNotice(const std::string& preset) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->Size.x * 0.5f, viewport->Size.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::Begin("##startup", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  ImGui::Text("Tallow: compiling shaders and drawing the first frame of %s ...", preset.c_str());
  ImGui::TextDisabled("seconds on a GPU, up to a minute on a software renderer (llvmpipe)");
  ImGui::End();
}

/// One frame that says what the window is waiting for, drawn before the shaders compile.
void showStartupNotice(gpu::ImGuiLayer& imgui, ViewCanvas& canvas, GLFWwindow* window, const std::string& preset) {
  int width = 0, height = 0;
  glfwPollEvents();
  glfwGetFramebufferSize(window, &width, &height);
  imgui.beginFrame();
  drawFirstFrameNotice(preset);
  canvas.present(ViewLayout{}, width, height);  // the background alone
  imgui.endFrame();
  glfwSwapBuffers(window);
}

/// Writes the window (.png, as shown) or the radiance (.exr) of the frame just drawn.
void saveScreenshot(const std::string& file, const ViewSession& session, int width, int height) {
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder);  // checked writable before the window opened
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

  bool panelVisible = !options.hidePanel;
  // --frames and --script run in lockstep, one render per window frame, so that their frames are the
  // same on every machine; a window left open renders on a thread of its own and answers at once.
  bool lockstep = options.frames > 0 || inputs.script.has_value();
  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::GlBackend::Glfw;
  contextOptions.swapInterval = options.vsync ? 1 : 0;
  std::tie(contextOptions.windowWidth, contextOptions.windowHeight) = windowSizeFor(inputs.width, inputs.height, panelVisible);
  contextOptions.title = "Tallow — " + (options.scene.preset.empty() ? defaultPresetName() : options.scene.preset);
  auto context = gpu::GlContext::create(contextOptions);
  GLFWwindow* window = context->window();
  HotkeyQueue hotkeys(window);  // before ImGui's backend, which passes every key on to it
  gpu::ImGuiLayer imgui(window);
  ViewCanvas canvas;
  // Compiling the shaders and the first frame take seconds on llvmpipe: said at once, not a black window.
  showStartupNotice(imgui, canvas, window,
                    options.scene.preset.empty() ? defaultPresetName() : options.scene.preset);
  const gpu::ShaderLibrary shaders = makeShaderLibrary(options.scene.shaderDir);
  std::optional<RenderWorker> worker;
  if (!lockstep) {
    try {
      worker.emplace(*context, shaders, inputs.reference);
    } catch (const gpu::ContextError& e) {  // no second context: the window renders its frames itself
      std::fprintf(stderr, "tallow: %s; rendering in the window's thread\n", e.what());
      lockstep = true;
    }
  }
  ViewSession session(options.scene, shaders, lockstep);
  std::optional<sss::DebugViewPass> debugPass;  // lockstep: drawn here; else on the render thread
  if (lockstep) {
    debugPass.emplace(shaders);
    if (inputs.reference) debugPass->setReference(*inputs.reference);
  }
  sss::DebugView debug = inputs.debug;
  ViewPanel panel;
  ViewFeedback feedback;
  feedback.stepFps = options.fps > 0.0 ? options.fps : kStepFps;
  if (options.scene.explain)
    std::fputs(sss::formatPlan(sss::Renderer::plan(session.config().scene, session.config().render)).c_str(), stdout);

  if (options.timeS) session.playback().seek(*options.timeS);
  if (options.paused) session.playback().pause();
  int generation = session.generation();
  int clockFrame = 0;  // frames on this scene's clock (--fps)
  int renders = 0;     // frames rendered (the render thread's, or the window's in lockstep)
  int windowFrames = 0;  // pictures shown
  std::string shownTitle = contextOptions.title;
  std::vector<const ScriptCommand*> queuedCommands;  // the script's commands after a screenshot, run next
  // Where the debug view shown was asked for (--debug-view, a script's line) until a frame shows
  // it: a view that cannot be shown (map:99 with K = 12) is refused there, not shown as the image.
  std::string debugWhere = options.debugView.empty() ? "" : "--debug-view " + options.debugView;
  std::vector<std::string> radianceFiles;  // .exr screenshots for the render thread's next frame
  bool movedSinceJob = false;              // input moved since the last job: the next is a preview

  RunRecord run;
  run.command = "view";
  run.backend = context->backend();
  run.gl = context->info();
  run.glLimits = glLimitsJson();
  run.plan = sss::Renderer::plan(session.config().scene, session.config().render);
  run.parameters = session.registry().snapshot(session.config());
  run.framesRequested = options.frames;
  nlohmann::json parameters = run.parameters;
  const InterruptScope interruptScope;
  // --stats: each frame's record appended as it is done (memory flat however long the window is open).
  std::optional<StatsWriter> stats;
  if (!options.stats.empty()) stats.emplace(options.stats);
  std::deque<FrameRecord> pendingStats;
  const auto flushStats = [&](bool all) {
    while (!pendingStats.empty()) {
      // The render thread read its frames' times before handing them over; here they are read
      // without a wait unless the timer's ring is full.
      if (session.rendersHere()) {
        const bool mustWait = all || pendingStats.size() + 1 >= gpu::GpuTimer::kRing;
        if (!session.renderer().resolveTimings(pendingStats.front().gpu, mustWait) && !mustWait) break;
      }
      stats->append(run, pendingStats.front());
      pendingStats.pop_front();
    }
  };

  auto last = Clock::now();
  auto lastTriangles = last - std::chrono::hours(1);
  int width = 0, height = 0;
  int imageW = session.config().render.width, imageH = session.config().render.height;
  // Where the panel and a picture of `c`'s size lie in the window as it is now.
  const auto layoutFor = [&](const Config& c) {
    return layoutView(width, height, panelVisible ? panel.width() : 0, c.render.width, c.render.height);
  };
  // The animation clock before a render: by --fps, or by the wall time since the last render, at
  // most --max-step (a slow machine plays slower instead of skipping).
  const auto advanceClock = [&](bool hold) {
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    if (session.generation() != generation) {  // the panel loaded another preset
      generation = session.generation();
      clockFrame = 0;
    }
    feedback.realTimeShare = 1.0;
    if (hold) return;
    if (options.fps > 0.0) {
      session.playback().setFrame(clockFrame, options.fps);
    } else if (renders > 0) {
      const double step = cappedStep(dt, options.maxStepS);
      session.playback().advance(step);
      if (step < dt) feedback.realTimeShare = step / dt;
    }
    ++clockFrame;
  };
  // A frame's record in --stats, once it is rendered.
  const auto recordFrame = [&](int index, const ViewSession::Frame& frame, const Config& shown, bool playing,
                               bool preview, bool scriptStep) {
    FrameRecord record;
    record.index = index;
    record.timeS = frame.timeS;
    record.wallMs = frame.wallMs;
    record.gpu = frame.gpu;
    nlohmann::json now = session.registry().snapshot(shown);
    record.changed = changedParameters(parameters, now);
    parameters = std::move(now);
    record.sss = session.summary().mapsRecord;
    record.view = layoutJson(layoutFor(shown), width, height);
    record.view["playing"] = playing;
    record.view["real_time_share"] = feedback.realTimeShare;
    record.view["script_step"] = scriptStep;  // the rest of a frame's script after a screenshot
    record.view["preview"] = preview;  // input moved: refinement held
    record.view["panel_visible"] = panelVisible;
    record.view["can_undo"] = session.history().canUndo();
    record.view["can_redo"] = session.history().canRedo();
    record.view["render_thread"] = !lockstep;
    record.view["window_frames"] = windowFrames;  // pictures shown so far (more than renders on the render thread)
    // Written once the GPU has the frame's times (a frame or two later), so that the window never
    // waits on a query; only a GPU as far behind as the timer's ring keeps frames makes it wait.
    pendingStats.push_back(std::move(record));
    flushStats(false);
  };
  // The render thread's frame, taken: the panel, the title and the picture follow it.
  const auto takeResult = [&](RenderResult r) {
    if (r.generation != session.generation()) return;  // a scene replaced meanwhile
    if (!r.error.empty()) {
      feedback.status = r.error;
      feedback.statusIsError = true;
    }
    for (const std::string& file : r.wrote) {
      feedback.status = "wrote " + file;
      feedback.statusIsError = false;
    }
    if (r.slot < 0) return;
    ++renders;
    if (!r.frame.refused.empty()) session.restore(r.config);  // as ViewSession::render does
    session.setSummary(std::move(r.summary));
    feedback.frame = r.frame;
    feedback.debugNote = r.debugNote;
    if (r.triangles) feedback.triangles = r.triangles;
    panel.record(feedback.frame);
    if (!debugWhere.empty() && !feedback.debugNote.empty()) throw InputError(debugWhere + ": " + feedback.debugNote);
    debugWhere.clear();
    if (stats) recordFrame(renders - 1, feedback.frame, r.config, r.playing, r.preview, false);
  };
  // stats.json written whole: `state` empty keeps the writer's own (complete), else with the reason.
  const auto finishStats = [&](const std::string& state, const std::string& reason) {
    flushStats(true);
    run.presetName = session.presetName();
    run.presetPath = session.presetPath().string();
    run.width = session.config().render.width;
    run.height = session.config().render.height;
    run.gpuBytes = session.summary().gpuBytes;
    run.triangles = session.rendersHere() ? session.renderer().triangleCount() : feedback.triangles.value_or(0);
    if (!state.empty()) {
      run.state = state;
      run.stopReason = reason;
    }
    stats->finish(run);
  };
  // A failure during the run (a script line the scene refuses, a debug view it cannot show) ends
  // it with --stats written whole, saying where and why it stopped, as capture does.
  try {
    for (int frame = 0; options.frames == 0 || frame < options.frames; ++frame) {
      // On the render thread's pictures the window waits for input, a finished frame (the thread
      // posts an empty event) or the next redraw of the panel, whichever comes first.
      if (lockstep) glfwPollEvents();
      else glfwWaitEventsTimeout(kPanelRedrawS);
      // SIGINT, SIGTERM or SIGHUP (a closed terminal) end the window as its close button does, with
      // --stats written whole and saying so.
      if (glfwWindowShouldClose(window) || interrupted()) break;
      glfwGetFramebufferSize(window, &width, &height);
      if (width == 0 || height == 0) {  // minimised
        --frame;
        glfwWaitEvents();
        continue;
      }
      // A script's commands after a screenshot in the same frame run in a render of their own at the
      // same animation time, so that the screenshot shows the scene as the script stood at its line.
      const bool scriptStep = !queuedCommands.empty();
      if (lockstep) advanceClock(scriptStep);

      // The script's commands for this frame, the hotkeys (pressed since the last frame, then the
      // script's), then the panel and the mouse: all take effect in the frame rendered next.
      ViewRequests requests;
      std::string scriptWhere;
      bool scriptMovedCamera = false;
      bool quit = false;
      if (inputs.script) {
        std::vector<const ScriptCommand*> commands = scriptStep ? std::move(queuedCommands) : inputs.script->at(frame);
        queuedCommands.clear();
        for (std::size_t i = 0; i < commands.size(); ++i) {
          const ScriptCommand* c = commands[i];
          if (applyScriptCommand(*c, session.config(), session.registry(), session.playback())) {
            scriptWhere = c->where;
            // A scripted camera move is a step of a drag: the frame is a preview as the mouse's is.
            scriptMovedCamera |= c->action == ScriptAction::Orbit || c->action == ScriptAction::Pan ||
                                 c->action == ScriptAction::Zoom;
            continue;
          }
          if (c->action == ScriptAction::Debug) {
            debug = c->debug;
            debugWhere = c->where + ": debug";
          }
          if (c->action == ScriptAction::Screenshot) {
            requests.screenshots.push_back(c->path);
            queuedCommands.assign(commands.begin() + static_cast<std::ptrdiff_t>(i) + 1, commands.end());
            break;  // the rest after this frame's render
          }
          if (c->action == ScriptAction::SavePreset) requests.presets.push_back(c->path);
          if (c->action == ScriptAction::Key) hotkeys.push(c->hotkey);
          if (c->action == ScriptAction::Quit) quit = true;
        }
      }
      for (const Hotkey key : hotkeys.take()) {
        Playback& clock = session.playback();
        switch (key) {
          case Hotkey::PlayPause:
            clock.playing() ? clock.pause() : clock.play();
            break;
          case Hotkey::StepBack:
          case Hotkey::StepForward:
            clock.pause();
            clock.seek(clock.time() + (key == Hotkey::StepForward ? 1.0 : -1.0) / feedback.stepFps);
            break;
          case Hotkey::ResetCamera:
            session.resetCamera();
            break;
          case Hotkey::Screenshot:
            requests.screenshots.push_back(nextNumberedFile(panel.saveBase(session.presetName()), ".png").string());
            break;
          case Hotkey::Undo:
          case Hotkey::Redo:
            break;  // below, one at a time in the order pressed
          case Hotkey::TogglePanel:
            panelVisible = !panelVisible;
            break;
          case Hotkey::Quit:
            quit = true;
            break;
        }
        if (key == Hotkey::Undo || key == Hotkey::Redo) {  // one at a time, in order
          const std::string what = key == Hotkey::Undo ? session.undo() : session.redo();
          feedback.status = what.empty() ? std::string("nothing to ") + (key == Hotkey::Undo ? "undo" : "redo")
                                         : std::string(key == Hotkey::Undo ? "undid " : "redid ") + what;
          feedback.statusIsError = false;
        }
      }
      if (quit) break;
      // The render thread's finished frame, if any: the panel below shows its figures.
      if (worker)
        if (std::optional<RenderResult> r = worker->take()) takeResult(std::move(*r));
      imgui.beginFrame();
      if (panelVisible) {
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
      if (requests.undo || requests.redo) {  // the panel's buttons
        const std::string what = requests.undo ? session.undo() : session.redo();
        feedback.status = (requests.undo ? "undid " : "redid ") + what;
        feedback.statusIsError = false;
      }
      const ViewLayout layout = layoutFor(session.config());
      mouseCamera(session, layout.image.height);
      // While the camera or a widget moves, a preview: the progressive passes keep what they hold
      // instead of accumulating more (Renderer::holdRefinement); the first still frame refines again.
      {
        const ImGuiIO& io = ImGui::GetIO();
        const bool dragOnImage = !io.WantCaptureMouse && (io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2]);
        feedback.preview = scriptMovedCamera || dragOnImage || (!io.WantCaptureMouse && io.MouseWheel != 0.0f) ||
                           ImGui::IsAnyItemActive();
        if (feedback.preview && lockstep) session.renderer().holdRefinement();
        movedSinceJob |= feedback.preview;
      }
      // A size set in the panel or a script: the window grows or shrinks to show it at scale 1.
      const Config& c = session.config();
      if (c.render.width != imageW || c.render.height != imageH) {
        imageW = c.render.width;
        imageH = c.render.height;
        const auto [w, h] = windowSizeFor(imageW, imageH, panelVisible);
        glfwSetWindowSize(window, w, h);
      }
      // PNG screenshots copy the window below; EXR ones the radiance, which the render thread holds.
      if (options.frames > 0 && frame == options.frames - 1 && queuedCommands.empty()) {
        for (const std::string& s : options.screenshots) requests.screenshots.push_back(s);
        if (!options.savePreset.empty()) requests.presets.push_back(options.savePreset);
      }
      if (worker)
        std::erase_if(requests.screenshots, [&](const std::string& file) {
          if (std::filesystem::path(file).extension() != ".exr") return false;
          radianceFiles.push_back(file);
          return true;
        });

      if (lockstep) {
        feedback.frame = session.render();
        ++renders;
        if (!feedback.frame.refused.empty() && !scriptWhere.empty())
          throw InputError(scriptWhere + ": " + feedback.frame.refused);
        panel.record(feedback.frame);
        const Config& shown = session.config();  // as rendered (a refused change was undone)
        const GLuint picture = canvas.target(shown.render.width, shown.render.height);
        feedback.debugNote = debugPass->render(debug, session.renderer(), shown.scene, shown.render, picture,
                                               shown.render.width, shown.render.height);
        if (!debugWhere.empty() && !feedback.debugNote.empty()) throw InputError(debugWhere + ": " + feedback.debugNote);
        debugWhere.clear();
        canvas.present(layoutFor(shown), width, height);
      } else {
        if (!worker->busy()) {  // the thread is free: the next frame, as things stand now
          advanceClock(false);
          RenderJob job;
          job.generation = session.generation();
          job.config = session.config();
          job.timeS = session.playback().time();
          job.playing = session.playback().playing();
          job.holdRefinement = movedSinceJob;
          job.debug = debug;
          job.radianceFiles = std::move(radianceFiles);
          radianceFiles.clear();
          job.presetName = session.presetName();
          job.measure = stats.has_value();
          worker->post(std::move(job));
          movedSinceJob = false;
        }
        const Config& shown = session.config();
        worker->present(layoutFor(shown), width, height);
        if (renders == 0) drawFirstFrameNotice(session.presetName());
      }
      // The title says what the picture waits for, where the panel may be hidden (F1) or scrolled.
      std::string title = "Tallow — " + session.presetName();
      if (const std::optional<AccumulationProgress> p = accumulationProgress(session, feedback.frame.wallMs))
        title += " — " + p->text();
      if (title != shownTitle) {
        glfwSetWindowTitle(window, title.c_str());
        shownTitle = std::move(title);
      }
      imgui.endFrame();
      // An edit ends when nothing is held: a slider released, a drag finished. Until then its
      // intermediate values are one step in the making.
      const ImGuiIO& io = ImGui::GetIO();
      if (!ImGui::IsAnyItemActive() && !io.MouseDown[0] && !io.MouseDown[1] && !io.MouseDown[2]) session.commitEdits();
      // Sampled a few times a second, and only once the GPU has the count: reading the transform-
      // feedback query right after the frame that issued it would wait for that frame's extraction.
      const auto now = Clock::now();
      if (lockstep && now - lastTriangles > std::chrono::duration<double>(kTriangleSampleS))
        if (const std::optional<std::size_t> n = session.renderer().triangleCountIfAvailable()) {
          feedback.triangles = *n;
          lastTriangles = now;
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

      ++windowFrames;
      if (lockstep && stats) recordFrame(frame, feedback.frame, session.config(), session.playback().playing(), feedback.preview,
                                         scriptStep);
      glfwSwapBuffers(window);
      if (!queuedCommands.empty()) --frame;  // the same script frame again, for the rest of its commands
    }
    // The frame in flight on the render thread is finished and recorded, as the window's last.
    if (worker && stats) {
      worker->finish();
      if (std::optional<RenderResult> r = worker->take()) takeResult(std::move(*r));
    }
  } catch (const std::exception& e) {
    if (stats) {
      try {
        finishStats("failed", e.what());
      } catch (const std::exception&) {
        // The error that stopped the run is the one to report.
      }
    }
    throw;
  }

  if (!options.stats.empty()) {
    if (interrupted()) finishStats("interrupted", interruptName());
    else finishStats("", "");
  }
  return interrupted() ? interruptExitCode() : 0;
}

}  // namespace tallow::app
