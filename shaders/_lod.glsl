// Seamless transitions (thesis 5.4, eq. 5.26). lod = (w, side): side 0 is the near
// representation of a transition and keeps blades with threshold / density below w, side 1 the
// far one and keeps the rest; a smoothstep window of half-width u_epsilon blends the crossover.
uniform float u_epsilon;
// The transitions' distances (e1, e2) of eq. 5.23 for this level: from the previous level (xy)
// and to the next (zw); e2 <= e1 where there is none (core/lod.py fades). A cell's (w, side)
// says whether it lies in a transition, its w taken at its centre. A macro-cell that two
// levels share in a transition (core/traversal.py _pair_weight) would so hand over as one
// block, and a row of them as a staircase: in a macro-cell w is weighed instead at the
// distance d of the sample or texel itself, as the partner level does there. A single cell
// keeps its own w, which both representations share exactly (each weighs blades at its own
// sample points, and those differ between a blade's root, a ray's hits and an image texel).
uniform vec4 u_fade;

vec2 lod_at(vec2 lod, float d, vec2 cells) {
    vec2 fade = lod.y > 0.5 ? u_fade.xy : u_fade.zw;
    bool in_transition = lod.y > 0.5 || lod.x <= 1.0;
    if (!in_transition || fade.y <= fade.x || max(cells.x, cells.y) <= 1.0) return lod;
    return vec2(1.0 - clamp((d - fade.x) / (fade.y - fade.x), 0.0, 1.0), lod.y);
}

float lod_opacity(float threshold, float density, vec2 lod) {
    float x = threshold / max(density, 1e-6);
    if (x > 1.0) return 0.0;
    float eps = max(u_epsilon, 1e-4);
    float near = 1.0 - smoothstep(lod.x - eps, lod.x + eps, x);
    return lod.y < 0.5 ? near : 1.0 - near;
}

// The share of a reduced slice texel's blades a representation keeps (core/lod.py: share): the
// texel stands for blades whose thresholds spread around its mean by `spread` (per mip level,
// render/slices.py), taken as uniform over √12 · spread within 0 … 1; it keeps those below the
// density, the near side those below w · density as well, the far side the rest. Spread 0:
// lod_opacity, one blade.
float lod_share(float threshold, float spread, float density, vec2 lod) {
    float d = max(density, 1e-6);
    float half_w = 1.7320508 * spread;
    float lo = max(threshold - half_w, 0.0);
    float hi = min(threshold + half_w, 1.0);
    float width = max(hi - lo, 1e-4);
    float kept = clamp((d - lo) / width, 0.0, 1.0);
    float window = max(u_epsilon, 1e-4) * d;
    float reach = sqrt(0.25 * width * width + window * window);
    float r = clamp((0.5 * (lo + hi) - (lod.x * d - reach)) / (2.0 * reach), 0.0, 1.0);
    float linear = width / (width + 2.0 * window);  // many blades: a ramp; one: the window
    float near = min(1.0 - mix(r * r * (3.0 - 2.0 * r), r, linear), kept);
    return lod.y < 0.5 ? near : kept - near;
}

// a per-level table (the spread of thresholds) read at a fractional mip level
#define SPREAD_LEVELS 12
float level_value(float table[SPREAD_LEVELS], float lod) {
    float l = clamp(lod, 0.0, float(SPREAD_LEVELS - 1));
    int i = int(floor(l));
    int j = min(i + 1, SPREAD_LEVELS - 1);
    return mix(table[i], table[j], l - float(i));
}
