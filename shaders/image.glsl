#version 400 core
// Image-based grass (thesis 5.3): one horizontal quad per (macro-)cell just above the ground,
// textured with the patch seen from above; density threshold test; the shared lighting model.
// Aperiodic tiling mirrors the lookup (eq. 6.6); design maps through the config transform.
#include "_lighting.glsl"
#include "_lod.glsl"
#include "_design.glsl"
#include "_slices.glsl"
#include "_wind.glsl"
#include "_coverage.glsl"

// what a view from each elevation of the table meets (core/canopy.py: θ_j = 90° ((j + ½) / 8)²):
// colour and height; and the top view's mean colour
uniform vec3 u_level_colors[8];
// over another type's grass (u_under), per elevation of the same table (render/image.py,
// core/canopy.py Canopy.over): the colour these blades show a ray above the grass beneath
uniform vec3 u_over_colors[8];
// per elevation of the same table, the mean of 1 − smoothstep(0, B_height, y) over the heights
// y the view meets (core/canopy.py Canopy.shade_met): AO_blade of what it meets
uniform float u_level_shade[8];
uniform float u_over_shade[8];  // the same over another type's grass (u_under)
uniform vec3 u_eye;

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_lift;          // height of the slice above the ground

in vec2 in_corner;             // unit square corner
// per instance: the rectangle (x0, z0, x1, z1), in cells from its corner, where its grass can
// grow (render/image.py): the slice keeps to it
in vec4 in_rect;
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)
in vec2 in_size;               // per instance: (macro-)cell extent in cells along x, z
in vec2 in_mirror;             // per instance: symmetry vector (s_x, s_z)
in vec4 in_config;             // per instance: config transform into the design maps

out vec2 v_patch;              // patch-space x, z (repeats across a macro-cell)
out vec3 v_world;
out vec2 v_design;             // design-map uv
// The terms that follow the direction to the eye and the ground's slant, taken at the vertices
// and interpolated over the grid's quads, over which they change little (a fragment's every
// instruction is what the pass costs on a CPU renderer): (tan θ of the view over the ground,
// the top view's share of the run, the slope's ratio of light, the blades' mean diffuse
// factor seen from here in still air), and what the view meets of the blades at θ: colour
// and AO_blade, over the ground and over another type's grass.
out vec4 v_view;
out vec3 v_met;
out vec3 v_met_over;
out vec2 v_shade;
flat out float v_density;
flat out vec2 v_lod;
flat out vec2 v_size;
flat out vec2 v_mirror;
flat out vec2 v_origin;

void main() {
    v_patch = mix(in_rect.xy, in_rect.zw, in_corner);
    v_design = design_uv(in_config, v_patch);
    v_density = in_cell_density;
    v_lod = in_lod;
    v_size = in_size;
    v_mirror = in_mirror;
    v_origin = in_origin;
    // the grid's vertices follow the ground (6.4.4; the thesis displaces the four corners)
    float ground = ground_height(v_design);
    vec3 world = vec3(in_origin.x + v_patch.x, u_lift + ground, in_origin.y + v_patch.y);
    v_world = world;
    gl_Position = u_view_proj * vec4(world, 1.0);
    // The blades a ray meets (Campbell's ellipsoidal leaf-angle model), by the elevation θ of
    // the ray over the grass layer: upright blades on ground that rises towards the eye are
    // crossed over a shorter run than on flat ground, and a ray descending at tan e over a
    // rise of gradient g along it meets the ground after h / (tan e + g), so tan θ = tan e + g
    // = (u · n) / (n_y |u_xz|), n the ground's normal (from the height map's slope here).
    vec2 texel = 1.0 / vec2(textureSize(u_design, 0).xy);
    vec2 gradient = vec2(
        ground_height(v_design + vec2(texel.x, 0.0)) - ground_height(v_design - vec2(texel.x, 0.0)),
        ground_height(v_design + vec2(0.0, texel.y)) - ground_height(v_design - vec2(0.0, texel.y)))
        * in_config.zw / (2.0 * texel);
    vec3 ground_up = normalize(vec3(-gradient.x, 1.0, -gradient.y));
    vec3 u = normalize(u_eye - world);
    float theta = atan(max(dot(u, ground_up), 0.0), max(ground_up.y * length(u.xz), 1e-4));
    float across = rise_across(u, gradient);  // the slope's other part
    float sin_up = max(sin(theta), 0.02);
    // the table's row for this elevation over the ground (θ_j = 90° ((j + ½) / 8)²)
    float row = clamp(sqrt(asin(sin_up) * 0.63661977) * 8.0 - 0.5, 0.0, 7.0);
    int i = int(floor(row));
    int j = min(i + 1, 7);
    float tan_up = sin_up / max(sqrt(1.0 - sin_up * sin_up), 1e-3);
    // The blades stand upright on sloping ground: a ray crosses their layer (of a height h
    // over the ground) over a run h n_y / (u · n), and meets their area from above over its
    // vertical part, h n_y u_y / (u · n): the top view's depth times n_y u_y / (u · n) (1 on
    // flat ground; on a slope facing the eye the ray leaves the layer after a short descent).
    // Its horizontal part, h n_y |u_xz| / (u · n) = h / tan θ, takes the side.
    float top_run = ground_up.y * max(u.y, 0.0) / max(dot(u, ground_up), 1e-3);
    // on a slope, upright blades differ from those on flat ground at this elevation over the
    // ground (slope_ratio_flat)
    float still = WIND_ON ? 0.0 : max(facing_lambert(u), 0.0);
    v_view = vec4(tan_up, top_run, slope_ratio_flat(u, theta, across), still);
    float f = row - float(i);
    v_met = mix(u_level_colors[i], u_level_colors[j], f);
    v_met_over = mix(u_over_colors[i], u_over_colors[j], f);
    v_shade = vec2(mix(u_level_shade[i], u_level_shade[j], f), mix(u_over_shade[i], u_over_shade[j], f));
}

#elif defined FRAGMENT_SHADER

uniform sampler2D u_top_color;
uniform sampler2D u_top_data;  // normal, threshold
uniform float u_top_spread[SPREAD_LEVELS];
uniform vec3 u_mean_normal;    // the top view's normal averaged over the patch (same encoding)
uniform vec4 u_under;          // 1 for each density channel whose grass lies beneath this one
// the optical depths of the blades (core/canopy.py side_column): seen from straight above (the
// top view's mean alpha, −ln(1 − a)), and of a level ray per patch length summed up the rows:
// all of them, and those above the grass beneath (u_under)
uniform float u_top_depth;
uniform float u_side_column;
uniform float u_over_column;
uniform vec3 u_top_mean;
uniform float u_density;
uniform float u_grass_height;  // the grass type's tallest blade (the slices' height)
uniform float u_canopy;        // the slice's height, a fraction of u_grass_height (render/image.py)

in vec2 v_patch;
in vec3 v_world;
in vec2 v_design;
in vec4 v_view;
in vec3 v_met;
in vec3 v_met_over;
in vec2 v_shade;
flat in float v_density;
flat in vec2 v_lod;
flat in vec2 v_size;
flat in vec2 v_mirror;
flat in vec2 v_origin;

out vec4 f_color;

void main() {
    // mirrored: s · p, which the repeating texture wraps like fract (eq. 6.6), by the bits of
    // the cell the fragment lies in (a macro-cell covers many); the top view has v = 1 - z. The
    // footprint comes from the unmirrored position: where s flips at a cell's edge, the
    // mirrored one jumps and a 2 × 2 quad across the edge would read the smallest mip.
    // the wind: the top view is read where the bent blades' upper parts, which it shows, came
    // from (Habel's sheared lookup, _wind.glsl)
    vec2 at = v_patch;
    vec2 lean = grass_lean(v_origin + v_patch, v_design);
    WindShear shear = wind_still(u_grass_height);
    if (WIND_ON) {
        shear = wind_shear(lean, u_grass_height);
        at -= wind_unbend(shear, u_canopy * shear.top).yz;
    }
    vec2 p = cell_mirror(v_origin + floor(at), v_mirror) * at;
    vec2 uv = vec2(p.x, 1.0 - p.y);
    vec2 duv_x = dFdx(v_patch), duv_y = dFdy(v_patch);
    vec2 design_dx = dFdx(v_design), design_dy = dFdy(v_design);  // the footprint on the maps
    // the mip level the footprint takes (as textureGrad would), once for both textures
    vec2 size = vec2(textureSize(u_top_color, 0));
    float lod = max(log2(max(length(duv_x * size), length(duv_y * size))), 0.0);
    vec4 c = textureLod(u_top_color, uv, lod);
    vec4 data = textureLod(u_top_data, uv, lod);
    float density = u_density * v_density * design_density(v_design);
    // The blades a ray meets (Campbell's ellipsoidal leaf-angle model). From straight above
    // they are what the top view covers, depth τ_top = −ln(1 − a); from the side, the blades'
    // area seen along a level ray, their column depth over tan θ (core/canopy.py side_column;
    // above another type's grass, u_under: the density channels of the types whose slices lie
    // lower, only the rows above that grass, for a ray passing between these blades meets it);
    // between, the two are the axes of an ellipse: τ(θ) = √(τ_top² + (column / tan θ)²). For
    // randomly turned blades the two agree and this is τ_top / sin θ; upright blades show
    // nothing from above (a vertical ribbon has no area there) and are all side. (θ, the
    // top view's share of the run: the vertex stage.)
    float under = clamp(dot(textureLod(u_design, vec3(v_design, 0.0), 0.0), u_under), 0.0, 1.0);
    bool top_seen = u_top_depth > 1e-3;  // a top view with something in it
    float tau_top = -log(max(1.0 - c.a, 1e-4)) * v_view.y;
    float tau_side = mix(u_side_column, u_over_column, under) / v_view.x;
    float tau = sqrt(tau_top * tau_top + tau_side * tau_side);
    // without a top view, the thresholds under a texel are all the blades': uniform
    float threshold = top_seen ? data.a : 0.5;
    // of the blades under the texel, the share kept: a share of blades picked at random by
    // their thresholds meets the ray with that share of the depth (alpha-to-coverage draws it)
    float kept = lod_share(threshold, top_seen ? level_value(u_top_spread, lod) : 0.28867513,
                           density, lod_at(v_lod, distance(u_eye.xz, v_world.xz), v_size));
    c.a = 1.0 - exp(-tau * kept);
    if (c.a < 0.02) discard;
    // The normal is not mirrored: far away a mirrored macro-cell would flip the small sideways
    // part of the patch's average normal and light hundreds of cells a few per cent brighter
    // or darker than their neighbours, a checkerboard nobody would see in the blades themselves.
    vec3 n = slice_normal(data);  // turned up, as the mean normal
    vec3 to_eye = normalize(u_eye - v_world);
    // Seen from above, the top view shows between the tips the blades' lower, darker parts,
    // which a lower view does not reach: the colour is what a view from this elevation meets of
    // the blades, from the side and from above (core/canopy.py), varied texel by texel as the
    // top view's colour varies about its mean.
    vec3 met = mix(v_met, v_met_over, under);
    vec3 seen = top_seen ? c.rgb * (met / max(u_top_mean, vec3(1e-3))) : met;
    vec3 albedo = modulate(seen, design_color_at(v_design, design_dx, design_dy));
    // The blades' mean diffuse factor from this side (core/facing.py), varied texel by texel as
    // the slice's own normal varies about the patch's mean normal; on a slope, by the vertex
    // stage's ratio. Under the wind the blades' light follows their bend (facing_leaned), and the texel's
    // normal turns with their curve at the height the top view shows (wind_axis).
    vec3 axis = wind_axis(shear, u_canopy * shear.top);
    const vec3 UP = vec3(0.0, 1.0, 0.0);
    float detail = top_seen ? lambert_through(turn(n, UP, axis))
                              / max(lambert_through(turn(u_mean_normal, UP, axis)), 0.05) : 1.0;
    float facing = WIND_ON ? facing_leaned(facing_entry(to_eye), lean) : v_view.w;
    float l = facing * clamp(detail, 0.25, 2.0) * v_view.z;
    // AO_blade (eq. 6.11) of what the view meets of the blades
    float shade = mix(v_shade.x, v_shade.y, under);
    float ao = 1.0 - u_ao_impact * clamp(density, 0.0, 1.0) * shade;
    vec3 lit = shade_l(albedo, l, ao, design_ambient(v_design), design_diffuse(v_design));
    f_color = vec4(technique(wind_view(lit, lean)), c.a);
    gl_SampleMask[0] = coverage_mask(c.a, floatBitsToUint(v_origin.x) ^ floatBitsToUint(v_origin.y));
}

#endif
