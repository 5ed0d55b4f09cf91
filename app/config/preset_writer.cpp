#include "app/config/preset_writer.h"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "gpu/atomic_file.h"

namespace tallow::app {

namespace {
using ordered = nlohmann::ordered_json;

bool isDataName(const ordered& v) { return v.is_string() && v.get<std::string>().rfind("data:", 0) == 0; }
}  // namespace

std::string presetText(std::string_view sourceText, const Config& config, const Registry& registry,
                       const PresetState& state) {
  ordered doc;
  try {
    doc = ordered::parse(sourceText);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("the preset to save from is not JSON: ") + e.what());
  }
  if (!doc.is_object()) throw InputError("the preset to save from is not a JSON object");
  const sss::Scene& scene = config.scene;

  // Paths relative to the source preset's folder would break in another folder.
  if (doc.contains("objects") && doc["objects"].is_array()) {
    ordered& objects = doc["objects"];
    for (std::size_t i = 0; i < objects.size() && i < scene.objects.size(); ++i) {
      ordered& o = objects[i];
      if (o.contains("mesh") && !isDataName(o["mesh"])) o["mesh"] = scene.objects[i].meshPath.string();
      if (o.contains("field") && o["field"].is_object() && o["field"].contains("mesh") && !isDataName(o["field"]["mesh"]))
        o["field"]["mesh"] = scene.objects[i].field.meshPath.string();
    }
  }
  if (doc.contains("environment") && doc["environment"].is_object() && scene.environment &&
      !isDataName(doc["environment"]["file"]))
    doc["environment"]["file"] = scene.environment->file.string();

  ordered animation = doc.contains("animation") && doc["animation"].is_object() ? doc["animation"] : ordered::object();
  animation["duration_s"] = scene.durationS;
  animation["loop"] = state.loop;
  animation["start_s"] = state.timeS;
  doc["animation"] = animation;

  const nlohmann::json snapshot = registry.snapshot(config);
  ordered settings = ordered::object();
  for (const Registry::Param& p : registry.params()) {
    const nlohmann::json& v = snapshot.at(p.key);
    if (v.is_null()) continue;
    if (p.key == "material") {
      // "Marble (modified)": the row it came from, which the material.* values written after it
      // (registry order) then modify again, so the name reads back as well as the coefficients.
      std::string name = v.get<std::string>();
      if (name.size() > kModifiedSuffix.size() &&
          name.compare(name.size() - kModifiedSuffix.size(), kModifiedSuffix.size(), kModifiedSuffix) == 0)
        name.resize(name.size() - kModifiedSuffix.size());
      if (std::find(p.choices.begin(), p.choices.end(), name) == p.choices.end()) continue;
      settings[p.key] = name;
      continue;
    }
    if (p.key == "light.position" && !scene.lights.empty() && scene.lights.front().follow >= 0) continue;
    settings[p.key] = ordered::parse(v.dump());
  }
  doc["settings"] = settings;
  return doc.dump(2) + "\n";
}

void writePreset(const std::filesystem::path& file, std::string_view sourceText, const Config& config,
                 const Registry& registry, const PresetState& state) {
  gpu::writeTextFileAtomically(file, presetText(sourceText, config, registry, state));
}

}  // namespace tallow::app
