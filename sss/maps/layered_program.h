#pragma once
// The programs of the layered passes (maps/layered.vert, a fragment shader): the layer written by
// the vertex shader where the driver offers GL_ARB_shader_viewport_layer_array, else by the
// pass-through geometry shader maps/layered.geom (issue 39, point 3: on GPUs with few raster
// units a geometry shader per triangle is the pass's bottleneck).
#include <string>

#include "gpu/program.h"

namespace tallow::sss {

/// Vertex (+ geometry) + `fragment` stages for a layered pass.
gpu::ProgramDesc layeredProgram(const std::string& fragment);
/// Whether layeredProgram writes the layer in the vertex shader: the driver offers it and
/// allowLayerInVertexShader has not forbidden it.
bool layerInVertexShader();
/// Tests build both variants: false makes later programs use the geometry shader.
void allowLayerInVertexShader(bool allow);

}  // namespace tallow::sss
