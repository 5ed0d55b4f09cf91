#version 450 core
// Layered passes (light G-buffers, map depth, map shading, the VPL cube, SSLPV's voxelisation):
// world position and normal; the instance picks the layer of a 2D array or cube-map array, seen
// through that layer's view-projection — all K maps (or all light views) in one instanced draw.
// Where the driver offers GL_ARB_shader_viewport_layer_array (TALLOW_LAYER_IN_VERTEX, chosen by
// sss/maps/layered_program.cpp) this shader writes gl_Layer itself and the pass is vertex and
// fragment work only; otherwise layered.geom does it, a pass-through geometry shader per triangle.
#ifdef TALLOW_LAYER_IN_VERTEX
#extension GL_ARB_shader_viewport_layer_array : require
#endif
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;

#ifdef TALLOW_LAYER_IN_VERTEX
layout(std430, binding = 4) readonly buffer LayerViews { mat4 layerViewProjection[]; };
uniform int uLayerBase;

out vec3 vWorldPosition;
out vec3 vWorldNormal;
flat out int vLayer;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  int layer = uLayerBase + gl_InstanceID;
  gl_Layer = layer;
  vLayer = layer;
  vWorldPosition = world.xyz;
  vWorldNormal = uNormalMatrix * aNormal;
  gl_Position = layerViewProjection[layer] * world;
}
#else
out vec3 vgPosition;
out vec3 vgNormal;
flat out int vgInstance;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vgPosition = world.xyz;
  vgNormal = uNormalMatrix * aNormal;
  vgInstance = gl_InstanceID;
  gl_Position = world;
}
#endif
