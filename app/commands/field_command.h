#pragma once
// `tallow field`: the continuous field of a preset's field objects at time t, evaluated at the
// points of a CSV file (world units), written as x,y,z,value,grad_x,grad_y,grad_z. Several field
// objects are combined by their union: the smallest value, with the gradient of the object that
// gave it. Also the pieces `tallow mesh` shares: the field objects of a scene and their transforms.
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "app/commands/points_csv.h"
#include "app/config/setup.h"
#include "sss/field_source.h"
#include "sss/scene.h"

namespace tallow::app {

/// A field object of a scene with its object → world transform (SceneGeometry::modelMatrix).
struct PlacedField {
  int objectIndex = 0;
  sss::FieldSource source;
  glm::dmat4 model{1.0};
};

/// Every field object of `scene`, in scene order. Throws InputError (`preset "NAME" has no field
/// objects …`) when there is none; std::runtime_error when a mesh field's file cannot be read.
std::vector<PlacedField> placeFields(const sss::Scene& scene, const std::string& presetName);

/// The union of `fields` at time t at each world point: value = min over the objects of
/// value(M⁻¹p), gradient = that object's ∇value turned back into world axes by (M⁻¹)ᵀ.
std::vector<FieldSample> evaluateFields(const std::vector<PlacedField>& fields, double timeS,
                                        const std::vector<glm::dvec3>& points);

struct FieldOptions {
  SceneOptions scene;  ///< preset and --set (size, shaders and --explain are not used)
  double timeS = 0.0;
  std::string in;      ///< POINTS.csv
  std::string out;     ///< VALUES.csv
};

/// Returns the exit code; throws InputError / std::runtime_error with one line on failure, before
/// anything is written.
int runField(const FieldOptions& options);

}  // namespace tallow::app
