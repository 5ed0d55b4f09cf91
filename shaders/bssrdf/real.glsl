// Conventions of the BSSRDF model files (shaders/bssrdf/*.glsl), which are written once and
// compiled both as GLSL 4.50 (every GPU pass, shaders/bssrdf/probe.comp) and as C++ through GLM,
// in float and in double precision (sss/bssrdf/bssrdf.cpp, the tests). See docs/bssrdf-models.md.
//
// Types. `real`, `real2`, `real3`, `real4` are the scalar and vector types. GLSL: the macros below (float,
// vec2, vec3). C++: type aliases declared in the namespace that includes the files
// (`using real = float; using real3 = glm::vec3;` or double / glm::dvec3), one namespace per
// precision, so that the float and the double instantiations are separate functions.
//
// Literals. Unsuffixed (`0.5`, never `0.5f`): a float literal in GLSL, a double literal in C++.
// Wherever a literal meets a real, write `real(0.5)` so that the C++ float instantiation computes
// in float like the GPU does (and so that it compiles: glm::vec3 * double and max(float, double)
// do not). Vectors times literals: `real(0.5) * v`. Zero: `max(x, real(0))`, not `max(x, 0.0)`.
// Constants: `const real NAME = 1.5;` (namespace scope in C++, global in GLSL). Constant arrays:
// `const real NAME[4] = {a, b, c, d};` (GLSL 4.20 initialiser lists; valid C++ aggregate syntax).
//
// Functions. Marked TALLOW_FN (inline in C++, empty in GLSL; common/shared.glsl), plain
// parameters only: no in/out/inout (several results are returned as a struct, whose declaration
// and member access read the same in both languages; build it with `S s; s.a = …; return s;`,
// never with a constructor), no swizzle assignment, no recursion, no function overloading on
// real (the float and double instantiations live in different C++ namespaces instead). Names do
// not clash with GLM/GLSL built-ins (fresnelReflectance, not reflect).
//
// Includes. A file includes what it needs only for GLSL, inside `#ifdef TALLOW_GLSL`; the shader
// loader (gpu/shader_library.h) expands each file once per stage. The C++ translation unit
// includes every file itself, in dependency order, once per precision namespace. There are no
// include guards in these files.
//
// Units: lengths in mm, coefficients in mm⁻¹. Directions are unit vectors; w_i points from x_i
// toward the light; n_i and n_o are the outward normals at x_i and x_o.
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#endif

const real BSSRDF_PI = 3.14159265358979323846;
