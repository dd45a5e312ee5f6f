#version 330 core
// Patch conversion (thesis 4.2.1): the geometry patch seen by an orthographic camera, kept
// between two clip planes, written to three layers: albedo + alpha, patch-space normal and the
// blade's density threshold. Colour is stored unlit so the slices are lit when drawn (6.4.3).

#if defined VERTEX_SHADER

#include "_blade_vertex.glsl"

#elif defined FRAGMENT_SHADER

uniform sampler2D u_blade;
uniform vec4 u_clip_lo;        // keep where dot(plane, vec4(world, 1)) >= 0
uniform vec4 u_clip_hi;
uniform float u_alpha_ref;
uniform float u_ao_root;

in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_color;
flat in float v_threshold;

layout(location = 0) out vec4 f_color;
layout(location = 1) out vec4 f_normal;
layout(location = 2) out vec4 f_threshold;

void main() {
    vec4 w = vec4(v_world, 1.0);
    if (dot(u_clip_lo, w) < 0.0 || dot(u_clip_hi, w) < 0.0) discard;
    vec4 tex = texture(u_blade, v_uv);
    if (tex.a < u_alpha_ref) discard;
    float ao = mix(u_ao_root, 1.0, pow(clamp(v_uv.y, 0.0, 1.0), 0.8));
    vec3 n = normalize(v_normal);
    f_color = vec4(v_color * tex.rgb * ao, tex.a);
    f_normal = vec4(n * 0.5 + 0.5, 1.0);
    f_threshold = vec4(v_threshold, 0.0, 0.0, 1.0);
}

#endif
