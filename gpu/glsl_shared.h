#pragma once
// Compiles shared GLSL include files (shaders/common/*.glsl and later the BSSRDF models) as C++
// through GLM, so that the CPU code, the tests and the GPU passes evaluate the same lines.
// Include this header, then the .glsl file, inside namespace tallow::glsl.
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#ifndef TALLOW_FN
#define TALLOW_FN inline
#endif

namespace tallow::glsl {
using namespace glm;  // GLSL's vocabulary: vec3, dot, clamp, pow, …
}  // namespace tallow::glsl
