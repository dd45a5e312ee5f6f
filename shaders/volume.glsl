#version 330 core
// Volume-based grass (thesis 5.2): a cuboid carrier per (macro-)cell instance; each fragment
// casts a ray through the vertical slices of both directions (eqs. 5.7-5.21), composites the
// samples front to back, stops early when opaque, and writes the depth of its first opaque hit.
#include "_lighting.glsl"
#include "_lod.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_height;        // patch height (cuboid height)

in vec3 in_corner;             // unit cube corner
in vec2 in_origin;             // per instance: cell origin
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in float in_size;              // per instance: macro-cell edge in cells

out vec3 v_patch;              // position on the cuboid in patch space
flat out vec2 v_origin;
flat out float v_density;
flat out float v_size;
flat out vec2 v_lod;

void main() {
    v_patch = in_corner * vec3(in_size, u_height, in_size);
    v_origin = in_origin;
    v_density = in_cell_density;
    v_size = in_size;
    v_lod = in_lod;
    gl_Position = u_view_proj * vec4(v_patch + vec3(in_origin.x, 0.0, in_origin.y), 1.0);
}

#elif defined FRAGMENT_SHADER

uniform mat4 u_view_proj;
uniform vec3 u_eye;
uniform float u_height;
uniform float u_density;
uniform float u_slices;        // p_num: slices per direction
uniform int u_max_steps;
uniform float u_opaque;        // early-exit opacity
uniform float u_lod_scale;
uniform float u_overrun;       // cells a ray may run on past its cuboid     // pixel footprint per unit distance × texels per patch unit
uniform sampler2D u_x_color;   // slices across x, stacked along v; u runs along z
uniform sampler2D u_x_data;    // rgb normal, a threshold
uniform sampler2D u_z_color;   // slices across z; u runs along x
uniform sampler2D u_z_data;

in vec3 v_patch;
flat in vec2 v_origin;
flat in float v_density;
flat in float v_size;
flat in vec2 v_lod;

out vec4 f_color;

vec2 atlas_uv(float u, float v, float slice, float rows) {
    float half_row = 0.5 / rows;
    return vec2(u, (slice + clamp(v, half_row, 1.0 - half_row)) / u_slices);
}

void main() {
    vec3 eye = u_eye - vec3(v_origin.x, 0.0, v_origin.y);
    vec3 d = normalize(v_patch - eye);                        // eq. 5.5 (no rotation yet)
    vec3 e = v_patch;                                         // eq. 5.4
    float p_inum = 1.0 / u_slices;                            // eq. 5.7
    float p_inum2 = 0.5 * p_inum;                             // eq. 5.8
    vec2 pm = floor((e.xz - p_inum2) * u_slices) * p_inum + p_inum2;  // eq. 5.9
    vec2 pd = sign(d.xz);                                     // eq. 5.10
    vec2 pi = pm + (pd + abs(pd)) * p_inum2;                  // eqs. 5.11-5.12
    vec2 safe_d = vec2(abs(d.x) < 1e-6 ? 1e-6 : d.x, abs(d.z) < 1e-6 ? 1e-6 : d.z);
    float lod = max(log2(distance(u_eye, v_patch + vec3(v_origin.x, 0, v_origin.y)) * u_lod_scale), 0.0);
    float rows = float(textureSize(u_x_color, 0).y) / u_slices;

    vec3 color = vec3(0.0);
    float alpha = 0.0;
    float depth_lambda = -1.0;
    for (int i = 0; i < u_max_steps; ++i) {
        vec2 w = (pi - e.xz) / safe_d;                        // eqs. 5.15-5.16
        bool hit_x = w.x < w.y;
        float lambda = max(hit_x ? w.x : w.y, 0.0);           // eq. 5.17
        vec3 h = e + lambda * d;                              // eq. 5.18
        // A ray may run on into the neighbouring cells (the patch tiles): a cell's fragment that
        // stopped at its own side wall would leave a gap, since the neighbour's wall behind it
        // fails the depth test once this fragment wrote depth.
        if (h.y < 0.0 || h.y > u_height || any(lessThan(h.xz, vec2(-u_overrun)))
            || any(greaterThan(h.xz, vec2(v_size + u_overrun)))) break;
        float plane = hit_x ? pi.x : pi.y;
        float slice = mod(floor(plane * u_slices), u_slices);
        float u = fract(hit_x ? h.z : h.x);
        vec2 uv = atlas_uv(u, h.y / u_height, slice, rows);
        vec4 c = hit_x ? textureLod(u_x_color, uv, lod) : textureLod(u_z_color, uv, lod);
        vec4 data = hit_x ? textureLod(u_x_data, uv, lod) : textureLod(u_z_data, uv, lod);
        c.a *= lod_opacity(data.a, u_density * v_density, v_lod);
        if (c.a > 0.003) {
            vec3 n = normalize(data.rgb * 2.0 - 1.0);
            if (dot(n, -d) < 0.0) n = -n;
            vec3 lit = technique(shade(c.rgb, n, 1.0));
            color += (1.0 - alpha) * c.a * lit;               // eq. 5.19 (colour is bled)
            alpha += (1.0 - alpha) * c.a;                     // eq. 5.20
            if (depth_lambda < 0.0 && alpha > 0.5) depth_lambda = lambda;
            if (alpha > u_opaque) break;
        }
        if (hit_x) pi.x += pd.x * p_inum; else pi.y += pd.y * p_inum;  // eq. 5.21
    }
    if (alpha < 0.01) discard;
    if (depth_lambda < 0.0) depth_lambda = 0.0;
    vec3 world = e + depth_lambda * d + vec3(v_origin.x, 0.0, v_origin.y);
    vec4 clip = u_view_proj * vec4(world, 1.0);
    gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
    f_color = vec4(color, alpha);                             // premultiplied
}

#endif
