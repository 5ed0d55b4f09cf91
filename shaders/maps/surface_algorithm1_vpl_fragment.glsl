// The radiosity maps' part of the camera pass with the VPLs' light on the surroundings summed in
// its fragment shader (the path before issue 39; kept to compare the compute pass with,
// VirtualPointLights::allowComputeReceivers).
#define TALLOW_VPL_IN_FRAGMENT
#include "maps/surface_algorithm1.glsl"
