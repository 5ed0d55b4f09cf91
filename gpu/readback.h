#pragma once
// Read-back of render targets into CPU images (top row first, as files store them).
#include <cstdint>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/image.h"

namespace tallow::gpu {

/// Reads colour attachment `attachment` of `fb` (any colour format) as linear RGBA floats.
Image readColor(const Framebuffer& fb, int attachment, int width, int height);
/// Reads the back buffer of the window's default framebuffer (what the next swap shows) as 8-bit
/// RGB, top row first: the pixels as displayed, already tone-mapped and sRGB-encoded.
std::vector<std::uint8_t> readWindowRgb8(int width, int height);
/// Reads level 0 of a 2D texture as RGBA floats (missing channels as GL fills them: 0, 0, 1).
Image readTexture(const Texture& texture);

}  // namespace tallow::gpu
