#pragma once
// Formats of the light and map G-buffers (issue 39, point 3: no wider targets than the precision
// needs). Positions keep float's 24 bits (a tenth of a micrometre at a metre: the dipole's distances
// are millimetres); unit normals are RGBA16F, 11 bits per component (an angle error below 1e-3 rad),
// half the bytes and bandwidth of RGBA32F. Measured against RGBA32F normals (GBufferPrecision.*,
// 96x54, llvmpipe): the candle's picture changes by 0.0002% and the bunny's by 0.0005% (relative
// RMSE), 46000x and 10000x below the noise left between 4 and 8 accumulated frames (with the maps'
// own normals in half floats too the candle's changed by 0.018%).
#include <glad/gl.h>

namespace tallow::sss {

inline constexpr GLenum kGBufferPositionFormat = GL_RGBA32F;
/// The maps' own G-buffer keeps float normals: the compute gather reads them where the fragment
/// gather interpolates them in float, and the two must give the same maps
/// (RadiosityMaps.FragmentAndComputeGathersGiveTheSameMaps: 2.4e-4 apart with half floats, 1e-4
/// allowed).
inline constexpr GLenum kMapGBufferNormalFormat = GL_RGBA32F;
/// The light G-buffers' and the VPL cube's normals: GL_RGBA16F unless a test chose otherwise.
GLenum gBufferNormalFormat();
/// Tests measure the precision: later G-buffers (and the memory budget) use `format`.
void setGBufferNormalFormat(GLenum format);

}  // namespace tallow::sss
