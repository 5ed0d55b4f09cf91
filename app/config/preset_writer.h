#pragma once
// "Save as preset" of the view window: a preset file that `tallow capture --preset FILE`
// renders as the window showed it. The scene (camera type, lights, objects, environment, map
// directions) is the preset the window loaded; every value the registry can set — camera,
// material, light, every renderer setting — is written under "settings" from the registry's
// snapshot (app/config/registry.h), so the file holds the window's state, not just the preset's.
#include <filesystem>
#include <string>
#include <string_view>

#include "app/config/config.h"
#include "app/config/registry.h"

namespace tallow::app {

struct PresetState {
  double timeS = 0.0;  ///< becomes animation.start_s: the time capture's first frame shows
  bool loop = true;    ///< becomes animation.loop
};

/// The preset text (JSON, two-space indent, the source's key order). `sourceText` is the preset
/// `config` was loaded from (its scene.sourcePath); mesh and environment paths that are not
/// "data:" names are written absolute (from `config`), so the file works from any folder. Values
/// that do not apply (null in the snapshot), a material name that is not a row of the table (its
/// coefficients, material.*, carry it; an edited row, "Marble (modified)", is written as the row,
/// which the coefficients after it modify again), and the position of a light that follows a
/// flame are left out. Throws InputError when `sourceText` is not a JSON object.
std::string presetText(std::string_view sourceText, const Config& config, const Registry& registry,
                       const PresetState& state);

/// presetText written atomically to `file` (std::runtime_error `cannot write …` on failure).
void writePreset(const std::filesystem::path& file, std::string_view sourceText, const Config& config,
                 const Registry& registry, const PresetState& state);

}  // namespace tallow::app
