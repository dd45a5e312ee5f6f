#version 330 core
// Geometry-based grass (thesis 5.1): every cell instance of the patch in one instanced draw.
// Blades whose density threshold exceeds the local density are dropped in the vertex stage
// (moved outside the clip volume, so they cost no raster work); the blade texture's alpha
// shapes the blade through an alpha test plus alpha-to-coverage under MSAA.
#include "_lighting.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_density;       // global density scale
uniform float u_cell_size;     // world units per patch

in vec3 in_position;
in vec3 in_normal;
in vec2 in_uv;
in vec3 in_color;
in vec2 in_root;
in float in_threshold;
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance

out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_color;

void main() {
    if (in_threshold > u_density * in_cell_density) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: the blade vanishes
        v_world = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_uv = vec2(0.0); v_color = vec3(0.0);
        return;
    }
    vec3 world = vec3(in_origin.x, 0.0, in_origin.y) * u_cell_size + in_position * u_cell_size;
    v_world = world;
    v_normal = in_normal;
    v_uv = in_uv;
    v_color = in_color;
    gl_Position = u_view_proj * vec4(world, 1.0);
}

#elif defined FRAGMENT_SHADER

uniform sampler2D u_blade;
uniform vec3 u_eye;
uniform float u_alpha_ref;     // medium alpha-test reference
uniform float u_ao_root;       // AO_blade at the root (1 at the tip)

in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_color;

out vec4 f_color;

void main() {
    vec4 tex = texture(u_blade, v_uv);
    if (tex.a < u_alpha_ref) discard;
    vec3 n = normalize(v_normal);
    if (dot(n, u_eye - v_world) < 0.0) n = -n;  // two-sided material
    float ao = mix(u_ao_root, 1.0, pow(v_uv.y, 0.8));
    f_color = vec4(shade(v_color * tex.rgb, n, ao), tex.a);
}

#endif
