#pragma once
// The translucent slots of a frame (issue 35): each translucent object has a slot, the index the
// GPU passes use for its material (G-buffer tags are slot + 1); an object with a liquid part (a
// candle's melt pool, SceneObject::liquidMaterial) has a second slot right after it for the liquid.
// Which slot a surface point belongs to is decided by shaders/materials/liquid_surface.glsl, in GLSL
// (materials/slots.glsl) and in C++ (materialAt) alike. Light scatters between the slots of one
// object: the pool and the wax are one body, each point exits with its own material's BSSRDF.
#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/program.h"
#include "sss/scene.h"

namespace tallow::sss {

/// Slots the GPU passes hold (shaders/materials/slots.glsl SSS_MAX_SLOTS).
inline constexpr int kMaxTranslucentSlots = 8;

struct SlotTable {
  std::vector<int> objectSlot;  ///< per scene object: its main slot, −1 for an opaque one
  int count = 0;                ///< slots in use
  std::array<int, kMaxTranslucentSlots> slotObject{};   ///< the object of each slot (−1 unused)
  std::array<int, kMaxTranslucentSlots> liquidSlot{};   ///< per slot: its object's liquid slot, −1 none
  std::array<glm::vec4, kMaxTranslucentSlots> liquidRegion{};
  std::array<glm::mat4, kMaxTranslucentSlots> worldToObject{};
  std::array<Material, kMaxTranslucentSlots> material{};
};

/// The slots of `scene` (as sceneAtTime left it: the liquid regions of this t). Throws
/// std::invalid_argument when the scene needs more than kMaxTranslucentSlots (a pool counts one).
SlotTable translucentSlotTable(const Scene& scene);

/// Slots `scene` needs: one per translucent object, one more per liquid.
int translucentSlotsNeeded(const Scene& scene);

/// True when the object-space point p with normal n lies on the liquid of `region`
/// (shaders/materials/liquid_surface.glsl, in double).
bool liquidSurfaceContains(const glm::dvec3& p, const glm::dvec3& n, const glm::vec4& region);

/// Where an object's surface is liquid at the frame's t, ready to test many points.
struct LiquidPart {
  glm::dmat4 worldToObject{1.0};  ///< computed once (a field's transform is rigid)
  glm::vec4 region{0.0f};         ///< SceneObject::liquidRegion
  /// liquidSurfaceContains at a world point and normal.
  bool contains(const glm::dvec3& worldPoint, const glm::dvec3& worldNormal) const;
};

/// The liquid part of `object` (as sceneAtTime left it), or none when it has no pool now.
std::optional<LiquidPart> liquidPart(const SceneObject& object);

/// The material at a surface point of `object` (world position and normal): the liquid's where
/// liquidSurfaceContains says so, else the object's. Many points: test liquidPart(object) instead.
const Material& materialAt(const SceneObject& object, const glm::dvec3& worldPoint, const glm::dvec3& worldNormal);

/// Sets materials/slots.glsl's uniforms (those `p` uses, η per slot included) and, when `materials`,
/// gather.glsl's per-slot coefficients (uSigmaA, uSigmaS, uG). Unused slots get a harmless medium.
void setSlotUniforms(gpu::Program& p, const SlotTable& table, bool materials);

}  // namespace tallow::sss
