// Conventions for files shared by GLSL and C++ (see gpu/glsl_shared.h for the C++ side):
// write plain functions on float/vec*, no in/out/inout parameters, no swizzle assignment, and
// mark each function TALLOW_FN (inline in C++, nothing in GLSL), and give float literals the f
// suffix (valid GLSL since 1.30) so that C++ does not promote them to double.
#ifndef TALLOW_FN
#define TALLOW_FN
#endif
