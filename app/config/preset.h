#pragma once
// Scene presets (presets/*.json → Config). The format is documented in docs/presets.md; every key
// is checked, and every error names file:line:col of the value or key to fix.
#include <filesystem>
#include <string>
#include <string_view>

#include "app/config/config.h"
#include "sss/bssrdf/material.h"

namespace tallow::app {

/// "bunny" → presetDir/bunny.json. Something containing '/' or ending in ".json" is a path, taken
/// as given. Throws InputError when the file does not exist; for a name, the message lists the
/// presets that do (with a did-you-mean suggestion).
std::filesystem::path resolvePresetName(std::string_view nameOrPath, const std::filesystem::path& presetDir);

/// Reads a preset file: registry defaults (parameterRegistry(materials)), then the preset's scene,
/// then its "settings". The caller applies --set afterwards. Mesh paths come back absolute: "data:x"
/// is dataDir/x, anything else is relative to the preset's folder; their existence is not checked.
/// Throws InputError `file:line:col: message` (the path as given names the file).
Config loadPreset(const std::filesystem::path& file, const sss::MaterialTable& materials,
                  const std::filesystem::path& dataDir);

/// The same from text in memory: `fileName` names it in messages and becomes scene.sourcePath;
/// `presetDir` is the folder relative mesh paths start from.
Config parsePreset(std::string_view text, const std::string& fileName, const std::filesystem::path& presetDir,
                   const sss::MaterialTable& materials, const std::filesystem::path& dataDir);

}  // namespace tallow::app
