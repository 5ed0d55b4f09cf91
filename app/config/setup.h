#pragma once
// What every command does first: find the data and preset folders, load the preset, apply --size
// and --set through the registry, and open the GL context the user asked for.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/config/config.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"
#include "sss/bssrdf/material.h"

namespace tallow::app {

/// Options shared by the rendering commands (view, capture).
struct SceneOptions {
  std::string preset;             ///< name in presets/ or a path; empty = the default preset
  std::vector<std::string> sets;  ///< "key=value", applied after the preset, in order
  std::string size;               ///< "WxH", empty = the registry's render.width/height
  std::string shaderDir;          ///< empty = the shaders embedded at build time
  bool explain = false;           ///< print the frame plan
};

/// The preset `tallow` runs without --preset.
std::string defaultPresetName();
/// $TALLOW_DATA_DIR, else ../shared/data beside the source checkout (set at configure time).
std::filesystem::path dataDir();
/// $TALLOW_PRESET_DIR, else presets/ of the source checkout.
std::filesystem::path presetDir();

struct LoadedScene {
  Config config;
  sss::MaterialTable materials;  ///< the table the preset's material names refer to
  std::filesystem::path presetPath;
  std::string presetName;
};

/// Loads the preset and applies --size and --set. Throws InputError with one line.
LoadedScene loadScene(const SceneOptions& options);

/// The shader sources: embedded, or from --shader-dir (which must exist).
gpu::ShaderLibrary makeShaderLibrary(const std::string& shaderDir);

/// Parses "WxH" (each 1..16384). Throws InputError.
std::pair<int, int> parseSize(const std::string& text);

}  // namespace tallow::app
