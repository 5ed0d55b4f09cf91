#pragma once
// Read-back of render targets into CPU images (top row first, as files store them): at once
// (readColor, readTexture, readWindowRgb8: the GPU's work is waited for), or through a ring of
// pixel-pack buffers that a later frame fetches without a stall (AsyncReadback).
#include <array>
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

/// Render targets read back so far by this process (each texture or framebuffer attachment once per
/// read, at once or issued asynchronously): what stats.json's per-frame "target_reads" counts.
std::uint64_t targetReads();

/// Level 0 of 2D textures read as RGBA floats into pixel-pack buffers behind a fence (issue 39,
/// point 4): issue() after a frame's passes, fetch() a frame later, when the GPU has long passed the
/// fence, so that a capture renders frame k+1 while frame k comes back. The buffers are made once
/// per slot and size and reused; a slot is free again once fetched.
class AsyncReadback {
 public:
  static constexpr std::size_t kSlots = 2;
  /// Copies the textures into the next slot and fences the copies; returns the slot's ticket.
  /// std::logic_error when that slot still holds a read not fetched.
  std::uint64_t issue(const std::vector<const Texture*>& textures);
  /// The images of `ticket` (top row first, in the order issued), waiting for its fence only if the
  /// GPU has not passed it yet. std::logic_error for a ticket not pending.
  std::vector<Image> fetch(std::uint64_t ticket);

 private:
  struct Slot {
    std::vector<Buffer> buffers;
    std::vector<std::array<int, 2>> sizes;  ///< width, height per texture of the pending read
    Fence fence;
    std::uint64_t ticket = 0;  ///< 0: free
  };
  std::array<Slot, kSlots> slots_;
  std::uint64_t issued_ = 0;
};

}  // namespace tallow::gpu
