#version 450 core
// SSLPV injection: the texel's SH coefficients per colour band, added by blending (ONE, ONE).
flat in vec4 fR, fG, fB;

layout(location = 0) out vec4 oR;
layout(location = 1) out vec4 oG;
layout(location = 2) out vec4 oB;

void main() {
  oR = fR;
  oG = fG;
  oB = fB;
}
