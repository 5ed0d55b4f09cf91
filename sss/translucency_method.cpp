#include "sss/translucency_method.h"

#include <algorithm>

namespace tallow::sss {

bool anyTranslucent(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) { return o.translucent; });
}

std::string AlbedoMethod::describeShading(const FrameState&) const {
  return "translucent ones with their albedo (method albedo: no transport)";
}

}  // namespace tallow::sss
