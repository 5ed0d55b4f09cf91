#version 450 core
// Depth pre-pass of the scattered radiosity maps: depth only, so that the shading pass runs the
// estimator once per visible texel (depth test EQUAL, writes off).
void main() {}
