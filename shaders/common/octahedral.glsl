// Unit vectors in one 32-bit word: the octahedral map (Meyer et al. 2010, "On Floating-Point
// Normal Vectors"), each coordinate as a 16-bit snorm; the angle lost is under 1e-4 rad.
vec2 octahedralSignNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

uint packOctahedral(vec3 n) {
  vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) p = (1.0 - abs(p.yx)) * octahedralSignNotZero(p);
  return packSnorm2x16(p);
}

vec3 unpackOctahedral(uint word) {
  vec2 p = unpackSnorm2x16(word);
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * octahedralSignNotZero(n.xy);
  return normalize(n);
}
