// The wind field and the bend it gives a blade (core/wind.py holds the same maths and its
// tests): a tip displacement, as a fraction of a blade's length, from a noise map translated in
// the wind's direction (Habel 2007: gusts of low frequency and high amplitude, turbulence of high
// frequency and low amplitude); a blade is the quadratic Bézier curve of its trajectory, its tip
// moved by the displacement, its middle control point by a quarter of it, and the curve scaled
// about the root back to its length at rest.
// whether the grass bends: the wind blows or the trample map lays it over (core/trample.py);
// defines, not uniforms (render/shaders.py wind_defines)
#if defined WIND || defined TRAMPLE
const bool WIND_ON = true;
#else
const bool WIND_ON = false;
#endif
// the design-map stack (_design.glsl's u_design, the same texture unit), for its trample layer
uniform sampler2DArray u_trample;
uniform sampler2D u_wind_noise;  // r: gusts, gb: turbulence, each -1 … 1, repeating
uniform vec2 u_wind_heading;     // unit (x, z) the wind blows towards
uniform vec2 u_gust_shift;       // how far the patterns have travelled (world, wrapped)
uniform vec2 u_turbulence_shift;
uniform float u_gust_strength;
uniform float u_gust_tile;       // world units a repeat of the noise map spans for the gusts
uniform float u_turbulence_strength;
uniform float u_turbulence_tile;

const float WIND_MAX_LEAN = 0.9;     // core/wind.py MAX_LEAN
const float WIND_MIDDLE_SHARE = 0.25;  // core/wind.py MIDDLE_SHARE

// The wind view (sward render --view wind): the grass coloured by the lean it is drawn with,
// red and green the x and z components (0.5: none), whatever the representation.
uniform float u_wind_view;

vec3 wind_view(vec3 lit, vec2 lean) {
    vec3 shown = vec3(0.5 + 0.5 * lean / WIND_MAX_LEAN, 0.25);
    return mix(lit, shown, u_wind_view);
}

// the wind's tip displacement (x, z) at a world point, a fraction of a blade's length, before
// grass_lean limits it
vec2 wind_gusts(vec2 xz) {
#if defined WIND
    float gust = textureLod(u_wind_noise, (xz - u_gust_shift) / u_gust_tile, 0.0).r;
    vec2 eddy = textureLod(u_wind_noise, (xz - u_turbulence_shift) / u_turbulence_tile, 0.0).gb;
    return u_wind_heading * (u_gust_strength * 0.5 * (1.0 + gust)) + u_turbulence_strength * eddy;
#else
    return vec2(0.0);
#endif
}

// the trampled lean at a design-map uv (core/trample.py decode)
vec2 trample_lean(vec2 uv) {
#if defined TRAMPLE
    return (textureLod(u_trample, vec3(uv, 5.0), 0.0).rg - 0.5) * (2.0 * WIND_MAX_LEAN);
#else
    return vec2(0.0);
#endif
}

// what the grass leans by at a world point xz and its design-map uv: the wind's and the
// trampled lean added, no further than WIND_MAX_LEAN (core/wind.py grass_lean)
vec2 grass_lean(vec2 xz, vec2 uv) {
    if (!WIND_ON) return vec2(0.0);
    vec2 w = wind_gusts(xz) + trample_lean(uv);
    return w * min(1.0, WIND_MAX_LEAN / max(length(w), 1e-9));
}

// B(t) of the curve from the root (origin) through c1 and c2, and its derivative
vec3 curve_point(vec3 c1, vec3 c2, float t) { return 2.0 * t * (1.0 - t) * c1 + t * t * c2; }
vec3 curve_tangent(vec3 c1, vec3 c2, float t) { return 2.0 * (1.0 - 2.0 * t) * c1 + 2.0 * t * c2; }

float curve_length(vec3 c1, vec3 c2) {
    return 0.1739274226 * length(curve_tangent(c1, c2, 0.0694318442))
         + 0.3260725774 * length(curve_tangent(c1, c2, 0.3300094782))
         + 0.3260725774 * length(curve_tangent(c1, c2, 0.6699905218))
         + 0.1739274226 * length(curve_tangent(c1, c2, 0.9305681558));
}

// bend the curve (c1, c2) by the tip displacement `lean`, keeping its length
void wind_bend(inout vec3 c1, inout vec3 c2, vec2 lean) {
    float rest = curve_length(c1, c2);
    vec3 move = vec3(lean.x, 0.0, lean.y) * rest;
    c1 += WIND_MIDDLE_SHARE * move;
    c2 += move;
    float scale = rest / max(curve_length(c1, c2), 1e-12);
    c1 *= scale;
    c2 *= scale;
}

// v turned by the rotation that takes unit a to unit b (Rodrigues)
vec3 turn(vec3 v, vec3 a, vec3 b) {
    vec3 k = cross(a, b);
    float s = length(k);
    float c = dot(a, b);
    if (s < 1e-6) return v;
    k /= s;
    return v * c + cross(k, v) * s + k * dot(k, v) * (1.0 - c);
}

// A blade's normal at curve parameter t of its full strip: the patch's own (its width
// direction × the curve's direction, core/patch.py) on the curve at rest (rest1, rest2), turned
// with the curve where the wind bends it (bent1, bent2)
vec3 strip_normal(vec3 side, vec3 rest1, vec3 rest2, vec3 bent1, vec3 bent2, float t) {
    vec3 rest = curve_tangent(rest1, rest2, t);
    vec3 n = cross(side, rest);
    if (WIND_ON) {
        vec3 bent = curve_tangent(bent1, bent2, t);
        if (dot(rest, rest) > 1e-12 && dot(bent, bent) > 1e-12)
            n = turn(n, normalize(rest), normalize(bent));
    }
    return dot(n, n) > 1e-18 ? normalize(n) : vec3(0.0, 1.0, 0.0);
}

// The slices and the top view hold the grass at rest: a far representation reads them where the
// bent blades' parts at height y came from (Habel's sheared lookup). For the grass type's
// tallest blade standing upright (height `height`) bent by `lean`, with t = y / its bent tip
// height: the shift is B(t).xz = 2t c1.xz + t² (c2 - 2 c1).xz, a polynomial in y, and the rest
// height t · height; a ray step evaluates it with two multiply-adds (and the identity when the
// air is still).
struct WindShear { vec2 lin; vec2 quad; float stretch; float top; };

WindShear wind_still(float height) {
    return WindShear(vec2(0.0), vec2(0.0), 1.0, height);
}

WindShear wind_shear(vec2 lean, float height) {
    vec3 c1 = vec3(0.0, 0.5 * height, 0.0);
    vec3 c2 = vec3(0.0, height, 0.0);
    wind_bend(c1, c2, lean);
    float inv = 1.0 / max(c2.y, 1e-6);
    return WindShear(2.0 * c1.xz * inv, (c2.xz - 2.0 * c1.xz) * inv * inv, height * inv, c2.y);
}

// (rest height, shift x, shift z) for a bent height y over the ground
vec3 wind_unbend(WindShear s, float y) {
    float b = min(y, s.top);
    return vec3(b * s.stretch, (s.lin + s.quad * b) * b);
}

// The direction of that blade's bent curve at bent height y, d/dy of (shift, y): the rest curve
// is upright. A far representation's blades at height y turn with it from the vertical, as a
// blade's normals turn with its curve (_blade_vertex.glsl): the light of a gust.
vec3 wind_axis(WindShear s, float y) {
    vec2 slope = s.lin + 2.0 * s.quad * clamp(y, 0.0, s.top);
    return normalize(vec3(slope.x, 1.0, slope.y));
}
