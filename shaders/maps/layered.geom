#version 450 core
// One triangle into layer uLayerBase + instance of a 2D array or cube-map array (gl_Layer), seen
// through that layer's view-projection: all K maps (or all light views) in one instanced draw.
// The fallback for drivers without GL_ARB_shader_viewport_layer_array (see layered.vert).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 vgPosition[];
in vec3 vgNormal[];
flat in int vgInstance[];

layout(std430, binding = 4) readonly buffer LayerViews { mat4 layerViewProjection[]; };
uniform int uLayerBase;

out vec3 vWorldPosition;
out vec3 vWorldNormal;
flat out int vLayer;

void main() {
  int layer = uLayerBase + vgInstance[0];
  mat4 viewProjection = layerViewProjection[layer];
  for (int i = 0; i < 3; ++i) {
    gl_Layer = layer;
    vLayer = layer;
    vWorldPosition = vgPosition[i];
    vWorldNormal = vgNormal[i];
    gl_Position = viewProjection * vec4(vgPosition[i], 1.0);
    EmitVertex();
  }
  EndPrimitive();
}
