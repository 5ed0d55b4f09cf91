// Invalidation by declared inputs (issues 21 and 38): every registry parameter is a frame input (or a
// part of the scene), each is read by some pass, and changing one reruns the passes that declare
// it (and those that read what they rewrite). Two checks do not take the declarations' word:
//   - the passes a change lets the renderer skip are observed not to matter: a fresh renderer that
//     draws the scene before the change, then restarts every pass but those for the frame after it,
//     gives the frame a fresh renderer draws after the change, bit for bit (a pass that reads a
//     parameter it does not declare keeps a stale output and fails this);
//   - each pass the change reruns is observed to matter the same way (held, the frame differs), or
//     is listed as a rerun the picture does not show;
// at the test scene's small pinned settings and at the defaults people run (sss.maps, sss.map_size
// and sss.light_map_size auto, sss.history on). Pinned, the incremental frame also equals the fresh
// renderer's, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/config/setup.h"
#include "gpu/gl_context.h"
#include "sss/frame_plan.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/renderer.h"
#include "support/render_support.h"

namespace tallow {
namespace {

using nlohmann::json;

/// The inputs of a frame (sss::inputNames) with their fingerprints.
std::map<std::string, std::uint64_t> fingerprints(const sss::Scene& scene, const sss::RenderSettings& settings) {
  const sss::FrameState state{scene, settings, 0.0, 0};
  std::map<std::string, std::uint64_t> out;
  for (const std::string& name : sss::inputNames()) out[name] = sss::inputFingerprint(name, state);
  return out;
}

std::set<std::string> changedInputs(const std::map<std::string, std::uint64_t>& a,
                                    const std::map<std::string, std::uint64_t>& b) {
  std::set<std::string> out;
  for (const auto& [name, value] : a)
    if (b.at(name) != value) out.insert(name);
  return out;
}

/// Another valid value of `p` than `current` (null when the parameter has none to offer).
json otherValue(const app::Registry::Param& p, const json& current) {
  if (current.is_null()) return nullptr;
  if (p.type == "bool") return !current.get<bool>();
  if (p.type == "int") {
    if (current.is_string()) return static_cast<long long>(p.min) * 2;  // "auto" → a small fixed size
    const long long v = current.get<long long>();
    return v + 1 <= static_cast<long long>(p.max) ? v + 1 : v - 1;
  }
  if (p.type == "float") {
    const double v = current.get<double>();
    const double up = v == 0.0 ? std::min(p.max, 0.1) : v * 1.25;
    return up <= p.max ? up : v * 0.8;
  }
  if (p.type == "enum") {
    const auto it = std::find(p.choices.begin(), p.choices.end(), current.get<std::string>());
    if (p.choices.size() < 2) return nullptr;
    return it == p.choices.end() || it + 1 == p.choices.end() ? p.choices.front() : *(it + 1);
  }
  if (p.type == "vec3") {
    json v = current;
    for (int c = 0; c < 3; ++c) {
      const double x = v[c].get<double>();
      double y = x == 0.0 ? 0.01 * (c + 1) : x * (1.1 + 0.05 * c);
      if (y > p.max) y = x * 0.9;
      v[c] = y;
    }
    return v;
  }
  return nullptr;
}

/// The settings a run of the test puts over the invalidation scene's.
struct Variant {
  const char* name;
  std::vector<std::string> sets;
  /// The incremental frame is a fresh renderer's bit for bit: no history kept across changes, a
  /// fixed K and fixed sizes (with sss.history a frame after a change depends on the frames before
  /// it by design, and auto K keeps its K within a band; MapHistory.* and MapCount* test those).
  bool incrementalIsFresh;
};
// render.aa averages the frames of a still (StillAverage.* in still_average_gltest.cpp), so the
// second frame of an unchanged scene is not the first by design; every frame here is drawn at the
// pixel centres, and render.aa's own change is among the parameters checked.
const Variant kPinned{"pinned", {"sss.history=0", "render.aa=1"}, true};
const Variant kDefaults{
    "defaults", {"sss.maps=auto", "sss.map_size=auto", "sss.light_map_size=auto", "render.aa=1"}, false};

app::LoadedScene loadInvalidationScene(const std::string& method, const Variant& variant = kPinned) {
  app::SceneOptions options;
  options.preset = test::testScene("invalidation");
  options.sets = variant.sets;
  options.sets.push_back("method=" + method);
  return app::loadScene(options);
}

TEST(FrameInvalidation, EveryRegistryParameterIsAFrameInputOrAPartOfTheScene) {
  const app::LoadedScene base = loadInvalidationScene("radiosity-maps");
  const app::Registry registry = app::parameterRegistry(base.materials);
  const std::set<std::string> settingsInputs = [] {
    std::set<std::string> s;
    for (const std::string& n : sss::inputNames())
      if (n.rfind("scene.", 0) != 0 && n != "time" && n != "accumulation") s.insert(n);
    return s;
  }();
  std::set<std::string> covered;
  for (const app::Registry::Param& p : registry.params()) {
    app::Config config = base.config;
    const json value = otherValue(p, registry.get(config, p.key));
    if (value.is_null()) {
      std::printf("[ inputs ] %s: no other value in this scene (%s)\n", p.key.c_str(), registry.get(config, p.key).dump().c_str());
      continue;
    }
    const auto before = fingerprints(config.scene, config.render);
    try {
      registry.set(config, p.key, value);
    } catch (const app::InputError& e) {
      ADD_FAILURE() << p.key << "=" << value.dump() << " refused in a scene made to take every parameter: " << e.what();
      continue;
    }
    const std::set<std::string> changed = changedInputs(before, fingerprints(config.scene, config.render));
    if (!p.sceneBound()) {
      // A settings key is the input of the same name, and setting it changes that input only.
      EXPECT_TRUE(sss::isInput(p.key)) << p.key << " is no frame input: add it to sss/frame_inputs.cpp";
      EXPECT_EQ(changed, std::set<std::string>{p.key}) << p.key << " set to " << value.dump();
      covered.insert(p.key);
    } else {
      // A scene-bound key (material, light, camera, …) changes a part of the scene and no setting.
      EXPECT_FALSE(changed.empty()) << p.key << " set to " << value.dump() << " changes no frame input";
      for (const std::string& n : changed) EXPECT_EQ(n.rfind("scene.", 0), 0u) << p.key << " changes " << n;
    }
  }
  // And the other way round: no settings input without its registry key.
  EXPECT_EQ(covered, settingsInputs);
}

/// Every pass of every method in the invalidation scene (which needs all of them).
std::vector<sss::Pass*> everyPass(sss::FramePlan& plan, app::LoadedScene& loaded) {
  std::vector<sss::Pass*> passes;
  for (const char* m : {"radiosity-maps", "no-cache", "sslpv", "image-space", "burley", "albedo"}) {
    app::Config config = loaded.config;
    app::parameterRegistry(loaded.materials).set(config, "method", m);
    // The still's average, the glare and the local exposure are planned only when on.
    config.render.aaSamples = 4;
    config.render.bloom = 0.5f;
    config.render.localExposure = 0.5f;
    const sss::FrameState state{config.scene, config.render, 0.0, 0};
    for (sss::Pass* p : plan.passes(state))
      if (std::find(passes.begin(), passes.end(), p) == passes.end()) passes.push_back(p);
  }
  return passes;
}

TEST(FrameInvalidation, EveryInputIsReadByAPassAndEveryResourceIsWritten) {
  app::LoadedScene loaded = loadInvalidationScene("radiosity-maps");
  sss::FramePlan plan;
  const sss::FrameState state{loaded.config.scene, loaded.config.render, 0.0, 0};
  std::set<std::string> read, written;
  std::vector<std::string> names;
  for (sss::Pass* p : everyPass(plan, loaded)) {
    // The camera pass's reads depend on the method; everyPass leaves it on the last one (albedo),
    // so collect each method's part too.
    const sss::PassIo io = p->io(state);
    names.push_back(p->name());
    read.insert(io.reads.begin(), io.reads.end());
    read.insert(io.paces.begin(), io.paces.end());
    written.insert(io.writes.begin(), io.writes.end());
  }
  for (const auto& m : sss::makeTranslucencyMethods()) {
    const sss::PassIo io = m->surfaceIo(state);
    read.insert(io.reads.begin(), io.reads.end());
  }
  for (const char* expected : {"field.sample", "field.extract", "shadow.directional", "shadow.point", "sss.light_gbuffer",
                               "sss.maps", "vpl", "sslpv.voxelize", "sslpv.light_gbuffer", "sslpv.inject",
                               "sslpv.propagate", "image_space.gbuffer", "image_space.scatter", "image_space.combine",
                               "surface", "vpl.receivers"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected << " is not planned";
  for (const std::string& input : sss::inputNames()) {
    if (sss::isDisplayOnlyInput(input)) {
      EXPECT_FALSE(read.count(input)) << input << " is display-only, yet a pass reads it";
      continue;
    }
    EXPECT_TRUE(read.count(input)) << "no pass reads the input " << input;
  }
  for (const std::string& r : read)
    if (!sss::isInput(r)) {
      EXPECT_TRUE(written.count(r)) << r << " is read but no pass writes it (a misspelt name?)";
    }
}

std::set<std::string> ranPasses(const sss::FrameTimings& t) {
  std::set<std::string> out;
  for (const auto& p : t.passes) out.insert(p.name);
  return out;
}

/// Passes that run every frame whatever changed: the camera pass and what follows it.
bool drawsEveryFrame(const std::string& pass) {
  return pass == "surface" || pass == "flame" || pass.rfind("camera.", 0) == 0;
}

/// The passes a frame must run after the inputs changed from `before` to `after` (both converged:
/// sss.frames = image_space.frames = 1): those that read (or are paced by) a changed input, those
/// not in the plan before, those that read a resource one of these rewrites, and the camera pass.
std::set<std::string> expectedReruns(const app::Config& before, const app::Config& after) {
  const std::set<std::string> changed =
      changedInputs(fingerprints(before.scene, before.render), fingerprints(after.scene, after.render));
  sss::FramePlan planBefore, planAfter;
  const sss::FrameState old{before.scene, before.render, 0.0, 0}, now{after.scene, after.render, 0.0, 0};
  std::set<std::string> previously;
  for (sss::Pass* p : planBefore.passes(old)) previously.insert(p->name());
  std::set<std::string> rerun, rewritten;
  for (sss::Pass* p : planAfter.passes(now)) {
    const sss::PassIo io = p->io(now);
    // The camera pass draws every frame, and the still's average, the glare and the local exposure
    // follow it; everything else here is converged (one frame each).
    bool runs = !previously.count(p->name()) || drawsEveryFrame(p->name());
    for (const std::string& r : io.reads) runs |= changed.count(r) > 0 || rewritten.count(r) > 0;
    for (const std::string& r : io.paces) runs |= changed.count(r) > 0;
    if (!runs) continue;
    rerun.insert(p->name());
    rewritten.insert(io.writes.begin(), io.writes.end());
  }
  return rerun;
}

std::string join(const std::set<std::string>& s) {
  std::string out;
  for (const auto& x : s) out += (out.empty() ? "" : " ") + x;
  return out;
}

/// A fresh renderer's frame of `after`. With `before`: it draws `before` first, then restarts every
/// pass (Renderer::invalidate) but the `held` ones, which keep what they made for `before`.
gpu::Image freshFrame(const gpu::ShaderLibrary& shaders, const app::Config& after, double t,
                      const app::Config* before = nullptr, const std::set<std::string>& held = {}) {
  const app::Config& first = before ? *before : after;
  sss::Renderer renderer(shaders, first.scene, first.render);
  if (before) {
    renderer.render(before->scene, before->render, t);
    renderer.invalidate();
    renderer.hold(held);
  }
  renderer.render(after.scene, after.render, t);
  return renderer.readRadiance();
}


/// For each registry parameter: a second value reruns the passes expectedReruns names; the passes
/// it skips are observed not to matter and those it reruns to matter (freshFrame with them held);
/// with variant.incrementalIsFresh the frame equals a fresh renderer's.
void checkEveryParameter(const std::string& method, int minimumVisible, const Variant& variant = kPinned) {
  app::LoadedScene loaded = loadInvalidationScene(method, variant);
  const app::Registry registry = app::parameterRegistry(loaded.materials);
  gpu::ContextOptions options;
  options.visible = false;
  const auto context = gpu::GlContext::create(options);
  gpu::ShaderLibrary shaders;
  const app::Config base = loaded.config;
  sss::Renderer renderer(shaders, base.scene, base.render);
  const double t = 1.0;
  // Frames of the base scene until one runs only the camera pass and the candle's flame drawn over
  // it (sss.maps=auto decides K from the coverage of a frame or two before: glFinish makes that lag
  // the same in every run). Returns the K in use (0 without maps).
  // With VPLs their light on the receivers is added after each camera pass (vpl.receivers).
  const std::string settled =
      sss::VirtualPointLights::applies(base.scene, base.render) ? "flame surface vpl.receivers" : "flame surface";
  const auto settle = [&] {
    std::string ran;
    for (int frame = 0; frame < 6 && ran != settled; ++frame) {
      ran = join(ranPasses(renderer.render(base.scene, base.render, t)));
      glFinish();
    }
    EXPECT_EQ(ran, settled) << variant.name << ", " << method << ": the base scene does not settle";
    return renderer.module<sss::RadiosityMaps>() ? static_cast<int>(renderer.module<sss::RadiosityMaps>()->views().size()) : 0;
  };
  // The settings as the passes saw them: sss.maps=auto replaced by the K in use.
  const auto withK = [](app::Config c, int k) {
    if (c.render.sss.maps == sss::kAuto && k > 0) c.render.sss.maps = k;
    return c;
  };
  int baseK = settle();
  gpu::Image basePicture = renderer.readRadiance();
  // Inputs that pace an accumulation (sss.frames): raising one adds frames to it, which a
  // recomputation from scratch does not have; their reruns are checked, their pictures are not.
  std::set<std::string> paces;
  {
    sss::FramePlan plan;
    for (const char* m : {"radiosity-maps", "image-space"}) {
      app::Config c = base;
      registry.set(c, "method", m);
      const sss::FrameState state{c.scene, c.render, 0.0, 0};
      for (sss::Pass* pass : plan.passes(state))
        for (const std::string& n : pass->io(state).paces) paces.insert(n);
    }
  }
  EXPECT_EQ(join(paces), "image_space.frames sss.frames");
  int checked = 0, visible = 0, observed = 0;
  std::vector<std::string> unseenReruns;
  for (const app::Registry::Param& p : registry.params()) {
    app::Config config = base;
    const json value = otherValue(p, registry.get(config, p.key));
    if (value.is_null()) continue;
    try {
      registry.set(config, p.key, value);
    } catch (const app::InputError& e) {  // e.g. light.type of a light that follows a flame
      std::printf("[ %s ] %s=%s refused: %s\n", method.c_str(), p.key.c_str(), value.dump().c_str(), e.what());
      continue;
    }
    ++checked;
    const std::string what = std::string(variant.name) + ", " + method + ": " + p.key + " = " + value.dump();
    const sss::FrameTimings timings = renderer.render(config.scene, config.render, t);
    glFinish();
    const std::set<std::string> ran = ranPasses(timings);
    const int k = renderer.module<sss::RadiosityMaps>() ? static_cast<int>(renderer.module<sss::RadiosityMaps>()->views().size()) : 0;
    EXPECT_EQ(join(ran), join(expectedReruns(withK(base, baseK), withK(config, k)))) << what;
    const gpu::Image incremental = renderer.readRadiance();
    if (incremental.pixels != basePicture.pixels) ++visible;
    baseK = settle();  // back to the base scene for the next parameter (with a history, its own still)
    basePicture = renderer.readRadiance();
    // New samples every frame, by design: the no-cache gather and VPLs with vpl.stable off.
    const bool freshEveryFrame = config.render.sss.method == sss::SssMethod::NoCache || !config.render.vpl.stable;
    if (freshEveryFrame || paces.count(p.key)) continue;
    const gpu::Image fresh = freshFrame(shaders, config, t);
    if (variant.incrementalIsFresh) {
      int differing = 0;
      for (std::size_t i = 0; i < incremental.pixels.size(); ++i)
        differing += incremental.pixels[i] != fresh.pixels[i] ? 1 : 0;
      // Bit for bit: the passes are deterministic, so a pixel that differs shows a pass that kept
      // its output although something it reads changed, an input it does not declare.
      EXPECT_EQ(differing, 0) << what << " gives another picture than a fresh renderer: a pass reads it undeclared";
    }
    // The passes the change skipped, held at their output for the base scene: the frame must not
    // change (observed, whatever the passes declare).
    std::set<std::string> skipped, planned;  // planned: for the base scene, so with an output to keep
    {
      sss::FramePlan plan;
      const sss::FrameState state{config.scene, config.render, t, 0}, was{base.scene, base.render, t, 0};
      for (sss::Pass* pass : plan.passes(state))
        if (!ran.count(pass->name())) skipped.insert(pass->name());
      for (sss::Pass* pass : plan.passes(was)) planned.insert(pass->name());
    }
    const gpu::Image heldSkipped = freshFrame(shaders, config, t, &base, skipped);
    EXPECT_TRUE(heldSkipped.pixels == fresh.pixels)
        << what << ": keeping what the skipped passes (" << join(skipped)
        << ") made before the change gives another frame: one of them reads it undeclared";
    // Each pass it reran, held alone beside them: a change of the frame shows the rerun was needed
    // (pinned only: at the defaults' sizes a fresh frame takes about a second on llvmpipe).
    if (!variant.incrementalIsFresh) continue;
    for (const std::string& pass : ran) {
      if (drawsEveryFrame(pass) || !planned.count(pass)) continue;  // new in the plan: it must run
      std::set<std::string> held = skipped;
      held.insert(pass);
      ++observed;
      if (freshFrame(shaders, config, t, &base, held).pixels == fresh.pixels) unseenReruns.push_back(p.key + ": " + pass);
    }
  }
  EXPECT_GT(checked, 50) << "parameters changed";
  // The comparison has teeth only for changes the picture shows: the scene is made so that most do
  // (the other method's parameters, display-only ones and equivalent options such as sss.gather
  // do not).
  std::printf("[ %s, %s ] %d of %d parameter changes show in the picture; %zu of %d reruns observed not to\n",
              variant.name, method.c_str(), visible, checked, unseenReruns.size(), observed);
  for (const std::string& u : unseenReruns) std::printf("[ %s, %s ]   rerun unseen: %s\n", variant.name, method.c_str(), u.c_str());
  EXPECT_GE(visible, minimumVisible) << "the scene no longer shows what its parameters change";
}

// The no-cache method draws new samples every frame by design, so its pictures are compared through
// the light G-buffer pass it shares with the radiosity maps.
TEST(FrameInvalidation, RadiosityMapsRerunExactlyWhatTheirInputsName) { checkEveryParameter("radiosity-maps", 36); }
TEST(FrameInvalidation, SslpvRerunsExactlyWhatItsInputsName) { checkEveryParameter("sslpv", 23); }
TEST(FrameInvalidation, ImageSpaceRerunsExactlyWhatItsInputsName) { checkEveryParameter("image-space", 24); }
TEST(FrameInvalidation, AlbedoRerunsExactlyWhatItsInputsName) { checkEveryParameter("albedo", 13); }
TEST(FrameInvalidation, BurleyRerunsExactlyWhatItsInputsName) { checkEveryParameter("burley", 13); }
TEST(FrameInvalidation, RadiosityMapsAtTheirDefaultsRerunWhatTheirInputsName) {
  checkEveryParameter("radiosity-maps", 36, kDefaults);
}

}  // namespace
}  // namespace tallow
