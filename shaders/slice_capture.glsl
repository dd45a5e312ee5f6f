#version 330 core
// Patch conversion (thesis 4.2.1): the geometry patch seen by an orthographic camera, kept
// between two clip planes (clip distances: triangles outside the slab are clipped before they
// are rasterised), written to three layers: albedo + alpha, patch-space normal, and the blade's
// density threshold and height. Colour is stored unlit and without AO so the slices are lit when drawn,
// like the blades (6.4.3).

#if defined VERTEX_SHADER

#define CAPTURE
#include "_blade_vertex.glsl"

#elif defined FRAGMENT_SHADER

uniform sampler2D u_blade;
uniform float u_alpha_ref;

centroid in vec3 v_world;
centroid in vec3 v_normal;
centroid in vec2 v_uv;
centroid in vec3 v_color;
centroid in float v_height;
flat in float v_threshold;

layout(location = 0) out vec4 f_color;
layout(location = 1) out vec4 f_normal;
layout(location = 2) out vec4 f_threshold;

void main() {
    vec4 tex = textureLod(u_blade, v_uv, 0.0);
    if (tex.a < u_alpha_ref) discard;
    vec3 n = normalize(v_normal);
    f_color = vec4(v_color * tex.rgb, tex.a);
    f_normal = vec4(n * 0.5 + 0.5, 1.0);
    f_threshold = vec4(v_threshold, v_height, 0.0, 1.0);
}

#endif
