#pragma once
// The driver's limits the passes check their sizes against (checkLimits, every frame): read once
// when a context is loaded (GlContext::loadGl), so that a frame asks the driver nothing (issue 39,
// point 4: about 15 glGetIntegerv a frame before). Every context this program makes is on the same
// driver, so the limits of the context loaded last stand for all of them.
#include <glad/gl.h>

namespace tallow::gpu {

struct GlLimits {
  GLint maxTextureSize = 0;         ///< GL_MAX_TEXTURE_SIZE
  GLint maxCubeMapTextureSize = 0;  ///< GL_MAX_CUBE_MAP_TEXTURE_SIZE
  GLint max3dTextureSize = 0;       ///< GL_MAX_3D_TEXTURE_SIZE
  GLint maxArrayTextureLayers = 0;  ///< GL_MAX_ARRAY_TEXTURE_LAYERS
  GLint maxViewportDims[2] = {0, 0};  ///< GL_MAX_VIEWPORT_DIMS
  GLint maxShaderStorageBlockSize = 0;  ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE (as GLint, as before)
  GLint maxGeometryOutputVertices = 0;   ///< GL_MAX_GEOMETRY_OUTPUT_VERTICES (dual contouring's quads.geom)
  GLint maxTransformFeedbackBuffers = 0; ///< GL_MAX_TRANSFORM_FEEDBACK_BUFFERS
  bool layerInVertexShader = false;  ///< GL_ARB_shader_viewport_layer_array: gl_Layer in a vertex shader
  bool pipelineStatistics = false;   ///< GL_ARB_pipeline_statistics_query (core in 4.6)
};

/// Reads the limits of the current context (GlContext::loadGl calls it).
void readGlLimits();
/// The limits read last; read now when none were (a context loaded by other means).
const GlLimits& glLimits();

}  // namespace tallow::gpu
