#include "app/commands/field_command.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "gpu/atomic_file.h"
#include "sss/scene_geometry.h"

namespace tallow::app {

std::vector<PlacedField> placeFields(const sss::Scene& scene, const std::string& presetName) {
  std::vector<PlacedField> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const sss::SceneObject& o = scene.objects[i];
    if (o.shape != sss::ShapeKind::Field) continue;
    sss::FieldSource source(o);
    const glm::dmat4 model(sss::SceneGeometry::modelMatrix(o, source.bounds()));
    out.push_back({static_cast<int>(i), std::move(source), model});
  }
  if (out.empty())
    throw InputError("preset " + quote(presetName) + " has no field objects (objects with a \"field\": blob, candle or mesh)");
  return out;
}

std::vector<FieldSample> evaluateFields(const std::vector<PlacedField>& fields, double timeS,
                                        const std::vector<glm::dvec3>& points) {
  std::vector<FieldSample> samples(points.size());
  for (FieldSample& s : samples) s.value = std::numeric_limits<double>::infinity();
  for (const PlacedField& f : fields) {
    const auto field = f.source.at(timeS);
    const glm::dmat4 toField = glm::inverse(f.model);
    // A gradient is a covector: it maps back with the inverse transpose (here the rotation itself,
    // since field transforms are rigid).
    const glm::dmat3 gradientToWorld = glm::transpose(glm::dmat3(toField));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 q(toField * glm::dvec4(points[i], 1.0));
      const double v = field->value(q);
      if (v < samples[i].value) samples[i] = {v, gradientToWorld * field->gradient(q)};
    }
  }
  return samples;
}

int runField(const FieldOptions& options) {
  if (options.in.empty()) throw InputError("field: --in POINTS.csv is required");
  if (options.out.empty()) throw InputError("field: --out VALUES.csv is required");
  checkTime("--time", options.timeS);
  checkOutputFile("--out", options.out);
  const LoadedScene loaded = loadScene(options.scene);
  const std::vector<glm::dvec3> points = parseInputFile(
      options.in, [&](const std::string& text) { return parsePoints(text, options.in); }, gpu::kMaxTableFileBytes,
      "a CSV table");
  const std::vector<PlacedField> fields = placeFields(loaded.config.scene, loaded.presetName);
  const std::vector<FieldSample> samples = evaluateFields(fields, options.timeS, points);
  gpu::writeTextFileAtomically(options.out, formatFieldValues(points, samples));
  std::printf("tallow: %zu point(s), %zu field object(s) of %s at t = %g s -> %s\n", points.size(), fields.size(),
              loaded.presetName.c_str(), options.timeS, options.out.c_str());
  return 0;
}

}  // namespace tallow::app
