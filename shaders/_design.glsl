// The design-map stack (thesis 6.4, core/design_maps.py): one texture array, a layer a map,
// reached through the cell's config transform uv = config.xy + local · config.zw.
uniform sampler2DArray u_design;

vec2 design_uv(vec4 config, vec2 local) { return config.xy + local * config.zw; }
uniform int u_density_channel;  // the grass type's channel of the density map (6.4.5)
float design_density(vec2 uv) { return textureLod(u_design, vec3(uv, 0.0), 0.0)[u_density_channel]; }
vec4 design_color(vec2 uv) { return textureLod(u_design, vec3(uv, 1.0), 0.0); }
// The ambient and diffuse light maps, read only where one has been painted (the define
// LIGHT_MAPS, render/uniforms.py FrameUniforms.defines): unpainted, every texel of both is 1,
// and a CPU renderer would still pay for their fetches in every fragment and vertex.
#if defined LIGHT_MAPS
vec3 design_ambient(vec2 uv) { return textureLod(u_design, vec3(uv, 2.0), 0.0).rgb; }
vec3 design_diffuse(vec2 uv) { return textureLod(u_design, vec3(uv, 3.0), 0.0).rgb; }
#else
vec3 design_ambient(vec2 uv) { return vec3(1.0); }
vec3 design_diffuse(vec2 uv) { return vec3(1.0); }
#endif
// The colour map as a pixel's footprint on the ground sees it (uv's change across the pixel, dx
// and dy; its mipmapped copy, render/design_maps.py): a far representation's fragment covers
// many texels, and a marking a texel wide read at the base level broke into dots. Seen at a
// grazing angle the footprint is long and thin: the colour is the mean of taps along its long
// axis, as many as it is times longer than wide (up to 4) but no more than the texels it spans
// (a footprint within a texel reads the bilinear surface at one point as well as at four),
// each as wide as the short axis (the texture's own anisotropic filter drew saw teeth beside
// the lines on llvmpipe; one tap at the long axis's mip level washed the far lines out).
uniform sampler2D u_design_far;  // the colour map, RGB times its weight
const int DESIGN_TAPS = 4;
vec4 design_color_at(vec2 uv, vec2 dx, vec2 dy) {
    bool x_long = dot(dx, dx) > dot(dy, dy);
    vec2 major = x_long ? dx : dy;
    vec2 minor = x_long ? dy : dx;
    vec2 size = vec2(textureSize(u_design_far, 0));
    float along = min(length(major) / max(length(minor), 1e-9), length(major * size));
    int taps = int(clamp(ceil(along), 1.0, float(DESIGN_TAPS)));
    // every tap's footprint is major / taps by minor: one mip level for all of them, as
    // textureGrad would take it from those sides (the longer one's texels)
    float lod = log2(max(max(length(major * size) / float(taps), length(minor * size)), 1e-9));
    vec4 c = vec4(0.0);
    for (int k = 0; k < taps; ++k) {
        vec2 at = uv + major * ((float(k) + 0.5) / float(taps) - 0.5);
        c += textureLod(u_design_far, at, lod);
    }
    c /= float(taps);
    return vec4(c.rgb / max(c.a, 1e-4), c.a);
}

// Terrain height in world units at a design-map uv (thesis 6.4.4, eq. 6.13 / 6.16).
uniform float u_height_scale;
float ground_height(vec2 uv) { return u_height_scale * textureLod(u_design, vec3(uv, 4.0), 0.0).r; }

// The ground's normal at a design-map uv, `per_unit` the uv's change per world unit (a cell's
// config.zw over the cell size): from the height map's slope over a texel either side.
vec3 ground_normal(vec2 uv, vec2 per_unit) {
    vec2 texel = 1.0 / vec2(textureSize(u_design, 0).xy);
    vec2 rise = vec2(
        ground_height(uv + vec2(texel.x, 0.0)) - ground_height(uv - vec2(texel.x, 0.0)),
        ground_height(uv + vec2(0.0, texel.y)) - ground_height(uv - vec2(0.0, texel.y)));
    vec2 gradient = rise * per_unit / (2.0 * texel);
    return normalize(vec3(-gradient.x, 1.0, -gradient.y));
}

// C = A_c · C_c + (1 − A_c) · M_b · C_b (eq. 6.8): the blade's modulated colour blended with the
// colour-modulation map by the map's alpha.
vec3 modulate(vec3 blade, vec4 map) { return mix(blade, map.rgb, map.a); }

// Aperiodic tiling (thesis 6.3): a point in cell units mirrored into the patch by the cell's
// symmetry vector s (eq. 6.6): floor(p) + fract(s · p).
vec2 mirror_local(vec2 p, vec2 s) { return floor(p) + fract(s * p); }

// The symmetry vector of the cell whose origin is `cell` (world, cell units): with the
// terrain's noise map (u_tiling, render/tiling.py) that cell's own bits as core/tiling.py
// mirror_sign gives them (eqs. 6.4-6.5), else the instance's `own`. A macro-cell covers many
// cells and its instance carries its first cell's bits; each cell's blades are mirrored by its
// own, and a slice lookup mirrored by the first cell's would show another patch than the
// blades in most cells of a macro-cell.
uniform sampler2D u_tiling_noise;
uniform float u_tiling;
vec2 cell_mirror(vec2 cell, vec2 own) {
    if (u_tiling < 0.5) return own;
    vec2 res = vec2(textureSize(u_tiling_noise, 0));
    vec2 n = texelFetch(u_tiling_noise, ivec2(mod(floor(cell), res)), 0).rg;
    return vec2(n.x >= 0.5 ? 1.0 : -1.0, n.y >= 0.5 ? 1.0 : -1.0);
}
