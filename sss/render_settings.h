#pragma once
// Every tunable of the renderer, one field each. The names, ranges, defaults and help live in one
// place only, the parameter registry (app/params.cpp); this struct just holds the values.
#include "gpu/tonemap.h"

namespace tallow::sss {

struct RenderSettings {
  int width = 0;              ///< render.width [px]
  int height = 0;             ///< render.height [px]
  bool shadows = false;       ///< render.shadows
  int shadowMapSize = 0;      ///< render.shadow_map_size [texels]
  float shadowBias = 0.0f;    ///< render.shadow_bias [shadow-map texels along the normal]
  int pcfRadius = 0;          ///< render.pcf_radius [texels]
  int fieldRes = 0;           ///< field.res [lattice samples per axis]
  gpu::ToneMapSettings toneMap;  ///< render.tonemap, render.exposure_ev
};

}  // namespace tallow::sss
