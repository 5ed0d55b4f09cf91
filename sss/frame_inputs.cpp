#include "sss/frame_inputs.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <utility>

namespace tallow::sss {

Fingerprint& Fingerprint::bytes(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h_ ^= p[i];
    h_ *= 1099511628211ull;
  }
  return *this;
}

namespace {

using Hasher = std::function<void(Fingerprint&, const FrameState&)>;

/// A settings input: the registry key and the one field of RenderSettings it sets.
template <typename Field>
std::pair<std::string, Hasher> setting(std::string key, Field field) {
  return {std::move(key), [field](Fingerprint& f, const FrameState& s) { f << field(s.settings); }};
}

Fingerprint& operator<<(Fingerprint& f, const Material& m) {
  // The coefficients only: the name is a label (a measured material edited keeps its name).
  return f << m.sigma_a << m.sigma_s << m.g << m.eta;
}

/// Every input with how its value is fingerprinted. The settings keys are the registry's
/// (app/config/params.cpp); tests/frame_invalidation_gltest.cpp checks the two lists agree.
const std::vector<std::pair<std::string, Hasher>>& table() {
  static const std::vector<std::pair<std::string, Hasher>> inputs = [] {
    std::vector<std::pair<std::string, Hasher>> t;
    using S = const RenderSettings&;
    t.push_back(setting("render.width", [](S s) { return s.width; }));
    t.push_back(setting("render.height", [](S s) { return s.height; }));
    t.push_back(setting("render.shadows", [](S s) { return s.shadows; }));
    t.push_back(setting("render.shadow_map_size", [](S s) { return s.shadowMapSize; }));
    t.push_back(setting("render.shadow_bias", [](S s) { return s.shadowBias; }));
    t.push_back(setting("render.pcf_radius", [](S s) { return s.pcfRadius; }));
    t.push_back(setting("render.tonemap", [](S s) { return s.toneMap.op; }));
    t.push_back(setting("render.exposure_ev", [](S s) { return s.toneMap.exposureEv; }));
    t.push_back(setting("render.aa", [](S s) { return s.aaSamples; }));
    t.push_back(setting("render.bloom", [](S s) { return s.bloom; }));
    t.push_back(setting("render.local_exposure", [](S s) { return s.localExposure; }));
    t.push_back(setting("render.specular", [](S s) { return s.specular; }));
    t.push_back(setting("render.flame", [](S s) { return s.flame; }));
    t.push_back(setting("flame.exposure_ev", [](S s) { return s.flameExposureEv; }));
    t.push_back(setting("field.res", [](S s) { return s.fieldRes; }));
    t.push_back(setting("field.placement", [](S s) { return s.fieldPlacement; }));
    t.push_back(setting("field.evaluate", [](S s) { return s.fieldOnGpu; }));
    t.push_back(setting("field.extraction", [](S s) { return s.fieldExtraction; }));
    t.push_back(setting("method", [](S s) { return s.sss.method; }));
    t.push_back(setting("sss.model", [](S s) { return s.sss.model; }));
    t.push_back(setting("sss.maps", [](S s) { return s.sss.maps; }));
    t.push_back(setting("sss.samples", [](S s) { return s.sss.samples; }));
    t.push_back(setting("sss.map_size", [](S s) { return s.sss.mapSize; }));
    t.push_back(setting("sss.light_map_size", [](S s) { return s.sss.lightMapSize; }));
    t.push_back(setting("sss.bias", [](S s) { return s.sss.bias; }));
    t.push_back(setting("sss.comb", [](S s) { return s.sss.comb; }));
    t.push_back(setting("sss.view_weight", [](S s) { return s.sss.viewWeight; }));
    t.push_back(setting("sss.frames", [](S s) { return s.sss.frames; }));
    t.push_back(setting("sss.history", [](S s) { return s.sss.history; }));
    t.push_back(setting("sss.history_move", [](S s) { return s.sss.historyMove; }));
    t.push_back(setting("sss.history_rescale", [](S s) { return s.sss.historyRescale; }));
    t.push_back(setting("sss.light_map_auto", [](S s) { return s.sss.lightMapAuto; }));
    t.push_back(setting("sss.projected_area", [](S s) { return s.sss.projectedArea; }));
    t.push_back(setting("sss.texel_plane", [](S s) { return s.sss.texelPlane; }));
    t.push_back(setting("sss.gather", [](S s) { return s.sss.computeGather; }));
    t.push_back(setting("sss.stereographic", [](S s) { return s.sss.stereographic; }));
    t.push_back(setting("sss.point_share", [](S s) { return s.sss.pointShare; }));
    t.push_back(setting("sslpv.grid", [](S s) { return s.sslpv.grid; }));
    t.push_back(setting("sslpv.steps", [](S s) { return s.sslpv.steps; }));
    t.push_back(setting("sslpv.skip", [](S s) { return s.sslpv.skip; }));
    t.push_back(setting("sslpv.inject_size", [](S s) { return s.sslpv.injectSize; }));
    t.push_back(setting("sslpv.exitance", [](S s) { return s.sslpv.exitance; }));
    t.push_back(setting("vpl.count", [](S s) { return s.vpl.count; }));
    t.push_back(setting("vpl.cube_size", [](S s) { return s.vpl.cubeSize; }));
    t.push_back(setting("vpl.placement", [](S s) { return s.vpl.placement; }));
    t.push_back(setting("vpl.area", [](S s) { return s.vpl.area; }));
    t.push_back(setting("vpl.stable", [](S s) { return s.vpl.stable; }));
    t.push_back(setting("vpl.shadows", [](S s) { return s.vpl.shadows; }));
    t.push_back(setting("vpl.shadow_clusters", [](S s) { return s.vpl.shadowClusters; }));
    t.push_back(setting("vpl.shadow_size", [](S s) { return s.vpl.shadowSize; }));
    t.push_back(setting("image_space.samples", [](S s) { return s.imageSpace.samples; }));
    t.push_back(setting("image_space.uniform_share", [](S s) { return s.imageSpace.uniformShare; }));
    t.push_back(setting("image_space.tile", [](S s) { return s.imageSpace.tile; }));
    t.push_back(setting("image_space.radius", [](S s) { return s.imageSpace.radius; }));
    t.push_back(setting("image_space.frames", [](S s) { return s.imageSpace.frames; }));
    t.push_back(setting("image_space.depth_ratio", [](S s) { return s.imageSpace.depthRatio; }));
    t.push_back(setting("image_space.jacobian", [](S s) { return s.imageSpace.jacobian; }));
    t.push_back(setting("image_space.renormalize", [](S s) { return s.imageSpace.renormalize; }));
    t.push_back(setting("burley.samples", [](S s) { return s.burley.samples; }));
    t.push_back(setting("burley.transmission", [](S s) { return s.burley.transmission; }));
    t.push_back(setting("burley.kernel", [](S s) { return s.burley.kernel; }));

    const auto scene = [&t](std::string name, Hasher h) { t.emplace_back(std::move(name), std::move(h)); };
    scene("scene.shapes", [](Fingerprint& f, const FrameState& s) {
      f << s.scene.objects.size();
      for (const SceneObject& o : s.scene.objects) {
        f << o.shape << o.meshPath.string() << o.field.kind << o.field.blobScale << o.field.candleDurationS
          << o.field.candleTimeScale << o.field.candleDrips << o.field.candleSeed << o.field.meshPath.string() << o.field.meltDurationS << o.size << o.transform.position
          << o.transform.rotationDeg << o.transform.scale << o.translucent;
      }
    });
    scene("scene.albedo", [](Fingerprint& f, const FrameState& s) {
      for (const SceneObject& o : s.scene.objects) f << o.albedo;
    });
    scene("scene.materials", [](Fingerprint& f, const FrameState& s) {
      for (const SceneObject& o : s.scene.objects) {
        f << o.material << o.volume.has_value() << o.liquidMaterial.has_value();
        if (o.liquidMaterial) f << *o.liquidMaterial;  // the pool's region follows t ("time")
        if (!o.volume) continue;
        const MaterialVolume& v = *o.volume;
        f << v.material << v.axis << v.period << v.fraction << v.turbulence << v.seed;
      }
    });
    // A light that follows a candle's flame is placed and coloured by the flame at t (sceneAtTime),
    // which flame.flicker changes: part of both.
    scene("scene.light_placement", [](Fingerprint& f, const FrameState& s) {
      f << s.scene.lights.size() << s.scene.flameFlicker;
      for (const Light& l : s.scene.lights) f << l.kind << l.direction << l.position << l.castsShadows;
    });
    scene("scene.light_intensity", [](Fingerprint& f, const FrameState& s) {
      f << s.scene.flameFlicker;
      for (const Light& l : s.scene.lights) f << l.intensity;
    });
    scene("scene.camera", [](Fingerprint& f, const FrameState& s) {
      const Camera& c = s.scene.camera;
      f << c.orthographic << c.position << c.target << c.up << c.fovYDeg << c.orthoHeight;
    });
    scene("scene.environment", [](Fingerprint& f, const FrameState& s) {
      f << s.scene.environment.has_value();
      if (const auto& e = s.scene.environment) f << e->file.string() << e->lights << e->rotationDeg << e->scale;
    });
    scene("scene.ambient", [](Fingerprint& f, const FrameState& s) { f << s.scene.ambient; });
    scene("scene.background", [](Fingerprint& f, const FrameState& s) { f << s.scene.background; });
    scene("scene.map_directions", [](Fingerprint& f, const FrameState& s) {
      f << s.scene.mapDirections.size();
      for (const glm::vec3& d : s.scene.mapDirections) f << d;
    });
    scene("time", [](Fingerprint& f, const FrameState& s) { f << s.timeS; });
    scene("accumulation", [](Fingerprint& f, const FrameState& s) { f << s.accumulation; });
    return t;
  }();
  return inputs;
}

const Hasher* find(std::string_view name) {
  for (const auto& [key, hasher] : table())
    if (key == name) return &hasher;
  return nullptr;
}

}  // namespace

std::uint64_t inputFingerprint(std::string_view name, const FrameState& state) {
  const Hasher* h = find(name);
  if (!h) throw std::logic_error("unknown frame input \"" + std::string(name) + "\"");
  Fingerprint f;
  (*h)(f, state);
  return f.value();
}

const std::vector<std::string>& inputNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& entry : table()) n.push_back(entry.first);
    return n;
  }();
  return names;
}

bool isInput(std::string_view name) { return find(name) != nullptr; }

bool isDisplayOnlyInput(std::string_view name) { return name == "render.tonemap" || name == "render.exposure_ev"; }

}  // namespace tallow::sss
