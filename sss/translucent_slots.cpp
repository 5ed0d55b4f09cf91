#include "sss/translucent_slots.h"

#include <stdexcept>
#include <string>

#include "gpu/glsl_shared.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

namespace liquid_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/materials/liquid_surface.glsl"
}  // namespace liquid_f64

namespace {
/// A field's transform is rigid (SceneGeometry::modelMatrix: translation and rotation only).
glm::dmat4 worldToObject(const SceneObject& o) {
  return glm::inverse(glm::dmat4(SceneGeometry::modelMatrix(o, geometry::Aabb{})));
}
}  // namespace

int translucentSlotsNeeded(const Scene& scene) {
  int n = 0;
  for (const SceneObject& o : scene.objects)
    if (o.translucent) n += o.liquidMaterial ? 2 : 1;
  return n;
}

SlotTable translucentSlotTable(const Scene& scene) {
  const int needed = translucentSlotsNeeded(scene);
  if (needed > kMaxTranslucentSlots)
    throw std::invalid_argument("the scene's translucent objects need " + std::to_string(needed) +
                                " material slots (a melt pool takes one more); the GPU passes hold at most " +
                                std::to_string(kMaxTranslucentSlots));
  SlotTable t;
  t.objectSlot.assign(scene.objects.size(), -1);
  t.slotObject.fill(-1);
  t.liquidSlot.fill(-1);
  t.liquidRegion.fill(glm::vec4(0.0f));
  t.worldToObject.fill(glm::mat4(1.0f));
  Material harmless;  // σ_s = 1, η = 1: no shader divides by zero in an unused slot
  harmless.sigma_s = glm::vec3(1.0f);
  harmless.eta = 1.0f;
  t.material.fill(harmless);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (!o.translucent) continue;
    const int slot = t.count++;
    t.objectSlot[i] = slot;
    const auto s = static_cast<std::size_t>(slot);
    t.slotObject[s] = static_cast<int>(i);
    t.material[s] = o.material;
    if (!o.liquidMaterial) continue;
    const int liquid = t.count++;
    const auto l = static_cast<std::size_t>(liquid);
    const glm::mat4 toObject(worldToObject(o));
    t.slotObject[l] = static_cast<int>(i);
    t.material[l] = *o.liquidMaterial;
    for (const std::size_t k : {s, l}) {
      t.liquidSlot[k] = liquid;
      t.liquidRegion[k] = o.liquidRegion;
      t.worldToObject[k] = toObject;
    }
  }
  return t;
}

bool liquidSurfaceContains(const glm::dvec3& p, const glm::dvec3& n, const glm::vec4& region) {
  return liquid_f64::liquidSurfaceContains(p, n, glm::dvec4(region));
}

bool LiquidPart::contains(const glm::dvec3& worldPoint, const glm::dvec3& worldNormal) const {
  const glm::dvec3 p(worldToObject * glm::dvec4(worldPoint, 1.0));
  return liquidSurfaceContains(p, glm::dmat3(worldToObject) * worldNormal, region);
}

std::optional<LiquidPart> liquidPart(const SceneObject& object) {
  if (!object.liquidMaterial || !(object.liquidRegion.y > 0.0f)) return std::nullopt;
  return LiquidPart{worldToObject(object), object.liquidRegion};
}

const Material& materialAt(const SceneObject& object, const glm::dvec3& worldPoint, const glm::dvec3& worldNormal) {
  const std::optional<LiquidPart> part = liquidPart(object);
  return part && part->contains(worldPoint, worldNormal) ? *object.liquidMaterial : object.material;
}

void setSlotUniforms(gpu::Program& p, const SlotTable& t, bool materials) {
  constexpr int n = kMaxTranslucentSlots;
  glProgramUniform1iv(p.id(), p.location("uSlotObject"), n, t.slotObject.data());
  glProgramUniform1iv(p.id(), p.location("uSlotLiquid"), n, t.liquidSlot.data());
  p.set("uSlotLiquidRegion", t.liquidRegion.data(), n);
  p.set("uSlotWorldToObject", t.worldToObject.data(), n);
  std::array<float, n> eta{};
  std::array<glm::vec3, n> sigmaA{}, sigmaS{}, g{};
  for (std::size_t s = 0; s < t.material.size(); ++s) {
    eta[s] = t.material[s].eta;
    sigmaA[s] = t.material[s].sigma_a;
    sigmaS[s] = t.material[s].sigma_s;
    g[s] = t.material[s].g;
  }
  glProgramUniform1fv(p.id(), p.location("uSlotEta"), n, eta.data());
  if (!materials) return;
  p.set("uSigmaA", sigmaA.data(), n);
  p.set("uSigmaS", sigmaS.data(), n);
  p.set("uG", g.data(), n);
}

}  // namespace tallow::sss
