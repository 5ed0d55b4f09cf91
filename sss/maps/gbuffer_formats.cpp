#include "sss/maps/gbuffer_formats.h"

#include <atomic>

namespace tallow::sss {
namespace {
std::atomic<GLenum> normalFormat{GL_RGBA16F};
}  // namespace

GLenum gBufferNormalFormat() { return normalFormat.load(); }

void setGBufferNormalFormat(GLenum format) { normalFormat.store(format); }

}  // namespace tallow::sss
