#include "app/config/setup.h"

#include <cstdlib>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/config/preset.h"
#include "sss/maps/environment_lights.h"

namespace tallow::app {

std::string defaultPresetName() { return "candle"; }

namespace {
std::filesystem::path fromEnvOr(const char* variable, const char* fallback) {
  const char* value = std::getenv(variable);
  return (value && *value) ? std::filesystem::path(value) : std::filesystem::path(fallback);
}
}  // namespace

std::filesystem::path dataDir() { return fromEnvOr("TALLOW_DATA_DIR", TALLOW_DEFAULT_DATA_DIR); }
std::filesystem::path presetDir() { return fromEnvOr("TALLOW_PRESET_DIR", TALLOW_DEFAULT_PRESET_DIR); }

LoadedScene loadScene(const SceneOptions& options) {
  const std::filesystem::path data = dataDir();
  const std::filesystem::path materialsCsv = data / "materials.csv";
  LoadedScene out;
  sss::MaterialTable& materials = out.materials;
  try {
    materials = sss::MaterialTable::load(materialsCsv);
  } catch (const std::exception& e) {
    throw InputError(std::string(e.what()) + " (set TALLOW_DATA_DIR to the folder holding materials.csv)");
  }
  out.presetName = options.preset.empty() ? defaultPresetName() : options.preset;
  out.presetPath = resolvePresetName(out.presetName, presetDir());
  out.config = loadPreset(out.presetPath, materials, data);
  // The preset's environment map becomes directional lights after the preset's own lights.
  if (const std::optional<sss::Environment>& env = out.config.scene.environment) {
    try {
      for (const sss::Light& l : sss::environmentLights(*env)) out.config.scene.lights.push_back(l);
    } catch (const std::exception& e) {
      throw InputError(out.presetPath.string() + ": environment: " + e.what());
    }
  }
  const Registry& registry = parameterRegistry(materials);
  // The lights drawn from an environment map hold to the range a light given by hand has.
  if (const std::optional<sss::Environment>& env = out.config.scene.environment) {
    const Registry::Param& intensity = *registry.find("light.intensity");
    for (const sss::Light& l : out.config.scene.lights)
      for (int b = 0; b < 3; ++b)
        if (!(l.intensity[b] <= intensity.max))
          throw InputError(out.presetPath.string() + ": environment: " + env->file.string() +
                           ": a light drawn from it has an irradiance of " + formatNumber(l.intensity[b]) +
                           " W/m², beyond light.intensity's range [0, " + formatNumber(intensity.max) +
                           "]; scale the map down with \"intensity\"");
  }
  if (!options.size.empty()) {
    const auto [w, h] = parseSize(options.size);
    registry.set(out.config, "render.width", w);
    registry.set(out.config, "render.height", h);
  }
  for (const std::string& s : options.sets) {
    try {
      registry.setFromString(out.config, s);
    } catch (const InputError& e) {
      throw InputError("--set " + s + ": " + e.what());
    }
  }
  return out;
}

gpu::ShaderLibrary makeShaderLibrary(const std::string& shaderDir) {
  if (shaderDir.empty()) return gpu::ShaderLibrary();
  if (!std::filesystem::is_directory(shaderDir)) throw InputError("--shader-dir: " + shaderDir + " is not a folder");
  return gpu::ShaderLibrary(std::filesystem::path(shaderDir));
}

}  // namespace tallow::app
