#include "app/commands/capture_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "app/commands/frame_stats.h"
#include "app/commands/frame_writer.h"
#include "app/commands/interrupt.h"
#include "app/commands/progress.h"
#include "app/commands/provenance.h"
#include "app/commands/reference_command.h"
#include "app/commands/option_checks.h"
#include "app/commands/output_folder.h"
#include "app/commands/stats_writer.h"
#include "app/commands/video_encoder.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/playback/playback.h"
#include "app/playback/scene_controls.h"
#include "app/playback/view_script.h"
#include "gpu/atomic_file.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"
#include "gpu/readback.h"
#include "sss/field_source.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/peers/sslpv.h"
#include "sss/renderer.h"

namespace tallow::app {

namespace {
/// A frame whose passes were issued and whose targets are on their way back (AsyncReadback).
struct InFlight {
  FrameRecord frame;
  std::uint64_t ticket = 0;  ///< AsyncReadback: frameTargets' two
  bool shownSeparate = false;
  gpu::ToneMapSettings toneMap;
  std::chrono::steady_clock::time_point start;
  std::uint64_t targetReads = 0;  ///< render targets read back for it
};

/// What a capture reads back of the last frame, two targets: the radiance (the EXR), then the
/// picture shown when it is not the radiance (the PNG: the glare, the local exposure; the masks in
/// its alpha), else the coverage (the masks).
std::vector<const gpu::Texture*> frameTargets(const sss::Renderer& renderer) {
  return {&renderer.radiance(), renderer.showsRadiance() ? &renderer.coverage() : &renderer.shownTexture()};
}

/// Sums `more` into `total` pass by pass (passes absent from `total` are appended).
void addTimings(sss::FrameTimings& total, const sss::FrameTimings& more) {
  for (const gpu::PassTiming& p : more.passes) {
    auto it = std::find_if(total.passes.begin(), total.passes.end(),
                           [&](const gpu::PassTiming& q) { return q.name == p.name; });
    if (it == total.passes.end()) {
      total.passes.push_back(p);
    } else {
      it->gpuMs += p.gpuMs;
      it->cpuMs += p.cpuMs;
      it->threadCpuMs += p.threadCpuMs;
      if (it->counts && p.counts) *it->counts += *p.counts;
      else it->counts.reset();  // a render not counted: no sum to show
    }
  }
  total.gpuTotalMs += more.gpuTotalMs;
  total.cpuTotalMs += more.cpuTotalMs;
  total.threadCpuTotalMs += more.threadCpuTotalMs;
}

/// What a capture writes into its folder, which a rerun clears (OutputFolder::clearEarlierRun).
const std::vector<std::string> kCaptureOutputs = {"frame_[0-9]*.png", "frame_[0-9]*.exr", "stats.json",
                                                  "stats.frames.jsonl"};

std::string frameName(int index, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%04d.%s", index, extension);
  return name;
}
}  // namespace

namespace {

/// The run's summary after its last frame (map coverage, warnings, SSLPV's grid): it reads the frame
/// back, so it is computed once, when the frames are done (or stopped).
nlohmann::json finalSummary(const sss::Renderer& renderer, const Config& config) {
  nlohmann::json summary;
  if (const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>()) {
    const sss::MapCoverage coverage = renderer.mapCoverage();
    nlohmann::json pearling = nlohmann::json::array();
    for (const auto& w : sss::pearlingWarnings(config.scene, maps->sphere().radius, maps->lightMapSize())) {
      pearling.push_back({{"object", w.object}, {"band", w.band}, {"mean_free_path_mm", w.meanFreePathMm},
                          {"light_texel_mm", w.texelMm}});
      std::fprintf(stderr, "tallow: warning: pearling on %s (band %d): 1/sigma_tr = %.3g mm is below the light "
                           "G-buffer texel of %.3g mm; raise sss.light_map_size\n",
                   w.object.c_str(), w.band, w.meanFreePathMm, w.texelMm);
    }
    // A point light inside a translucent object's bounds with planar sampling: the paper's Fig. 4a
    // noise; allowed (it is how the comparison is made) but said.
    nlohmann::json warnings = nlohmann::json::array();
    if (!config.render.sss.stereographic)
      for (const sss::Light& l : config.scene.lights) {
        if (l.kind != sss::LightKind::Point) continue;
        const glm::vec3 c = maps->sphere().centre;
        if (glm::length(l.position - c) < maps->sphere().radius) {
          const std::string w = "a point light lies inside the translucent objects' bounds with sss.stereographic off: "
                                "planar sampling of its cube G-buffer is noisy there (the paper's Fig. 4a)";
          warnings.push_back(w);
          std::fprintf(stderr, "tallow: warning: %s\n", w.c_str());
        }
      }
    summary = {{"map_bytes", maps->bytes()},
               {"warnings", warnings},
               {"light_map_size", maps->lightMapSize()},
               {"map_size", maps->mapSize()},
               {"maps", maps->views().size()},
               {"frames_accumulated", maps->frames()},
               {"translucent_pixels", coverage.translucentPixels},
               {"unseen_pixels", coverage.unseenPixels},
               {"unseen_share", coverage.unseenShare()},
               {"pearling", pearling}};
  }
  if (const sss::Sslpv* lpv = renderer.module<sss::Sslpv>()) {
    const sss::SslpvGrid& g = lpv->grid();
    summary["sslpv"] = {{"grid", g.size},
                        {"cell_mm", g.cellMm()},
                        {"origin_m", {g.origin.x, g.origin.y, g.origin.z}},
                        {"bytes", lpv->bytes()}};
  }
  return summary;
}

}  // namespace

namespace {

/// Every frame's animation time within [0, kMaxTimeS], before any work: the clock is run through
/// the frames with the script's commands applied to copies (a seek, a negative speed or a low --fps
/// could take it out of range half-way through a run).
void checkFrameTimes(const CaptureOptions& options, const Config& config, const Registry& registry,
                     const std::optional<Script>& script) {
  Config trial = config;
  Playback clock(options.timeS.value_or(config.scene.startS), config.scene.durationS, config.scene.loop);
  std::string cause = "--time + frame / --fps";
  for (int i = 0; i < options.frames; ++i) {
    clock.setFrame(i, options.fps);
    if (script)
      for (const ScriptCommand* c : script->at(i)) {
        applyScriptCommand(*c, trial, registry, clock);
        if (c->action == ScriptAction::Seek || c->action == ScriptAction::Speed) cause = c->where;
      }
    const double t = clock.rawTime();
    if (!(t >= 0.0 && t <= kMaxTimeS))
      throw InputError(cause + ": frame " + std::to_string(i) + " would be at t = " + formatNumber(t) +
                       " s, out of range [0, " + formatNumber(kMaxTimeS) + "]");
  }
}

}  // namespace

int runCapture(const CaptureOptions& options) {
  if (options.outDir.empty()) throw InputError("capture: --out DIR is required");
  if (options.frames < 1) throw InputError("--frames: must be at least 1");
  checkFps("--fps", options.fps);
  if (options.timeS) checkTime("--time", *options.timeS);
  if (options.accumulate < 1 || options.accumulate > kMaxAccumulate)
    throw InputError("--accumulate: must be between 1 and " + std::to_string(kMaxAccumulate));
  LoadedScene loaded = loadScene(options.scene);
  Config& config = loaded.config;
  const std::filesystem::path out(options.outDir);
  checkWritableFolder(out);
  const Registry registry = parameterRegistry(loaded.materials);
  std::optional<Script> script;
  if (!options.script.empty()) {
    script = loadScript(options.script, registry);
    for (const ScriptCommand& c : script->commands) {
      if (windowOnly(c.action))
        throw InputError(c.where + ": " + std::string(scriptActionName(c.action)) +
                         " applies to view only (capture writes every frame)");
      if (c.frame >= options.frames)
        throw InputError(c.where + ": frame " + std::to_string(c.frame) + " is beyond --frames " +
                         std::to_string(options.frames));
      // Frames go to the video as they are rendered: its size is fixed by the first.
      if (!options.video.empty() && c.action == ScriptAction::Set && (c.key == "render.width" || c.key == "render.height"))
        throw InputError(c.where + ": --video: the script changes the image size, which a video cannot have");
      if (!options.reference.empty() && c.action == ScriptAction::Set &&
          (c.key == "render.width" || c.key == "render.height"))
        throw InputError(c.where + ": --reference: the script changes the image size, which the reference cannot");
    }
  }
  checkFrameTimes(options, config, registry, script);
  if (!options.video.empty()) {
    checkVideoOutput(options.video);
    checkOutputFile("--video", options.video);
  }

  // --reference: every frame's error against one reference (issue 17: an animation's frame k
  // against the reference at t_k), read and checked before any work.
  std::optional<ReferenceImages> reference;
  if (!options.reference.empty())
    reference = readReferencePair(options.reference, config.render.width, config.render.height, "the capture",
                                  "--reference", /*plainAllowed=*/true);

  // The folder is this run's from here on: a second run into it refuses (output_folder.h).
  OutputFolder folder(out, "capture");

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::parseGlBackend(options.gl);
  contextOptions.visible = false;
  auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary shaders = makeShaderLibrary(options.scene.shaderDir);
  sss::Renderer renderer(shaders, config.scene, config.render);

  RunRecord run;
  run.command = "capture";
  run.presetName = loaded.presetName;
  run.presetPath = loaded.presetPath.string();
  run.backend = context->backend();
  run.gl = context->info();
  run.glLimits = glLimitsJson();
  run.width = config.render.width;
  run.height = config.render.height;
  run.plan = sss::Renderer::plan(config.scene, config.render);
  run.accumulate = options.accumulate;
  run.parameters = registry.snapshot(config);
  run.framesRequested = options.frames;
  run.state = "running";
  if (options.scene.explain) std::fputs(sss::formatPlan(run.plan).c_str(), stdout);

  // Each frame is written when it is done (PNG, EXR, the video's next frame, its line in
  // stats.frames.jsonl), so memory does not grow with --frames and a stopped run keeps every frame it
  // finished. Only the frame before is kept, for the receivers' frame-to-frame change.
  const InterruptScope interruptScope;
  // Counted in renders with --accumulate (a frame of 16 renders of the candle takes half a minute).
  const int rendersPerFrame = options.accumulate;
  Progress progress("capture", rendersPerFrame > 1 ? "render" : "frame", options.frames * rendersPerFrame);
  std::unique_ptr<VideoEncoder> video;
  std::optional<gpu::Image> previous;
  StatsWriter stats(out / "stats.json");
  int undefinedErrors = 0;  // frames whose error against --reference is undefined (NaN or infinite pixels)
  // Frame i is at start + i / fps unless a script pauses, seeks or changes the speed (no wrapping:
  // a capture past the animation's end shows the time it asks for).
  Playback playback(options.timeS.value_or(config.scene.startS), config.scene.durationS, config.scene.loop);
  nlohmann::json parameters = run.parameters;
  // Issue 39, point 4: no frame waits for its own pixels. Frame k's targets are copied into a ring
  // of pixel-pack buffers; they are fetched after frame k+1's passes were issued (the GPU has long
  // finished k by then) and handed to the writer's thread, which computes the frame's figures and
  // writes its files while frame k+1 renders. The writer is declared last, so that it is joined
  // before anything its jobs use goes.
  gpu::AsyncReadback readback;
  std::optional<InFlight> inFlight;
  // On the writer's thread, one frame after the other: what the render thread no longer touches
  // (the frame before, the video, the stats, the folder, the progress line).
  const auto writeFrame = [&](FrameRecord& frame, std::vector<gpu::Image>& images, bool shownSeparate,
                              const gpu::ToneMapSettings& toneMap) {
    const int i = frame.index;
    gpu::Image& image = images[0];
    const gpu::PixelCensus census = gpu::censusPixels(image);
    frame.pixels = pixelsRecord(census, options.exrFloat);
    // The masks, read back once: the clipped count and both frame-to-frame changes use them.
    const sss::PixelMasks masks = shownSeparate ? sss::pixelMasksOfCode(images[1]) : sss::pixelMasksOf(images[1]);
    frame.pixels.update(clippedRecord(image, masks.translucent, toneMap));
    if (census.nonFinite > 0)
      std::fprintf(stderr,
                   "tallow: warning: frame %d: %zu pixel(s) are NaN or infinite (kept so in the EXR, black in the PNG)\n",
                   i, census.nonFinite);
    // A script that resizes the image starts the frame-to-frame change afresh (null at the resize).
    if (previous && (previous->width != image.width || previous->height != image.height)) previous.reset();
    if (previous) {
      // Flicker of what the receivers show (issue 7, point 4): the VPLs' light from frame to frame;
      // and of the translucent objects themselves (issue 17, point 3).
      const auto any = [](const std::vector<std::uint8_t>& mask) {
        return std::any_of(mask.begin(), mask.end(), [](std::uint8_t m) { return m != 0; });
      };
      if (any(masks.receivers)) frame.receiverChange = gpu::relativeChange(image, *previous, masks.receivers);
      if (any(masks.translucent)) frame.translucentChange = gpu::relativeChange(image, *previous, masks.translucent);
    }
    const gpu::ExrPixelType asked = options.exrFloat ? gpu::ExrPixelType::Float : gpu::ExrPixelType::Half;
    if (reference) {
      // The frame as its EXR stores it: a capture compared with its own stored frame differs by 0.
      frame.reference = referenceErrorRecord(gpu::storedAsExr(image, asked), reference->radiance, reference->standardError);
      frame.reference["compared"] = reference->plain ? "all pixels" : "object pixels";
      if (frame.reference["rel_rmse"].is_null() && frame.reference["non_finite"]["image"].get<std::size_t>() > 0) {
        ++undefinedErrors;
        std::fprintf(stderr, "tallow: frame %d: its error against %s is undefined (NaN or infinite pixels)\n", i,
                     options.reference.c_str());
      }
    }

    // The earlier run's outputs go when this one has its first frame to write (docs/commands.md).
    if (i == 0) folder.clearEarlierRun(kCaptureOutputs);
    // The PNG and the video show the picture as the window does (render.bloom's glare and
    // render.local_exposure's adaptation included); the EXR keeps the radiance.
    const gpu::Image& picture = shownSeparate ? images[1] : image;
    gpu::writePng(out / frameName(i, "png"), picture, toneMap);
    if (gpu::writeExr(out / frameName(i, "exr"), image, asked,
                      {{"tallow.preset", loaded.presetName}, {"tallow.renderer", run.gl.renderer}}) != asked)
      std::fprintf(stderr,
                   "tallow: %s: %s pixel(s) beyond half-float's range (%g): written with 32-bit float channels\n",
                   (out / frameName(i, "exr")).string().c_str(), frame.pixels["beyond_half"].dump().c_str(),
                   double(gpu::kHalfMax));
    if (!options.video.empty()) {
      if (!video) video = std::make_unique<VideoEncoder>(options.video, image.width, image.height, options.fps);
      video->add(gpu::toneMappedRgb8(picture, toneMap));
    }
    frame.rssBytes = residentBytes();
    previous = std::move(image);
    if (i + 1 == options.frames) run.state = "complete";
    stats.append(run, frame);
    progress.update((i + 1) * rendersPerFrame);
  };
  FrameWriter writer;
  const auto complete = [&](InFlight& f, std::chrono::steady_clock::time_point end) {
    std::vector<gpu::Image> images = readback.fetch(f.ticket);
    renderer.resolveTimings(f.frame.gpu);  // its queries were issued before the fence it passed
    // The time from this frame's start to the next one's: the rate frames are made at, rendering
    // overlapping the writing of the frame before.
    f.frame.wallMs = std::chrono::duration<double, std::milli>(end - f.start).count();
    f.frame.targetReads = static_cast<std::int64_t>(f.targetReads);
    writer.submit([&, frame = std::move(f.frame), images = std::move(images), separate = f.shownSeparate,
                   toneMap = f.toneMap]() mutable {
      writeFrame(frame, images, separate, toneMap);
    });
  };
  try {
    for (int i = 0; i < options.frames && !interrupted(); ++i) {
      FrameRecord frame;
      frame.index = i;
      playback.setFrame(i, options.fps);
      std::string where;  // the frame's last script command, to locate a change the GPU refuses
      if (script)
        for (const ScriptCommand* c : script->at(i)) {
          applyScriptCommand(*c, config, registry, playback);
          where = c->where;
        }
      if (!where.empty()) {
        nlohmann::json now = registry.snapshot(config);
        frame.changed = changedParameters(parameters, now);
        parameters = std::move(now);
      }
      frame.timeS = playback.rawTime();
      const auto start = std::chrono::steady_clock::now();
      try {
        // With --accumulate N the frame's time is rendered N times (a paused window's progressive
        // accumulation); its GPU timings are the sums over those renders, like its wall time.
        const auto rendered = [&](int a) {
          if (rendersPerFrame > 1)
            progress.update(i * rendersPerFrame + std::min(a, rendersPerFrame),
                            options.frames > 1 ? "frame " + std::to_string(i + 1) + " of " + std::to_string(options.frames) : "");
        };
        // The maps' frames accumulated (RadiosityMaps::frames), or N where the method has none.
        const auto mapFrames = [&] {
          const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>();
          return maps && sss::RadiosityMaps::applies(config.scene, config.render) ? maps->frames() : options.accumulate;
        };
        const auto renderFrame = [&] {
          frame.gpu = renderer.render(config.scene, config.render, frame.timeS);
          rendered(1);
          // A still after motion starts its count with the render after the one that reused the maps'
          // history (RadiosityMaps::renderMaps): one render more then, so that N frames are accumulated.
          for (int a = 1; a < options.accumulate || (a == options.accumulate && options.accumulate > 1 &&
                                                     mapFrames() < options.accumulate);
               ++a) {
            // The GPU times of the renders so far are read before the sum is taken (a wait, as the
            // accumulated frame is timed whole).
            renderer.resolveTimings(frame.gpu);
            sss::FrameTimings more = renderer.render(config.scene, config.render, frame.timeS);
            renderer.resolveTimings(more);
            addTimings(frame.gpu, more);
            rendered(a + 1);
          }
        };
        renderFrame();
        // A field's mesh that overflowed its buffers: grown, and the frame drawn again whole
        // (each growth at least doubles them, up to their cap).
        while (renderer.repairGeometry()) renderFrame();
      } catch (const std::invalid_argument& e) {
        if (where.empty()) throw;
        throw InputError(where + ": " + e.what());
      }
      frame.sss = mapsRecord(renderer);
      for (const sss::Light& l : sss::sceneAtTime(config.scene, frame.timeS).lights)
        if (l.kind == sss::LightKind::Point) {
          frame.pointLights.push_back(l.position);
          frame.pointLightIntensities.push_back(l.intensity);
        }
      // The frame's targets go into the read-back ring behind a fence; the frame before comes back
      // now, while the GPU works on this one, and is written on the writer's thread.
      const std::uint64_t readsBefore = gpu::targetReads();
      InFlight next{std::move(frame), readback.issue(frameTargets(renderer)), !renderer.showsRadiance(),
                    config.render.toneMap, start, 0};
      next.targetReads = gpu::targetReads() - readsBefore;
      if (inFlight) complete(*inFlight, next.start);
      inFlight = std::move(next);
    }
    if (inFlight) complete(*inFlight, std::chrono::steady_clock::now());
    inFlight.reset();
    writer.finish();
    progress.finish();
    if (interrupted()) {
      run.state = "interrupted";
      run.stopReason = interruptName();
    }
    if (video) video->finish();
  } catch (const std::exception& e) {
    // What was written stays (each file whole); stats.json says where and why the run stopped. The
    // frame before the one that failed was rendered whole: it is written too.
    if (inFlight) try {
        complete(*inFlight, std::chrono::steady_clock::now());
      } catch (const std::exception&) {
        // The error that stopped the run is the one to report.
      }
    writer.settle();
    progress.finish();
    video.reset();  // no partial video
    if (run.framesWritten > 0) {
      run.state = "failed";
      run.stopReason = e.what();
      try {
        stats.finish(run);
      } catch (const std::exception&) {
        // The error that stopped the run is the one to report.
      }
    }
    throw;
  }
  if (run.framesWritten == 0) {  // stopped before the first frame was done: nothing to write
    std::fprintf(stderr, "tallow: capture stopped (%s) before the first frame; nothing written\n", interruptName());
    return interruptExitCode();
  }
  run.gpuBytes = renderer.gpuBytes();
  run.triangles = renderer.triangleCount();  // after the frames: includes the last field extraction
  run.sss = finalSummary(renderer, config);
  stats.finish(run);
  const int written = run.framesWritten;
  if (interrupted()) {
    std::fprintf(stderr, "tallow: capture stopped by %s after %d of %d frame(s); wrote them to %s\n", interruptName(),
                 written, options.frames, out.string().c_str());
    return interruptExitCode();
  }
  std::printf("tallow: wrote %d frame(s) of %s (%dx%d, %s) to %s\n", written, loaded.presetName.c_str(), run.width,
              run.height, run.gl.renderer.c_str(), out.string().c_str());
  if (undefinedErrors > 0) {
    // A comparison that cannot be made fails, rather than pass as a perfect match.
    std::fprintf(stderr, "tallow: capture: %d frame(s) have NaN or infinite pixels: their error against %s is undefined\n",
                 undefinedErrors, options.reference.c_str());
    return 1;
  }
  return 0;
}

}  // namespace tallow::app
