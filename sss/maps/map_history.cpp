#include "sss/maps/map_history.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "sss/maps/radiosity_estimator.h"

namespace tallow::sss {

double shortestDiffusionLengthMm(const Scene& scene) {
  double shortest = 1e300;
  for (const SceneObject& o : scene.objects)
    if (o.translucent)
      for (int c = 0; c < 3; ++c)
        shortest = std::min(shortest, 1.0 / samplingSigmaTr(o.material.sigma_a[c], o.material.sigma_s[c],
                                                            o.material.g[c], o.material.eta));
  return shortest;
}

HistoryTolerance historyTolerance(const Scene& scene, double diffusionLengths) {
  constexpr double kMaxTurnDegrees = 25.0;
  HistoryTolerance t;
  t.maxMoveM = static_cast<float>(diffusionLengths * shortestDiffusionLengthMm(scene) * 1e-3);
  t.minCos = static_cast<float>(std::cos(kMaxTurnDegrees * 3.14159265358979323846 / 180.0));
  return t;
}

int historyRescaleLevel(int mapSize, double spanMm, double shortestDiffusionMm, double diffusionLengths) {
  const double texels = diffusionLengths * shortestDiffusionMm / std::max(spanMm, 1e-12) * mapSize;
  const int top = static_cast<int>(std::bit_width(static_cast<unsigned>(std::max(mapSize, 1)))) - 1;  // the last mip
  const int asked = texels > 1.0 ? static_cast<int>(std::lround(std::log2(texels))) : 0;
  return std::clamp(std::max(asked, kHistoryRescaleMinLevel), 0, top);
}

}  // namespace tallow::sss
