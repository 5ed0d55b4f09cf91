// The coverage counts of sss.maps=auto (sss/maps/map_count.h), laid out in one storage buffer
// (maps/coverage_count_buffer.glsl) that the VPL pass and the camera's histogram pass fill and the
// renderer reads back a frame or more later. Per histogram, bin k < K counts the points for which
// map k is the one that completes what the histogram asks (the maps' Halton directions are nested:
// the first K' of them are the maps a smaller K would have), bin COVERAGE_MAX_MAPS those for which
// no map does. Three histograms: the camera's visible translucent pixels by the first map that sees
// them at all (COVERAGE_CAMERA), and by the second map that sees them within COVERAGE_MIN_COS of their
// normal (COVERAGE_CAMERA_FACING: two face-on estimates of B, see below); the VPLs by the first that
// sees them (COVERAGE_VPLS). Shared with C++ (gpu/glsl_shared.h): auto chooses K in
// [1, COVERAGE_MAX_MAPS].
const int COVERAGE_MAX_MAPS = 32;
const int COVERAGE_HISTOGRAM_SIZE = COVERAGE_MAX_MAPS + 1;
const int COVERAGE_CAMERA = 0;
const int COVERAGE_CAMERA_FACING = 1;
const int COVERAGE_VPLS = 2;
const int COVERAGE_HISTOGRAMS = 3;
// A map that sees a point at θ from its normal spreads a texel over 1/cos θ of surface: a pixel
// that only such maps see gets B blurred across it (and biased where B varies). At most 60°. One
// such map is not enough: a pixel that a single map sees face-on takes that map's blur and bias
// nearly alone (the animated candle's lower-wall silhouette at K = 8: 10% bright, a firefly that
// the reference does not have; docs/radiosity-maps.md), so the facing histogram asks for two.
const float COVERAGE_MIN_COS = 0.5;
