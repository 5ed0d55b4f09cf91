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
  gLimits = l;
  gRead = true;
}

const GlLimits& glLimits() {
  if (!gRead) readGlLimits();
  return gLimits;
}

}  // namespace tallow::gpu
