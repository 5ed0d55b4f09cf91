// Invalidation by declared inputs (issue 21): every registry parameter is a frame input (or a part
// of the scene), each is read by some pass, changing one reruns exactly the passes that declare it
// (and those that read what they rewrite), and — the check that catches a dependency a pass forgot
// to declare — the frame the declared inputs give is bit for bit the frame of a renderer that
// recomputes everything.
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

app::LoadedScene loadInvalidationScene(const std::string& method) {
  app::SceneOptions options;
  options.preset = test::testScene("invalidation");
  // sss.history keeps the maps' history across changes of the geometry and the lights, so a picture
  // then depends on the frames before it, by design; the bit-for-bit comparison with a full
  // recomputation needs the paper's restart (the history: MapHistory.* in radiosity_maps_gltest.cpp).
  // render.aa averages the frames of a still (StillAverage.* in still_average_gltest.cpp), so the
  // second frame of an unchanged scene is not the first by design; here every frame is drawn at the
  // pixel centres, and render.aa's own change is among the parameters checked below.
  options.sets = {"method=" + method, "sss.history=0", "render.aa=1"};
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
  for (const char* m : {"radiosity-maps", "no-cache", "sslpv", "image-space", "albedo"}) {
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
                               "surface"})
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
    bool runs = !previously.count(p->name()) || p->name() == "surface" || p->name() == "camera.still" ||
                p->name() == "camera.bloom" || p->name() == "camera.local_exposure";
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

/// For each registry parameter: a second value reruns the passes expectedReruns names, and the
/// frame equals the one a renderer that forgets everything (Renderer::invalidate) gives.
void checkEveryParameter(const std::string& method, int minimumVisible) {
  app::LoadedScene loaded = loadInvalidationScene(method);
  const app::Registry registry = app::parameterRegistry(loaded.materials);
  gpu::ContextOptions options;
  options.visible = false;
  const auto context = gpu::GlContext::create(options);
  gpu::ShaderLibrary shaders;
  const app::Config base = loaded.config;
  sss::Renderer renderer(shaders, base.scene, base.render);
  const double t = 1.0;
  renderer.render(base.scene, base.render, t);
  const sss::FrameTimings settled = renderer.render(base.scene, base.render, t);
  const gpu::Image basePicture = renderer.readRadiance();
  EXPECT_EQ(join(ranPasses(settled)), "flame surface")
      << "a second frame of an unchanged scene runs only the camera pass and the candle's flame drawn over it";
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
  int checked = 0, visible = 0;
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
    const sss::FrameTimings timings = renderer.render(config.scene, config.render, t);
    const std::set<std::string> ran = ranPasses(timings), expected = expectedReruns(base, config);
    EXPECT_EQ(join(ran), join(expected)) << method << ": " << p.key << " = " << value.dump();
    const gpu::Image incremental = renderer.readRadiance();
    if (incremental.pixels != basePicture.pixels) ++visible;
    // New samples every frame, by design: the no-cache gather and VPLs with vpl.stable off.
    const bool freshEveryFrame = config.render.sss.method == sss::SssMethod::NoCache || !config.render.vpl.stable;
    if (freshEveryFrame || paces.count(p.key)) {
      renderer.render(base.scene, base.render, t);
      continue;
    }
    renderer.invalidate();
    renderer.render(config.scene, config.render, t);
    const gpu::Image recomputed = renderer.readRadiance();
    int differing = 0;
    for (std::size_t i = 0; i < incremental.pixels.size(); ++i)
      differing += incremental.pixels[i] != recomputed.pixels[i] ? 1 : 0;
    // Bit for bit: the passes are deterministic, so a pixel that differs shows a pass that kept its
    // output although something it reads changed, an input it does not declare.
    EXPECT_EQ(differing, 0) << method << ": " << p.key << " = " << value.dump()
                            << " gives another picture than a full recomputation: a pass reads it undeclared";
    renderer.render(base.scene, base.render, t);  // back to the base scene for the next parameter
  }
  EXPECT_GT(checked, 50) << "parameters changed";
  // The comparison has teeth only for changes the picture shows: the scene is made so that most do
  // (the other method's parameters, display-only ones and equivalent options such as sss.gather
  // do not).
  std::printf("[ %s ] %d of %d parameter changes show in the picture\n", method.c_str(), visible, checked);
  EXPECT_GE(visible, minimumVisible) << "the scene no longer shows what its parameters change";
}

// The no-cache method draws new samples every frame by design, so its pictures are compared through
// the light G-buffer pass it shares with the radiosity maps.
TEST(FrameInvalidation, RadiosityMapsRerunExactlyWhatTheirInputsName) { checkEveryParameter("radiosity-maps", 36); }
TEST(FrameInvalidation, SslpvRerunsExactlyWhatItsInputsName) { checkEveryParameter("sslpv", 23); }
TEST(FrameInvalidation, ImageSpaceRerunsExactlyWhatItsInputsName) { checkEveryParameter("image-space", 24); }
TEST(FrameInvalidation, AlbedoRerunsExactlyWhatItsInputsName) { checkEveryParameter("albedo", 13); }

}  // namespace
}  // namespace tallow
