#version 330 core
// Image-based grass (thesis 5.3): one horizontal quad per (macro-)cell just above the ground,
// textured with the patch seen from above; density threshold test; the shared lighting model.
#include "_lighting.glsl"
#include "_lod.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_lift;          // height of the slice above the ground

in vec2 in_corner;             // unit square corner
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in float in_size;              // per instance: macro-cell edge in cells

out vec2 v_patch;              // patch-space x, z (repeats across a macro-cell)
flat out float v_density;
flat out vec2 v_lod;

void main() {
    v_patch = in_corner * in_size;
    v_density = in_cell_density;
    v_lod = in_lod;
    vec3 world = vec3(in_origin.x + v_patch.x, u_lift, in_origin.y + v_patch.y);
    gl_Position = u_view_proj * vec4(world, 1.0);
}

#elif defined FRAGMENT_SHADER

uniform sampler2D u_top_color;
uniform sampler2D u_top_data;  // rgb normal, a threshold
uniform float u_density;
uniform float u_alpha_ref;

in vec2 v_patch;
flat in float v_density;
flat in vec2 v_lod;

out vec4 f_color;

void main() {
    vec2 uv = vec2(v_patch.x, 1.0 - v_patch.y);  // the top view has v = 1 - z; textures repeat
    vec4 c = texture(u_top_color, uv);
    vec4 data = texture(u_top_data, uv);
    c.a *= lod_opacity(data.a, u_density * v_density, v_lod);
    if (c.a < u_alpha_ref) discard;
    vec3 n = normalize(data.rgb * 2.0 - 1.0);
    if (n.y < 0.0) n = -n;  // seen from above
    f_color = vec4(technique(shade(c.rgb, n, 1.0)), c.a);
}

#endif
