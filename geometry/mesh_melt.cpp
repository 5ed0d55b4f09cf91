#include "geometry/mesh_melt.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

// PNanoVDB's C port reads NanoVDB grids from a plain array of 32-bit words: the same functions the
// GPU runs as GLSL (fields/melt_uniforms.glsl) over the same bytes. 32-bit addresses as on the GPU.
#define PNANOVDB_C
#define PNANOVDB_ADDRESS_32
#include <nanovdb/PNanoVDB.h>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// The melt per point: the lines the GPU evaluates (shaders/fields/melt.glsl), compiled here in
// double, the precision the CPU mesher, `tallow field` and the reference integrator use.
namespace tallow::geometry::melt_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/fields/melt.glsl"
}  // namespace tallow::geometry::melt_f64

namespace tallow::geometry {

namespace {

pnanovdb_buf_t bufferOf(const MeltGrids& grids) {
  // PNanoVDB's C buffer holds a non-const pointer; it only ever reads through it.
  return pnanovdb_make_buf(const_cast<std::uint32_t*>(grids.nanoVdb.data()), grids.nanoVdb.size());
}

melt_f64::MeltShape shapeOf(const MeltGrids& grids, const MeltState& s) {
  melt_f64::MeltShape m;
  m.anchor = grids.anchor;
  m.heightScale = s.heightScale;
  m.invVoxel = 1.0 / grids.voxelSize;
  m.gridA = s.gridA;
  m.gridB = s.gridB;
  m.blend = s.blend;
  m.puddleRadius = s.puddleRadius;
  m.puddleHeight = s.puddleHeight;
  m.joinRadius = s.joinRadius;
  m.boxLo = grids.backgroundBoxLo();
  m.boxHi = grids.backgroundBoxHi();
  m.background = grids.bandWidth;
  return m;
}

}  // namespace

void checkMeltParams(const MeltParams& p, double t) {
  if (!(p.durationS > 0.0) || !(p.slump >= 0.0 && p.slump <= 0.9) || !(p.puddleSpread >= 0.0) ||
      !(p.puddleHeight >= 0.0 && p.puddleHeight <= 1.0) || p.smoothingIterations < 0 || p.smoothingIterations > 200 ||
      !std::isfinite(t))
    throw std::invalid_argument("MeltParams: durationS > 0, slump in [0, 0.9], puddleSpread >= 0, puddleHeight in [0, 1], "
                                "smoothingIterations in [0, 200], t finite");
}

MeltState meltStateAt(const MeltGrids& grids, double t, const MeltParams& p) {
  checkMeltParams(p, t);
  if (grids.smoothingIterations != p.smoothingIterations || grids.iterations.empty())
    throw std::logic_error("meltStateAt: grids built for another smoothing count");
  MeltState s;
  s.f = std::clamp(t / p.durationS, 0.0, 1.0);
  s.heightScale = 1.0 - p.slump * s.f;
  // Rounding: f·N mean-curvature steps, between the two levels that bracket it.
  const double steps = p.smoothingIterations * s.f;
  std::size_t below = 0;
  while (below + 1 < grids.iterations.size() && grids.iterations[below + 1] <= steps) ++below;
  s.gridA = grids.gridAddress[below];
  s.gridB = s.gridA;
  if (below + 1 < grids.iterations.size()) {
    const double lo = grids.iterations[below], hi = grids.iterations[below + 1];
    s.gridB = grids.gridAddress[below + 1];
    s.blend = (steps - lo) / (hi - lo);
  }
  // The puddle: as thick as puddleHeight·height·f once that exceeds a voxel, as wide as the
  // slumped footprint times 1 + spread·f (the CSG melt's disc, issue 4).
  const double thickness = p.puddleHeight * grids.height * s.f;
  if (thickness > grids.voxelSize) {
    s.puddleHeight = thickness;
    s.puddleRadius = grids.footprint / std::sqrt(s.heightScale) * (1.0 + p.puddleSpread * s.f);
    s.joinRadius = std::min(thickness, grids.bandWidth * s.heightScale);
  }
  return s;
}

double meltValue(const MeltGrids& grids, const MeltState& state, glm::dvec3 p) {
  return melt_f64::meltFieldValue(bufferOf(grids), p, shapeOf(grids, state));
}

double meltLevelSample(const MeltGrids& grids, int level, glm::dvec3 p) {
  return melt_f64::meltGridSample(bufferOf(grids), grids.gridAddress.at(static_cast<std::size_t>(level)),
                                  p / grids.voxelSize);
}

Aabb meltBounds(const MeltGrids& grids, const MeltState& s) {
  // The body: the levels' box under the slump M (x, z widen by 1/√s, y shrinks by s, about the anchor).
  const glm::dvec3 a = grids.anchor;
  const glm::dvec3 scale(1.0 / std::sqrt(s.heightScale), s.heightScale, 1.0 / std::sqrt(s.heightScale));
  Aabb box;
  for (const glm::vec3& corner : {grids.levelBounds.min, grids.levelBounds.max})
    box.extend(glm::vec3(a + (glm::dvec3(corner) - a) * scale));
  if (s.puddleHeight > 0.0) {  // the puddle's box, padded by the band as the body's is
    const double r = s.puddleRadius + grids.bandWidth;
    box.extend(glm::vec3(a + glm::dvec3(-r, -grids.bandWidth, -r)));
    box.extend(glm::vec3(a + glm::dvec3(r, s.puddleHeight + grids.bandWidth, r)));
  }
  // The smooth union lies at most k/4 outside both shapes.
  const auto pad = static_cast<float>(0.25 * s.joinRadius);
  box.min -= glm::vec3(pad);
  box.max += glm::vec3(pad);
  return box;
}

}  // namespace tallow::geometry
