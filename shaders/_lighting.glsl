// One lighting model for every representation (thesis 6.4.3):
// light = I_ambient · AO · albedo + I_diffuse · albedo · max(0, N·L)            (eq. 6.9)
// with I_ambient and I_diffuse scaled by the ambient and diffuse light maps (the ambient map
// carries AO_scene) and AO = AO_scene · AO_blade (eq. 6.10), where
// AO_blade = 1 − B_impact · density · smoothstep(B_height, 0, P_y)                (eq. 6.11).
// Grass blades are thin: a little light passes through from behind (translucency).
uniform vec3 u_light_dir;      // towards the light, normalised, world space
uniform vec3 u_light_color;    // I_diffuse
uniform vec3 u_ambient_color;  // I_ambient
uniform float u_translucency;
uniform float u_ao_impact;     // B_impact
uniform float u_ao_height;     // B_height, world units

float ao_blade(float height, float density) {
    // smoothstep(B_height, 0, P_y) with reversed edges, written the way GLSL defines it
    return 1.0 - u_ao_impact * clamp(density, 0.0, 1.0) * (1.0 - smoothstep(0.0, u_ao_height, height));
}

// the diffuse factor of eq. 6.9 with the light passed through from behind
float lambert_through(vec3 n) {
    float lambert = max(dot(n, u_light_dir), 0.0);
    return lambert + u_translucency * max(dot(-n, u_light_dir), 0.0);
}

// The mean diffuse factor of the grass type's blades seen from the direction to_eye (render/
// facing.py, core/facing.py): what a slice far away must show to light like its blades; and how
// it changes as the wind bends them by the lean λ: L + G · λ + ½ λᵀ H λ (core/facing.py
// bend_coefficients; the table's rows 0 … 7 hold L, G_x, G_z, its rows 8 … 15 H_xx, H_xz, H_zz).
uniform sampler2D u_facing;
const float FACING_ROWS = 8.0;  // core/facing.py ELEVATIONS
const float LEAN_STEP = 0.3;    // core/facing.py LEAN_STEP: the leans the coefficients span

struct Facing { float l; vec2 g; vec3 h; };

vec2 facing_uv(vec3 to_eye) {
    vec3 e = normalize(to_eye);
    float azimuth = atan(e.x, e.z) * 0.15915494;  // 0 = +z, turning towards +x, in turns
    float elevation = asin(clamp(e.y, 0.0, 1.0)) * 0.63661977;  // 0 … 1 over 0 … 90 degrees
    return vec2(azimuth, clamp(elevation * FACING_ROWS, 0.5, FACING_ROWS - 0.5) / (2.0 * FACING_ROWS));
}

float facing_lambert(vec3 to_eye) {
    return textureLod(u_facing, facing_uv(to_eye), 0.0).r;
}

Facing facing_entry(vec3 to_eye) {
    vec2 uv = facing_uv(to_eye);
    vec3 a = textureLod(u_facing, uv, 0.0).rgb;
    vec3 b = textureLod(u_facing, uv + vec2(0.0, 0.5), 0.0).rgb;
    return Facing(a.r, a.gb, b);
}

// the entry's diffuse factor with the blades bent by the wind's lean (_wind.glsl grass_lean)
float facing_leaned(Facing f, vec2 lean) {
    vec2 x = clamp(lean, -LEAN_STEP, LEAN_STEP);
    return max(f.l + dot(f.g, x) + 0.5 * (f.h.x * x.x * x.x + 2.0 * f.h.y * x.x * x.y
                                          + f.h.z * x.y * x.y), 0.0);
}

// Upright blades on sloping ground against the slices, which are sheared with it (core/
// slopes.py slope_tables, render/facing.py): the factor on a far representation's diffuse light
// seen from to_eye at elevation theta over the ground (radians), the ground rising `across` per
// unit of run to the viewer's right; 1 on flat ground. Within a block the table's layers hold
// elevations over the ground minus over the horizon of SPAN · t|t|, t in -1 … 1; the blocks,
// one after another along z, hold rises across the view of ACROSS_SPAN · s|s|, s in -1 … 1.
uniform bool u_slopes;
uniform sampler3D u_slope_ratio;
const float SLOPE_SPAN = 0.52359878;  // core/slopes.py SLOPE_SPAN (30°)
const float SLOPE_LAYERS = 9.0;       // core/slopes.py SLOPES
const float ACROSS_SPAN = 0.6;        // core/slopes.py ACROSS_SPAN
const float ACROSS_BLOCKS = 7.0;      // core/slopes.py ACROSS

// the ground's rise per unit of run to the right of a view towards -to_eye, from its gradient
// (d height / dx, d height / dz)
float rise_across(vec3 to_eye, vec2 gradient) {
    vec2 away = -to_eye.xz / max(length(to_eye.xz), 1e-6);
    return dot(gradient, vec2(-away.y, away.x));
}

vec2 slope_ratios(vec3 to_eye, float theta, float across) {
    if (!u_slopes) return vec2(1.0);
    vec3 e = normalize(to_eye);
    float elevation = asin(clamp(e.y, 0.0, 1.0));
    float du = theta - elevation;
    float t = clamp(sign(du) * sqrt(abs(du) / SLOPE_SPAN), -1.0, 1.0);
    float layer = (t + 1.0) * 0.5 * (SLOPE_LAYERS - 1.0) + 0.5;  // texels into a block
    float s = clamp(sign(across) * sqrt(abs(across) / ACROSS_SPAN), -1.0, 1.0);
    float block = (s + 1.0) * 0.5 * (ACROSS_BLOCKS - 1.0);
    float b0 = min(floor(block), ACROSS_BLOCKS - 2.0);
    vec2 uv = vec2(atan(e.x, e.z) * 0.15915494, elevation * 0.63661977);
    float depth = SLOPE_LAYERS * ACROSS_BLOCKS;
    vec2 r0 = textureLod(u_slope_ratio, vec3(uv, (b0 * SLOPE_LAYERS + layer) / depth), 0.0).rg;
    vec2 r1 = textureLod(u_slope_ratio, vec3(uv, ((b0 + 1.0) * SLOPE_LAYERS + layer) / depth), 0.0).rg;
    return mix(r0, r1, block - b0);
}

// the volume's: upright blades against the sheared slices
float slope_ratio(vec3 to_eye, float theta, float across) {
    return slope_ratios(to_eye, theta, across).r;
}

// the image-based grass's: upright blades on the slope against upright blades on flat ground,
// whose light its facing table holds
float slope_ratio_flat(vec3 to_eye, float theta, float across) {
    return slope_ratios(to_eye, theta, across).g;
}

vec3 shade(vec3 albedo, vec3 n, float ao, vec3 ambient_map, vec3 diffuse_map) {
    return albedo * (u_ambient_color * ambient_map * ao + u_light_color * diffuse_map * lambert_through(n));
}

vec3 shade_l(vec3 albedo, float lambert, float ao, vec3 ambient_map, vec3 diffuse_map) {
    return albedo * (u_ambient_color * ambient_map * ao + u_light_color * diffuse_map * lambert);
}

// Σ w_i · shade(modulate(c_i, map), n_i, ao_i, ambient_map, diffuse_map) for samples that share
// one colour-modulation, ambient and diffuse value (eq. 6.8 and 6.9 are linear in the sample's
// colour, AO and diffuse factor), from the sums c_ao = Σ w_i c_i ao_i, c_l = Σ w_i c_i l_i,
// s_ao = Σ w_i ao_i and s_l = Σ w_i l_i, where l_i = lambert_through(n_i).
vec3 shade_sum(vec3 c_ao, vec3 c_l, float s_ao, float s_l, vec4 map, vec3 ambient_map,
               vec3 diffuse_map) {
    vec3 ka = u_ambient_color * ambient_map;
    vec3 kd = u_light_color * diffuse_map;
    return (1.0 - map.a) * (ka * c_ao + kd * c_l) + map.a * map.rgb * (ka * s_ao + kd * s_l);
}

// Technique colour view (thesis Figs. 7.1-7.6): geometry red, volume yellow, image blue, keeping
// the shading's brightness so the structure stays readable. Off (0) unless a renderer sets it.
uniform vec3 u_technique_color;
uniform float u_technique_view;

vec3 technique(vec3 lit) {
    float luma = dot(lit, vec3(0.299, 0.587, 0.114));
    return mix(lit, u_technique_color * clamp(0.35 + 2.0 * luma, 0.0, 1.0), u_technique_view);
}
