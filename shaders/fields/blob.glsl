// The animated blob's field, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl: `real`/`real3`, unsuffixed literals wrapped in real(), TALLOW_FN, no
// include guards). The GPU evaluates it per lattice sample (fields/blob_lattice.comp) and per
// extracted vertex for the normal (dual_contouring/vertices.geom with DC_BLOB_NORMALS);
// geometry::BlobField::value / gradient evaluate the same lines in double (blob_field.cpp), so
// `tallow field`, `tallow mesh --cpu`, the CPU reference integrator and the renderer agree.
//
// Radiosity-maps paper §4: Φ_t(p) = Σᵢ exp(−σ‖p − pᵢ(t)‖²) over BLOB_COUNT blobs whose centres
// pᵢ(t) move on periodic paths. The centres at t are the caller's (BlobField computes them from t:
// a few sin() per blob, uniforms on the GPU). Here p is in world units and the blob lives in its own
// unscaled space, q = p / scale; the field is exposed as iso − Φ_t(q), negative inside.
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

const int BLOB_COUNT = 4;  // the paper's four blobs (geometry::BlobParams::kBlobCount)

// iso − Φ_t(p / scale): centres in unscaled units, sigma in 1/unit², p in world units.
TALLOW_FN real blobFieldValue(real3 p, const real3 centres[BLOB_COUNT], real sigma, real iso, real scale) {
  real3 q = p / scale;
  real phi = real(0);
  for (int i = 0; i < BLOB_COUNT; ++i) {
    real3 d = q - centres[i];
    phi += exp(-sigma * dot(d, d));
  }
  return iso - phi;
}

// ∇_p (iso − Φ_t(p / scale)) = Σᵢ 2σ (q − cᵢ) exp(−σ‖q − cᵢ‖²) / scale, in field units per world
// unit: the analytic gradient (outward, as the field is negative inside).
TALLOW_FN real3 blobFieldGradient(real3 p, const real3 centres[BLOB_COUNT], real sigma, real scale) {
  real3 q = p / scale;
  real3 g = real3(real(0));
  for (int i = 0; i < BLOB_COUNT; ++i) {
    real3 d = q - centres[i];
    g += (real(2) * sigma * exp(-sigma * dot(d, d))) * d;
  }
  return g / scale;
}
