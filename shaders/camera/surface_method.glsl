// What the camera pass (surface.frag) asks of the frame's translucency method, which each method
// defines in its own file, included as TALLOW_SURFACE_METHOD (sss/translucency_method.h,
// surfaceShader(): one variant of the camera pass per method, binding only its own samplers):
//   TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot)
//     B at a translucent surface point x_o [m] (facing: its normal turned toward the camera, dpdx,
//     dpdy: the pixel's footprint, slot: x_o's material slot), with the share of maps that see it
//     and sss.maps=auto's coverage bins (0 for methods without maps);
//   vec3 surroundingsIrradiance(vec3 p, vec3 n)
//     the irradiance the method carries from the translucent objects to an opaque point (the VPLs
//     of §3.4), 0 for methods that carry none.
struct TranslucentShading {
  vec3 b;              // scattered radiosity B [W/m²]
  float seenBy;        // > 0 where some map (or grid) sees x_o
  uvec2 coverageBins;  // sss.maps=auto: the bins + 1 of the first map and second facing map
};

TranslucentShading shadingOf(vec3 b) {
  TranslucentShading s;
  s.b = b;
  s.seenBy = 1.0;
  s.coverageBins = uvec2(0u);
  return s;
}
