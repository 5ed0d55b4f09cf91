// libFuzzer entry for the Radiance RGBE reader: any input must give an image or a std::exception,
// never a crash, leak, hang or huge allocation.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>

#include "gpu/hdr_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tallow::gpu::decodeHdr(std::span<const std::uint8_t>(data, size), "fuzz.hdr");
  } catch (const std::exception&) {
    // Rejecting the input is fine; only crashes and sanitizer reports are findings.
  }
  return 0;
}
