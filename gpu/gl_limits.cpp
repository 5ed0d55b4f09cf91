#include "gpu/gl_limits.h"

namespace tallow::gpu {
namespace {
GlLimits gLimits;
bool gRead = false;
}  // namespace

void readGlLimits() {
  GlLimits l;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
  glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &l.maxCubeMapTextureSize);
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &l.max3dTextureSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &l.maxArrayTextureLayers);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, l.maxViewportDims);
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &l.maxShaderStorageBlockSize);
  glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &l.maxGeometryOutputVertices);
  glGetIntegerv(GL_MAX_TRANSFORM_FEEDBACK_BUFFERS, &l.maxTransformFeedbackBuffers);
  l.layerInVertexShader = GLAD_GL_ARB_shader_viewport_layer_array != 0;
  l.pipelineStatistics = GLAD_GL_ARB_pipeline_statistics_query != 0;
  gLimits = l;
  gRead = true;
}

const GlLimits& glLimits() {
  if (!gRead) readGlLimits();
  return gLimits;
}

}  // namespace tallow::gpu
