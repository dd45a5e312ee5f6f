#version 330 core
// Volume-based grass (thesis 5.2): a cuboid carrier per (macro-)cell instance; each fragment
// casts a ray through the vertical slices of both directions (eqs. 5.7-5.21), composites the
// samples front to back, stops early when opaque, and writes the depth of its first opaque hit.
// Aperiodic tiling: the lookups are mirrored by the cell's symmetry vector (eq. 6.6); design
// maps are sampled at every step through the cell's config transform (6.4).
#include "_lighting.glsl"
#include "_lod.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_height;        // patch height (cuboid height)
uniform vec2 u_band;           // the heights over the ground this pass counts (below)
uniform vec3 u_eye;
uniform float u_pixel;         // radians a pixel spans
const float FOLLOW_PIXELS = 2.0;  // the least thickness on the screen of a cuboid on a slope

in vec3 in_corner;             // unit cube corner
in vec2 in_origin;             // per instance: cell origin
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in vec2 in_size;               // per instance: (macro-)cell extent in cells along x, z
in vec2 in_mirror;             // per instance: symmetry vector (s_x, s_z)
in vec4 in_config;             // per instance: config transform into the design maps
in vec2 in_ground;             // per instance: lowest ground, unplanarity (eq. 6.14)
// per instance: the ground's slope along x and z per cell and the lowest and highest ground
// over that plane, relative to the lowest ground (core/terrain.py planes_of)
in vec4 in_plane;
// per instance: the rectangle (x0, z0, x1, z1), in cells from its corner, where its grass can
// grow (render/volume.py carriers): the cuboid keeps to it
in vec4 in_rect;

out vec3 v_patch;              // position on the cuboid in patch space
flat out vec2 v_origin;
flat out float v_density;
flat out vec2 v_size;
flat out vec2 v_lod;
flat out vec2 v_mirror;
flat out vec4 v_config;
flat out vec2 v_ground;
flat out float v_follows;      // 1: the cuboid drawn follows the slope or keeps to in_rect

void main() {
    // eq. 6.14: the cuboid reaches from the lowest ground to the grass over the highest, or to
    // the top of this pass's band of heights over it, above which its rays count nothing (a
    // band pass of a type that grows among another: render/volume_order.py). On a slope its
    // bottom and top follow the ground's plane (in_plane): a level one held air above the
    // grass on the slope's lower side, which rays crossed for nothing; the fragment stage
    // still steps through the level cuboid, which holds this one's grass.
    // A cuboid follows the slope only where it spans a few pixels on the screen (its
    // thickness at its nearest point): a thinner one covers most of its pixels in part, and a
    // pixel's one ray, through its centre, then meets grass that the samples it colours do
    // not (a lattice of light pixels on far hills); level cuboids are tall enough there.
    vec2 local = mix(in_rect.xy, in_rect.zw, in_corner.xz);
    vec3 base = vec3(in_origin.x, in_ground.x, in_origin.y);
    float band_top = min(u_band.y, u_height);
    vec3 box_far = base + vec3(in_size.x, in_ground.y + band_top, in_size.y);
    float near = distance(u_eye, clamp(u_eye, base, box_far));
    float thick = in_plane.w - in_plane.z + band_top;
    bool slope = (in_plane.x != 0.0 || in_plane.y != 0.0) && thick > FOLLOW_PIXELS * u_pixel * near;
    bool part = any(notEqual(in_rect, vec4(0.0, 0.0, in_size)));
    v_follows = slope || part ? 1.0 : 0.0;
    vec4 planes = slope ? in_plane : vec4(0.0, 0.0, 0.0, in_ground.y);
    float plane = dot(planes.xy, local);
    float y = plane + (in_corner.y > 0.5 ? planes.w + band_top : planes.z);
    v_patch = vec3(local.x, y, local.y);
    v_origin = in_origin;
    v_density = in_cell_density;
    v_size = in_size;
    v_lod = in_lod;
    v_mirror = in_mirror;
    v_config = in_config;
    v_ground = in_ground;
    gl_Position = u_view_proj * vec4(v_patch + base, 1.0);
}

#elif defined FRAGMENT_SHADER

#include "_design.glsl"
#include "_slices.glsl"
#include "_wind.glsl"

uniform mat4 u_view_proj;
uniform vec3 u_eye;
uniform float u_height;
uniform float u_density;
uniform float u_slices;        // p_num: slices per direction
uniform int u_max_steps;
uniform float u_opaque;        // early-exit opacity
uniform float u_lod_scale;     // pixel footprint per unit distance × texels per patch unit
// the heights over the ground this pass counts (grass types that grow among each other are
// drawn in bands of height: render/volume_order.py)
uniform vec2 u_band;
// the blades' depth from the side per patch length, summed over this pass's heights
// (core/canopy.py side_column)
uniform float u_band_column;
// what a view from each elevation meets of the blades' side (core/canopy.py side_colors)
uniform vec3 u_side_colors[8];
// the vertical slices' rows' depth −ln(1 − mean alpha) per mip level: x along the height,
// y one level a row, the base level first (core/mipmaps.py row_depths)
uniform sampler2D u_side_depths;
// the vertical slices, stacked along v: the N across x (u runs along z), then the N across z
// (u runs along x); one texture for both, so that a step fetches once (render/slices.py)
uniform sampler2D u_side_color;
uniform sampler2D u_side_data;  // normal, threshold
uniform sampler2D u_top_color; // the horizontal slice: the floor of the volume
uniform sampler2D u_top_data;
uniform float u_side_spread[SPREAD_LEVELS];  // thresholds' spread under a texel, per mip level
uniform float u_top_spread[SPREAD_LEVELS];
uniform float u_top_lod_offset; // log2(top slice width / vertical slice width)
uniform float u_side_mean_length;  // length of the vertical slices' mean normal (smallest level)
uniform float u_floor;         // height of the horizontal slice inside the volume (< 0: none)
// whether the pass has the horizontal slice at all: a define, not the sign of u_floor alone
// (render/volume.py), for a CPU renderer runs the search for it, its sample and the run it
// leaves uncounted in every fragment, whichever way their branches go
#if defined FLOOR
const bool HAS_FLOOR = true;
#else
const bool HAS_FLOOR = false;
#endif
uniform vec4 u_under;          // the density channels of the grass types beneath (render/volume.py)
// the mean of 1 − smoothstep(0, B_height, y) over the heights y the horizontal slice shows
// (core/canopy.py Canopy.top_shade): AO_blade of what it shows
uniform float u_floor_shade;
uniform int u_skip_steps;      // coarse steps over the height map before the slices
// the height map and this grass type's density in one texture (render/design_maps.py): the ray
// reads both at every step with one fetch; the same texels as u_design's height and density
uniform sampler2D u_ground;

// (ground height in world units, design density) at a design-map uv
vec2 ground_density(vec2 uv) {
    vec2 t = textureLod(u_ground, uv, 0.0).rg;
    return vec2(u_height_scale * t.x, t.y);
}

in vec3 v_patch;
flat in vec2 v_origin;
flat in float v_density;
flat in vec2 v_size;
flat in vec2 v_lod;
flat in vec2 v_mirror;
flat in vec4 v_config;
flat in vec2 v_ground;
flat in float v_follows;

out vec4 f_color;

// v (0 … 1 up a slice) kept half a texel of the coarser mip level read inside the slice: the
// filter must not reach the next one
float slice_v(float v, float rows, float lod) {
    float half_row = min(0.5 * exp2(ceil(lod)) / rows, 0.5);
    return clamp(v, half_row, 1.0 - half_row);
}

// slice: 0 … N-1 across x, N … 2N-1 across z
vec2 atlas_uv(float u, float v, float slice) {
    return vec2(u, (slice + v) / (2.0 * u_slices));
}

// What the ray has gathered, front to back (eqs. 5.19-5.20), kept as the sums that shade_sum
// (_lighting.glsl) turns into the lit colour once, after the ray: the colour-modulation, ambient
// and diffuse maps are read once per fragment at the gathered samples' mean position instead of
// at every sample (their texels span several blades; the sums keep every sample's own colour,
// normal and AO).
vec3 g_c_ao = vec3(0.0);   // Σ w c ao
vec3 g_c_l = vec3(0.0);    // Σ w c l
float g_ao = 0.0;          // Σ w ao
float g_l = 0.0;           // Σ w l
vec2 g_at = vec2(0.0);     // Σ w xz
float g_alpha = 0.0;       // Σ w

// a sample of colour c (alpha c.a), AO ao and diffuse factor l at xz, behind what was gathered
void gather(vec4 c, float ao, float l, vec2 xz) {
    float w = (1.0 - g_alpha) * c.a;
    g_c_ao += (w * ao) * c.rgb;
    g_c_l += (w * l) * c.rgb;
    g_ao += w * ao;
    g_l += w * l;
    g_at += w * xz;
    g_alpha += w;
}

// What the ray's crossings did not count of its run through the grass, added behind all it
// met. Where the run is short against the slices' spacing (short grass, few slices, steep
// views) a ray crosses no slice, and the horizontal slice alone covers only what the blades
// cover from straight above. `missed` of the run: its depth through the pass's heights from the side, the blades'
// column over tan θ (u_band_column), missed · column / tan θ, in
// the colour a view from that elevation meets of the vertical slices (`met`, core/canopy.py);
// `keep`: the share of the blades kept there (the density, the LOD transition).
vec4 missed_blades(float missed, float keep, float tan_up, vec3 met) {
    float a = (1.0 - exp(-missed * u_band_column / max(tan_up, 1e-3))) * keep;
    return vec4(met, a);
}

// The horizontal slice as a layer of the volume at height u_floor (render/volume.py): colour,
// alpha, AO and diffuse factor where the ray crosses it.
// `keep`: the share of the texel's blades kept (the density, the LOD transition).
vec4 horizontal(vec3 g, vec2 shift, float lod, float facing, out vec2 ao_l, out float keep) {
    vec2 at = g.xz - shift;  // where the bent blades crossing the layer stand at rest
    vec2 p = cell_mirror(v_origin + floor(at), v_mirror) * at;
    vec2 uv = vec2(p.x, 1.0 - p.y);
    float top_lod = max(lod + u_top_lod_offset, 0.0);  // explicit: no derivatives in the loop
    vec4 c = textureLod(u_top_color, uv, top_lod);
    vec4 data = textureLod(u_top_data, uv, top_lod);
    float density = u_density * v_density * ground_density(design_uv(v_config, g.xz)).y;
    keep = lod_share(data.a, level_value(u_top_spread, top_lod), density,
                     lod_at(v_lod, distance(u_eye.xz, v_origin + g.xz), v_size));
    c.a *= keep;
    // The layer is the top view: AO_blade of the heights it shows (u_floor_shade). Its texels
    // hold many blades each: lit
    // by the blades' mean diffuse factor seen from the ray (the facing table). Its averaged
    // normal, turned up and made unit length, faced the sky and lit the steep views near the
    // eye brighter than the blades.
    ao_l = vec2(1.0 - u_ao_impact * clamp(density, 0.0, 1.0) * u_floor_shade, facing);
    return c;
}

// The ray of this fragment through its cuboid, in the cuboid's frame (its corner at the origin)
struct Ray {
    vec3 eye;
    vec3 d;           // eq. 5.5 (no rotation yet)
    vec3 e;           // where the slice stepping starts
    float top;        // the cuboid's top
    float band_top;   // the top of this pass's heights
    float lod;        // the mip level read
    float crossing;   // the weight of one crossing (below)
    float exit;       // where the ray leaves its cuboid (by a wall or the top)
};

// the ground's height under a point of the cuboid, over the cuboid's lowest ground
float ground_under(vec2 xz) {
    return ground_density(design_uv(v_config, xz)).x - v_ground.x;
}

// eq. 5.4: the ray starts where it enters the level cuboid: where the cuboid follows a slope
// (v_follows), the one drawn lies inside the level one where the grass is and may reach out
// of it above the grass
vec3 enter_cuboid(vec3 eye, vec3 d, float top) {
    if (v_follows <= 0.5) return v_patch;
    vec3 inv = 1.0 / vec3(abs(d.x) < 1e-6 ? 1e-6 : d.x, abs(d.y) < 1e-6 ? 1e-6 : d.y,
                          abs(d.z) < 1e-6 ? 1e-6 : d.z);
    vec3 tmin = min((vec3(0.0) - eye) * inv, (vec3(v_size.x, top, v_size.y) - eye) * inv);
    return eye + max(max(max(tmin.x, tmin.y), tmin.z), 0.0) * d;
}

// On uneven ground the extruded cuboid holds empty space above the grass: march the ray over
// the height map in a few coarse steps and start the slice stepping just before it reaches
// the grass layer, or a tall cuboid would use up the steps in empty air. Then halve the step
// between the last point above the grass and the first in it: a start up to a coarse step
// short of the grass would spend the slice steps in air in bands that follow the ground's
// contours.
vec3 skip_air(vec3 e, vec3 d, float top, float band_top) {
    if (v_ground.y <= 0.05 * u_height) return e;
    vec3 inv = 1.0 / vec3(abs(d.x) < 1e-6 ? 1e-6 : d.x, d.y, abs(d.z) < 1e-6 ? 1e-6 : d.z);
    vec3 t0 = (vec3(0.0) - e) * inv;
    vec3 t1 = (vec3(v_size.x, top, v_size.y) - e) * inv;
    vec3 tmax = max(t0, t1);
    float leave = max(min(min(tmax.x, tmax.y), tmax.z), 0.0);
    float start = 0.0, below = -1.0;
    for (int k = 1; k <= u_skip_steps; ++k) {
        float lam = leave * float(k) / float(u_skip_steps);
        vec3 p = e + lam * d;
        if (p.y < ground_under(p.xz) + band_top) {
            below = lam;
            break;
        }
        start = lam;
    }
    for (int k = 0; k < 5 && below > 0.0; ++k) {
        float lam = 0.5 * (start + below);
        vec3 p = e + lam * d;
        if (p.y < ground_under(p.xz) + band_top) below = lam;
        else start = lam;
    }
    return e + start * d;
}

// Where the ray meets the horizontal slice (1e30: never, if it starts below or rises, or if
// there is none). On uneven ground the layer follows the ground: the ray's height over it,
// h(λ), is positive where the ray enters, and the layer lies at its first zero. Rising ground
// meets the layer before the flat plane at the entry's ground would: a march of a few steps
// towards that plane looks for a point below; falling ground meets it beyond: steps to where
// the plane would be at the ground reached; once a point lies below, regula falsi between it
// and the last point above. A layer flat at the entry's ground would hover over downhill
// ground and lie under uphill ground; a search from the flat plane alone would jump past hill
// crests. `descent`: how fast the ray's height over the ground falls along it, by the
// ground's slope where it enters (a ray rising up a hill that rises faster falls into the
// grass like one falling onto flat ground).
float floor_crossing(vec3 e, vec3 d, float descent) {
    float floor_y = u_floor + ground_density(design_uv(v_config, e.xz)).x - v_ground.x;
    if (!(HAS_FLOOR && u_floor >= 0.0 && descent < -1e-4 && e.y > floor_y)) return 1e30;
    float floor_lambda = (floor_y - e.y) / descent;
    float a = 0.0, ha = e.y - floor_y, b = floor_lambda, hb = -1.0;
    bool below = false;
    for (int k = 0; k < 5; ++k) {
        float x = below ? a + (b - a) * ha / (ha - hb)
                : (k < 2 ? floor_lambda * float(k + 1) / 2.0 : a - ha / descent);
        vec3 q = e + x * d;
        float hx = q.y - (u_floor + ground_density(design_uv(v_config, q.xz)).x - v_ground.x);
        if (hx > 0.0) {
            a = x;
            ha = hx;
        } else {
            b = x;
            hb = hx;
            below = true;
        }
    }
    return below ? a + (b - a) * ha / (ha - hb) : a - ha / descent;
}

// The horizontal slice where the ray crosses it, shaded once before the slice stepping and
// composited when the ray reaches it: inside the loop SIMD lanes meet it at different steps,
// and its fetches and shading would run once for every step at which any lane met it.
struct Floor {
    float lambda;    // where along the ray (1e30: nowhere)
    vec3 at;
    vec4 color;      // premultiplied by nothing: colour and alpha
    vec2 ao_l;       // AO and diffuse factor
    float keep;      // the share of its blades kept (0: outside the cuboid or the band)
};

Floor floor_sample(Ray r, float floor_lambda, vec3 ground_up, float facing, WindShear shear) {
    Floor f = Floor(floor_lambda, r.e + floor_lambda * r.d, vec4(0.0), vec2(0.0), 0.0);
    if (floor_lambda >= 1e29) return f;
    if (!(all(greaterThanEqual(f.at.xz, vec2(0.0))) && all(lessThanEqual(f.at.xz, v_size))))
        return f;
    f.color = horizontal(f.at, wind_unbend(shear, u_floor).yz, r.lod, facing, f.ao_l, f.keep);
    // in this pass's band of heights (u_band); on sloping ground the ray meets their area from
    // above over the vertical part of its run through the layer, n_y u_y / (u · n) of the top
    // view's depth (as image.glsl)
    bool in_band = u_floor >= u_band.x && u_floor < min(u_band.y, u_height + 1.0);
    float top_run = ground_up.y * max(-r.d.y, 0.0) / max(dot(-r.d, ground_up), 1e-3);
    f.color.a = in_band ? 1.0 - pow(1.0 - min(f.color.a, 0.999), top_run) : 0.0;
    if (!in_band) f.keep = 0.0;
    // where grass of a type beneath grows, its volume holds what the ray meets below
    f.color.a *= 1.0 - clamp(dot(textureLod(u_design, vec3(design_uv(v_config, f.at.xz), 0.0),
                                            0.0), u_under), 0.0, 1.0);
    return f;
}

// what the stepping found besides the gathered sums
const float DEPTH_ALPHA = 0.5;  // the depth written: where the ray became half opaque
float g_depth_lambda = -1.0;
float g_reached = 0.0;  // the farthest point of the ray known to lie above the ground
float g_counted = 0.0;  // how much of the ray's run through the grass its crossings counted

void gather_floor(inout Floor f) {
    gather(f.color, f.ao_l.x, f.ao_l.y, f.at.xz);
    if (g_depth_lambda < 0.0 && g_alpha > DEPTH_ALPHA) g_depth_lambda = f.lambda;
    f.lambda = 1e30;
}

// One crossing of a vertical slice at `h` (its plane `plane` across x or z): the slice's
// sample over the part `inside` of a slab it stands for, gathered at y over the ground.
void cross_slice(Ray r, vec3 h, float y, float gd_density, bool hit_x, float plane,
                 float inside, float sample_lambda, WindShear shear, float rows,
                 float side_spread, float facing, float slope_l, inout vec2 mirror_cell,
                 inout vec2 s) {
    float slice = mod(floor(plane * u_slices), u_slices);
    // the wind: read where the bent blades here stood at rest, moved along the slice
    vec3 rest = wind_unbend(shear, y);  // (y, 0, 0) in still air
    vec2 at = hit_x ? vec2(h.x, h.z - rest.z) : vec2(h.x - rest.y, h.z);
    // eq. 6.6: a mirrored cell reads slice N-1-k and u from the other end (the bits of the
    // cell that point lies in: a macro-cell's, or the neighbour's a ray ran on into; a blade
    // the wind bends over a cell's edge keeps its own cell's bits)
    vec2 cell = floor(at);
    if (cell != mirror_cell) {  // a ray crosses N slices a cell: one fetch per cell
        mirror_cell = cell;
        s = cell_mirror(v_origin + cell, v_mirror);
    }
    if ((hit_x ? s.x : s.y) < 0.0) slice = u_slices - 1.0 - slice;
    float u = fract((hit_x ? s.y * at.y : s.x * at.x));
    float v = slice_v(rest.x / u_height, rows, r.lod);
    vec2 uv = atlas_uv(u, v, hit_x ? slice : u_slices + slice);
    vec4 c = textureLod(u_side_color, uv, r.lod);
    vec4 data = textureLod(u_side_data, uv, r.lod);
    float density = u_density * v_density * gd_density;
    // The share of the texel's blades kept (density map, LOD transition) thins them as a layer
    // of random blades thins: transmittance (1 - a)^share, like the crossing's weight. Scaling
    // the alpha by the share would let half the blades cover half as much where they cover
    // more than half of it: the ground would show at the hand-over from the blades.
    float share = lod_share(data.a, side_spread, density,
                            lod_at(v_lod, distance(u_eye.xz, v_origin + h.xz), v_size));
    // A reduced level's texel averages alpha over rows whose depths differ (the lower rows all
    // but opaque, the upper ones nearly empty); a ray descending through the grass crosses the
    // slices at all those heights and meets the mean of their depths, not the depth of their
    // mean alpha. The texel's depth is scaled by its row's at the base level over its row's at
    // the level read: the row keeps the base level's depth at this height, the texel where
    // along the slice the blades stand.
    float levels = float(textureSize(u_side_depths, 0).y);
    float row = textureLod(u_side_depths, vec2(v, (r.lod + 0.5) / levels), 0.0).r;
    float base = textureLod(u_side_depths, vec2(v, 0.5 / levels), 0.0).r;
    float depth = -log(1.0 - clamp(c.a, 0.0, 0.999)) * (base + 1e-3) / (row + 1e-3);
    c.a = 1.0 - exp(-depth * r.crossing * share * inside);
    if (c.a <= 0.003) return;
    vec3 n = slice_normal(data) * vec3(s.x, 1.0, s.y);
    if (dot(n, -r.d) < 0.0) n = -n;
    // A texel's normal is the mean of its blades' (render/slices.py): of one blade near the
    // eye, of many far away, where the mean is short and would light them as one dull face.
    // Lit by its own direction, blended towards the blades' mean diffuse factor seen from the
    // ray (the facing table) as far as the averaging shortened it, from unit length to that of
    // the family's mean normal.
    float len = length(n);
    float k = clamp((1.0 - len) / (1.0 - u_side_mean_length), 0.0, 1.0);
    // under the wind the texel's normal turns with the blades' curve here (wind_axis)
    if (WIND_ON) n = turn(n, vec3(0.0, 1.0, 0.0), wind_axis(shear, y));
    float l = mix(lambert_through(n / max(len, 1e-4)), facing, k) * slope_l;
    gather(c, ao_blade(y, density), l, h.xz);  // eqs. 5.19-5.20
    if (g_depth_lambda < 0.0 && g_alpha > DEPTH_ALPHA) g_depth_lambda = sample_lambda;
}

// eqs. 5.7-5.21: step from slice to slice of both families, gathering front to back, the
// horizontal slice when the ray reaches it, until the ray is opaque or leaves its cuboid.
// Each crossing stands for the blades of the ray's path around it (a slice holds the blades
// between it and its neighbours, thesis 4.2.1): the crossings of both families cut the ray
// into stretches, each from half the way back to the crossing before (of either family) to
// half the way on to the next, the first from where the ray starts and the last to where it
// leaves what it may cross; each crossing counts the part of its stretch inside the grass
// layer (0 … height over the ground), in slabs: the ray's mean distance between crossings,
// p_inum / (|d.x| + |d.z|), is a slab's worth. The stretches tile the ray, so a ray through
// the layer in less than a slab (a slope facing the eye, a steep view) meets the share of
// blades its path holds wherever the planes fall, and a ray that meets the grass only near
// where it enters its cuboid counts all of it.
void march_slices(Ray r, inout Floor f, WindShear shear, float facing, float slope_l) {
    vec3 e = r.e, d = r.d;
    float p_inum = 1.0 / u_slices;                            // eq. 5.7
    float p_inum2 = 0.5 * p_inum;                             // eq. 5.8
    vec2 pm = floor((e.xz - p_inum2) * u_slices) * p_inum + p_inum2;  // eq. 5.9
    vec2 pd = sign(d.xz);                                     // eq. 5.10
    vec2 pi = pm + (pd + abs(pd)) * p_inum2;                  // eqs. 5.11-5.12
    vec2 safe_d = vec2(abs(d.x) < 1e-6 ? 1e-6 : d.x, abs(d.z) < 1e-6 ? 1e-6 : d.z);
    float rows = float(textureSize(u_side_color, 0).y) / (2.0 * u_slices);
    float side_spread = level_value(u_side_spread, r.lod);
    vec2 mirror_cell = vec2(1e9), s = v_mirror;  // the symmetry vector of the cell last hit
    float slab = p_inum / max(abs(d.x) + abs(d.z), 0.25);
    vec2 spacing = p_inum / abs(safe_d);  // the ray between two planes of either family
    float prev_lambda = 0.0;
    float rate_lambda = 0.0;
    float prev_y = e.y - ground_under(e.xz);
    for (int i = 0; i < u_max_steps; ++i) {
        vec2 w = (pi - e.xz) / safe_d;                        // eqs. 5.15-5.16
        bool hit_x = w.x < w.y;
        float lambda = max(hit_x ? w.x : w.y, 0.0);           // eq. 5.17
        float next_lambda = hit_x ? min(w.x + spacing.x, w.y) : min(w.x, w.y + spacing.y);
        if (f.lambda < lambda) {  // the horizontal slice lies before the next vertical one
            gather_floor(f);
            if (g_alpha > u_opaque) break;
        }
        vec3 h = e + lambda * d;                              // eq. 5.18
        // The ray stops at its cuboid's walls: the cuboid beyond draws the rest of the grass
        // along it, blended over or under this fragment (render/frame.py).
        if (h.y < 0.0 || h.y > r.top || any(lessThan(h.xz, vec2(0.0)))
            || any(greaterThan(h.xz, v_size))) break;
        vec2 gd = ground_density(design_uv(v_config, h.xz));
        // eqs. 6.16-6.18: shift the lookup by the ground under the hit
        float y = h.y - (gd.x - v_ground.x);
        // the heights over the ground the crossing's stretch spans (the ground taken as
        // straight between this crossing and the previous one), from where the ray entered
        float rate = lambda - rate_lambda > 1e-4 ? (y - prev_y) / (lambda - rate_lambda) : d.y;
        float from = i == 0 ? 0.0 : 0.5 * (prev_lambda + lambda);
        float to = next_lambda >= r.exit ? r.exit : 0.5 * (lambda + next_lambda);
        float y_from = y - rate * (lambda - from), y_to = y + rate * (to - lambda);
        float lo = min(y_from, y_to), hi = max(y_from, y_to);
        prev_lambda = lambda;
        rate_lambda = lambda;
        prev_y = y;
        // under the ground the ray is hidden by the ground drawn before: nothing after counts
        // (nor, for a pass of a band of heights, under that band: u_band)
        if (hi < u_band.x) break;
        if (y >= 0.0) g_reached = lambda;
        if (lo <= r.band_top) {
            float in_lo = max(lo, u_band.x), in_hi = min(hi, r.band_top);
            float share_in = hi - lo > 1e-5 ? max(in_hi - in_lo, 0.0) / (hi - lo) : 1.0;
            g_counted += share_in * (to - from);
            // the stretch's blades are read at the middle of its heights inside the layer,
            // and stand there on the ray: the crossing point itself may lie under the ground
            // (a ray rising up a slope meets the ground within a stretch), and a depth written
            // there would hide the fragment behind the ground
            float mid = 0.5 * (in_lo + in_hi);
            float sample_lambda = abs(rate) > 1e-6
                ? clamp(lambda + (mid - y) / rate, from, to) : lambda;
            cross_slice(r, h, mid, gd.y, hit_x, hit_x ? pi.x : pi.y,
                        share_in * (to - from) / slab, sample_lambda, shear, rows,
                        side_spread, facing, slope_l, mirror_cell, s);
            if (g_alpha > u_opaque) break;
        }
        if (hit_x) pi.x += pd.x * p_inum; else pi.y += pd.y * p_inum;  // eq. 5.21
    }
}

// What the ray's crossings did not count of its run through the grass, behind all it met:
// the run from where its height over the ground (falling evenly from `entry_h` to the floor)
// reaches the top of the pass's heights to where it reaches the ground or leaves the cuboid;
// of that, the part in this cuboid (the cuboid beyond a wall the ray leaves by counts the
// rest).
void gather_missed(Ray r, Floor f, float entry_h, float floor_tan, vec3 floor_met) {
    float fall = (entry_h - u_floor) / max(distance(r.e, f.at), 1e-6);
    float start = entry_h > r.band_top ? (entry_h - r.band_top) / max(fall, 1e-6) : 0.0;
    float full = entry_h / max(fall, 1e-6) - start;
    float run = min(full + start, r.exit) - start;
    float missed = full > 1e-6 ? clamp((run - g_counted) / full, 0.0, 1.0) : 0.0;
    gather(missed_blades(missed, f.keep, floor_tan, floor_met), f.ao_l.x, f.ao_l.y, f.at.xz);
}

// The gathered sums shaded once, at their mean position; the depth of the point where the ray
// became half opaque, or else of the farthest point it reached above the ground (its grass
// lies before it, the ground beyond).
void shade_and_write(Ray r, vec3 base, vec3 d_dx, vec3 d_dy, vec2 lean) {
    vec3 d = r.d;
    vec2 at = g_at / g_alpha;
    vec2 duv = design_uv(v_config, at);
    // the pixel's footprint on the ground there: a ray met at distance t moves its point on a
    // level plane by t (δd − d δd.y / d.y) as its direction changes by δd (a ray differential)
    float t = length(at - r.eye.xz) / max(length(d.xz), 1e-4);
    float dy = d.y < 0.0 ? min(d.y, -0.01) : max(d.y, 0.01);
    vec2 foot_x = t * (d_dx.xz - d.xz * d_dx.y / dy) * v_config.zw;
    vec2 foot_y = t * (d_dy.xz - d.xz * d_dy.y / dy) * v_config.zw;
    vec3 color = shade_sum(g_c_ao, g_c_l, g_ao, g_l, design_color_at(duv, foot_x, foot_y),
                           design_ambient(duv), design_diffuse(duv));
    color = technique(wind_view(color / g_alpha, lean)) * g_alpha;  // of the mean colour
    float depth_lambda = g_depth_lambda < 0.0 ? g_reached : g_depth_lambda;
    vec3 world = r.e + depth_lambda * d + base;
    vec4 clip = u_view_proj * vec4(world, 1.0);
    gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
    f_color = vec4(color, g_alpha);                           // premultiplied
}

void main() {
    vec3 base = vec3(v_origin.x, v_ground.x, v_origin.y);  // the cuboid's corner in the world
    Ray r;
    r.eye = u_eye - base;
    r.band_top = min(u_band.y, u_height);
    r.top = r.band_top + v_ground.y;  // the cuboid's (vertex stage)
    r.d = normalize(v_patch - r.eye);                         // eq. 5.5 (no rotation yet)
    vec3 d_dx = dFdx(r.d), d_dy = dFdy(r.d);  // how the ray turns across the pixel
    vec3 entered = enter_cuboid(r.eye, r.d, r.top);
    r.lod = max(log2(distance(r.eye, entered) * u_lod_scale), 0.0);
    r.e = skip_air(entered, r.d, r.top, r.band_top);
    vec3 d = r.d, e = r.e;
    // the wind where the ray enters (it varies over metres, a ray crosses a cell or two): the
    // slices are read where the bent blades came from (Habel's sheared lookup, _wind.glsl),
    // taken where the ray reaches half the grass's height over the ground under its start:
    // the blades it shows stand there, not under the cuboid's top where it enters at grazing
    // angles, metres nearer
    vec2 lean = vec2(0.0);
    WindShear shear = wind_still(u_height);
    if (WIND_ON) {
        float over = e.y - ground_under(e.xz);
        float run = d.y < -1e-4 ? clamp((over - 0.5 * u_height) / -d.y, 0.0, 4.0) : 0.0;
        lean = grass_lean(v_origin + e.xz + run * d.xz, design_uv(v_config, e.xz + run * d.xz));
        shear = wind_shear(lean, u_height);
    }
    // the blades' mean diffuse factor seen along the ray, as bent by the wind here
    float facing = WIND_ON ? facing_leaned(facing_entry(-d), lean) : facing_lambert(-d);
    // The slices are sheared with the ground, the blades stand upright on it: on a slope the
    // light differs by the ratio of the two (core/slopes.py slope_tables, its first layer), at
    // the ray's elevation over the ground where it enters (tan θ = (u · n) / (n_y |u_xz|), as
    // in image.glsl).
    vec2 slope = vec2(
        ground_density(design_uv(v_config, e.xz + vec2(1.0, 0.0))).x
            - ground_density(design_uv(v_config, e.xz - vec2(1.0, 0.0))).x,
        ground_density(design_uv(v_config, e.xz + vec2(0.0, 1.0))).x
            - ground_density(design_uv(v_config, e.xz - vec2(0.0, 1.0))).x);
    vec3 ground_up = normalize(vec3(-0.5 * slope.x, 1.0, -0.5 * slope.y));
    float over_ground = atan(max(dot(-d, ground_up), 0.0), max(ground_up.y * length(d.xz), 1e-4));
    float slope_l = slope_ratio(-d, over_ground, rise_across(-d, 0.5 * slope));
    // Opacity per slice crossed. A slice holds what a ray across its slab meets at right
    // angles, and both families hold every blade: a ray travelling a unit of the patch across
    // meets |d.x| N slices of one and |d.z| N of the other, where it meets the blades of N
    // slabs once. So each crossing counts 1 / (|d.x| + |d.z|) of a slab (1 / |cos φ| per
    // family would count a diagonal ray's blades twice).
    r.crossing = length(d.xz) / max(abs(d.x) + abs(d.z), 1e-6);
    vec2 safe_d = vec2(abs(d.x) < 1e-6 ? 1e-6 : d.x, abs(d.z) < 1e-6 ? 1e-6 : d.z);
    vec2 to_bound = (mix(vec2(0.0), v_size, step(0.0, vec2(d.x, d.z))) - e.xz) / safe_d;
    r.exit = min(to_bound.x, to_bound.y);
    if (d.y > 1e-6) r.exit = min(r.exit, (r.top - e.y) / d.y);
    float descent = d.y - dot(0.5 * slope, d.xz);
    Floor f = floor_sample(r, floor_crossing(e, d, descent), ground_up, facing * slope_l, shear);
    // the colour a view from the ray's elevation over the ground meets of the vertical slices
    // (the table's rows: θ_j = 90° ((j + ½) / 8)², as image.glsl)
    float met_row = clamp(sqrt(over_ground * 0.63661977) * 8.0 - 0.5, 0.0, 7.0);
    int met_i = int(floor(met_row));
    vec3 floor_met = mix(u_side_colors[met_i], u_side_colors[min(met_i + 1, 7)],
                         met_row - float(met_i));
    march_slices(r, f, shear, facing, slope_l);
    if (f.lambda < 1e29 && g_alpha <= u_opaque) gather_floor(f);  // it lies beyond the slices
    if (f.keep > 0.0 && g_alpha <= u_opaque)
        gather_missed(r, f, e.y - ground_under(e.xz), tan(over_ground), floor_met);
    if (g_alpha < 0.01) discard;
    shade_and_write(r, base, d_dx, d_dy, lean);
}

#endif
