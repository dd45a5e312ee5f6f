#version 330 core
// Image-based grass (thesis 5.3): one horizontal quad per (macro-)cell just above the ground,
// textured with the patch seen from above; density threshold test; the shared lighting model.
// Aperiodic tiling mirrors the lookup (eq. 6.6); design maps through the config transform.
#include "_lighting.glsl"
#include "_lod.glsl"
#include "_design.glsl"
#include "_slices.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_lift;          // height of the slice above the ground

in vec2 in_corner;             // unit square corner
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in vec2 in_size;               // per instance: (macro-)cell extent in cells along x, z
in vec2 in_mirror;             // per instance: symmetry vector (s_x, s_z)
in vec4 in_config;             // per instance: config transform into the design maps

out vec2 v_patch;              // patch-space x, z (repeats across a macro-cell)
out vec3 v_world;
out vec2 v_design;             // design-map uv
flat out float v_density;
flat out vec2 v_lod;
flat out vec2 v_mirror;

void main() {
    v_patch = in_corner * in_size;
    v_design = design_uv(in_config, v_patch);
    v_density = in_cell_density;
    v_lod = in_lod;
    v_mirror = in_mirror;
    // the grid's vertices follow the ground (6.4.4; the thesis displaces the four corners)
    float ground = ground_height(v_design);
    vec3 world = vec3(in_origin.x + v_patch.x, u_lift + ground, in_origin.y + v_patch.y);
    v_world = world;
    gl_Position = u_view_proj * vec4(world, 1.0);
}

#elif defined FRAGMENT_SHADER

uniform sampler2D u_top_color;
uniform sampler2D u_top_data;  // normal (2 components), height, threshold
uniform float u_density;
uniform float u_alpha_ref;
uniform float u_top_height;    // typical height of what the slice shows from above (AO_blade)
uniform vec3 u_eye;
uniform float u_grazing_lean;  // 0 … 1: how far the normal turns to the viewer at grazing angles

in vec2 v_patch;
in vec3 v_world;
in vec2 v_design;
flat in float v_density;
flat in vec2 v_lod;
flat in vec2 v_mirror;

out vec4 f_color;

void main() {
    // mirrored: s · p, which the repeating texture wraps like fract (eq. 6.6) without a seam in
    // the derivatives; the top view has v = 1 - z
    vec2 p = v_mirror * v_patch;
    vec2 uv = vec2(p.x, 1.0 - p.y);
    vec4 c = texture(u_top_color, uv);
    vec4 data = texture(u_top_data, uv);
    float density = u_density * v_density * design_density(v_design);
    c.a *= lod_opacity(data.a, density, v_lod);
    if (c.a < u_alpha_ref) discard;
    // The normal is not mirrored: far away a mirrored macro-cell would flip the small sideways
    // part of the patch's average normal and light hundreds of cells a few per cent brighter
    // or darker than their neighbours, a checkerboard nobody would see in the blades themselves.
    vec3 n = slice_normal(data);
    // The slice keeps the normals of what is seen from straight above (mostly up). Seen at a
    // grazing angle, grass shows the sides of its blades, whose normals face the viewer: lean the
    // normal that way as the view flattens, so the far zone lights like the volume beside it.
    vec3 to_eye = normalize(u_eye - v_world);
    vec3 side = normalize(vec3(to_eye.x, 0.0, to_eye.z) + vec3(0.0, 1e-4, 0.0));
    n = normalize(mix(n, side, u_grazing_lean * (1.0 - abs(to_eye.y))));
    if (dot(n, to_eye) < 0.0) n = -n;  // two-sided, as the blades and the slices
    vec3 albedo = modulate(c.rgb, design_color(v_design));
    vec3 lit = shade(albedo, n, ao_blade(u_top_height, density),
                     design_ambient(v_design), design_diffuse(v_design));
    f_color = vec4(technique(lit), c.a);
}

#endif
