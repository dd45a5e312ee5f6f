// Vertex stage shared by geometry.glsl and slice_capture.glsl: one patch instance per cell,
// mirrored by the aperiodic tiling (eq. 6.7); blades above the local density (per cell, times the
// density map at the blade's root) or handed to the other LOD representation are moved outside
// the clip volume. slice_capture.glsl defines CAPTURE: it records the bare patch, no maps.
#include "_lod.glsl"
#include "_design.glsl"
#if !defined CAPTURE && !defined WIND_INCLUDED
#include "_wind.glsl"
#endif
#ifndef CAPTURE
#include "_segments.glsl"
#endif
uniform mat4 u_view_proj;
uniform float u_density;       // global density scale
uniform float u_cell_size;     // world units per patch
#ifdef CAPTURE
uniform vec4 u_clip_lo;        // keep where dot(plane, vec4(world, 1)) >= 0
uniform vec4 u_clip_hi;
#endif

in vec3 in_position;
in vec3 in_normal;
in vec2 in_uv;
in vec3 in_color;
in vec2 in_root;
in float in_threshold;
in vec3 in_ctrl1;              // the blade's Bézier control points from its root (core/patch.py)
in vec3 in_ctrl2;
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in vec2 in_mirror;             // per instance: symmetry vector (s_x, s_z)
in vec4 in_config;             // per instance: config transform into the design maps
#ifndef CAPTURE
in float in_segment;           // per instance: its blades' continuous segment level
in vec3 in_chord_color;        // the colour this vertex takes on where it leaves
in vec4 in_level_width;        // its blade's width at levels 1 … 4, the full strip's 1
#endif

// Taken at the centroid of the samples a fragment covers: far away a blade's triangles are
// thinner than a pixel, and at the pixel's centre, outside the triangle, its attributes were
// extrapolated along the blade, and the far blades drew more of their tips' colour, height
// and light than they show.
centroid out vec3 v_world;
centroid out vec3 v_normal;
centroid out vec2 v_uv;
centroid out vec3 v_color;
centroid out vec4 v_map_color; // colour modulation (eq. 6.8) at the vertex
centroid out vec3 v_ambient;   // ambient and diffuse light maps at the vertex (eq. 6.9)
centroid out vec3 v_diffuse;
flat out float v_threshold;
flat out uint v_salt;          // its blade's (its triangle's in a capture) and its cell's
flat out float v_opacity;
flat out float v_density;      // local density at the root, for AO_blade
centroid out float v_height;  // height above the ground, for AO_blade
#ifndef CAPTURE
flat out vec2 v_lean;          // the wind's lean at the root (the wind view)
// the blade's curve at rest and bent, and its width direction: the fragment shader rebuilds
// the full strip's normals from them at every segment level (shaders/geometry.glsl)
flat out vec3 v_rest1;
flat out vec3 v_rest2;
flat out vec3 v_bent1;
flat out vec3 v_bent2;
flat out vec3 v_side;
#endif

void main() {
#if defined CAPTURE
    uint salt = uint(gl_VertexID);
#else
    // the blade's own (its vertices' rows), so a blade keeps its samples at every segment level
    uint salt = uint(gl_VertexID) / uint(2.0 * u_subdivisions + 2.0);
#endif
    v_salt = salt * 747796405u
             + (floatBitsToUint(in_origin.x) ^ (floatBitsToUint(in_origin.y) * 2891336453u));
    vec3 s = vec3(in_mirror.x, 1.0, in_mirror.y);
    vec3 local = (in_position - vec3(0.5, 0.0, 0.5)) * s + vec3(0.5, 0.0, 0.5);  // eq. 6.7
    vec2 root = (in_root - 0.5) * in_mirror + 0.5;
#ifdef CAPTURE
    float density = u_density * in_cell_density;
    vec4 w = vec4((vec3(in_origin.x, 0.0, in_origin.y) + local) * u_cell_size, 1.0);
    gl_ClipDistance[0] = dot(u_clip_lo, w);
    gl_ClipDistance[1] = dot(u_clip_hi, w);
#else
    float density = u_density * in_cell_density * design_density(design_uv(in_config, root));
#endif
    v_density = density;
    v_opacity = lod_opacity(in_threshold, density, in_lod);  // one cell each: its own w
    if (v_opacity <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: the blade vanishes
        v_world = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_uv = vec2(0.0); v_color = vec3(0.0);
        v_threshold = 1.0;
        v_height = 0.0;
        v_map_color = vec4(0.0); v_ambient = vec3(1.0); v_diffuse = vec3(1.0);
#ifndef CAPTURE
        v_lean = vec2(0.0);
#endif
        return;
    }
    // the maps change slowly across a cell: sampled per vertex, not per fragment
    vec2 duv = design_uv(in_config, local.xz);
#if defined CAPTURE || defined SHADOW
    // the capture records the bare patch; a shadow has the ground's colour, not the blade's
    v_map_color = vec4(0.0); v_ambient = vec3(1.0); v_diffuse = vec3(1.0);
#else
    v_map_color = design_color(duv); v_ambient = design_ambient(duv); v_diffuse = design_diffuse(duv);
#endif
    vec3 normal = in_normal * s;
    vec3 color = in_color;
#ifndef CAPTURE
    // the blade's curve from its root (core/patch.py); the vertex keeps its place across the
    // blade (its offset from the curve) wherever the curve goes
    vec3 root3 = vec3(root.x, 0.0, root.y);
    vec3 c1 = in_ctrl1 * s, c2 = in_ctrl2 * s;
    float t = in_uv.y;
    vec3 across = local - root3 - curve_point(c1, c2, t);
    v_rest1 = c1;
    v_rest2 = c2;
    vec3 side = cross(curve_tangent(c1, c2, t), normal);  // the strip's width direction
    v_side = dot(side, side) > 1e-12 ? normalize(side) : vec3(1.0, 0.0, 0.0);
    // the wind and the trampling bend the curve about the root (core/wind.py)
    vec2 lean = grass_lean((in_origin + root) * u_cell_size, design_uv(in_config, root));
    v_lean = lean;
    if (lean != vec2(0.0)) wind_bend(c1, c2, lean);
    v_bent1 = c1;
    v_bent2 = c2;
    normal = strip_normal(v_side, v_rest1, v_rest2, c1, c2, t);  // its row's, for WHOLE_STRIP
    // fewer segments far away (core/segments.py): a vertex the next level leaves out slides
    // onto its chord, its colour with it, and the blade widens as its strip shortens
    float m = segment_morph(in_segment);
    vec3 centre = curve_point(c1, c2, t);
    float t_lo, t_hi, share;
    if (m > 0.0 && segment_leaves(t, u_segment_level, t_lo, t_hi, share)) {
        centre = mix(centre, mix(curve_point(c1, c2, t_lo), curve_point(c1, c2, t_hi), share), m);
        color = mix(in_color, in_chord_color, m);
    }
    local = root3 + centre + across * segment_width(in_level_width, m);
#endif
    vec3 world = (vec3(in_origin.x, 0.0, in_origin.y) + local) * u_cell_size;
#ifndef CAPTURE
    world.y += ground_height(design_uv(in_config, root));  // eq. 6.13: the root's height
#endif
#ifdef SHADOW
    // its shadow (core/shadows.py): along the sun onto the ground's plane at the root, the sun
    // no lower than 5° (a lower one casts shadows as long as that)
    vec2 foot_uv = design_uv(in_config, root);
    vec3 foot = vec3((in_origin.x + root.x) * u_cell_size, ground_height(foot_uv),
                     (in_origin.y + root.y) * u_cell_size);
    vec3 up = u_height_scale > 0.0 ? ground_normal(foot_uv, in_config.zw / u_cell_size)
                                   : vec3(0.0, 1.0, 0.0);
    vec3 sun = normalize(vec3(u_light_dir.x, max(u_light_dir.y, 0.0872), u_light_dir.z));
    world -= sun * (dot(world - foot, up) / max(dot(sun, up), 0.0872));
#endif
    v_height = local.y * u_cell_size;
    v_world = world;
    v_normal = normal;
    v_uv = in_uv;
    v_color = color;
    v_threshold = in_threshold;
    gl_Position = u_view_proj * vec4(world, 1.0);
}
