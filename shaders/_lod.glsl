// Seamless transitions (thesis 5.4, eq. 5.26). lod = (w, side): side 0 is the near
// representation of a transition and keeps blades with threshold / density below w, side 1 the
// far one and keeps the rest; a smoothstep window of half-width u_epsilon blends the crossover.
uniform float u_epsilon;

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
