#version 400 core
// Geometry-based grass (thesis 5.1): every cell instance of the patch in one instanced draw.
// Blades whose density threshold exceeds the local density are dropped in the vertex stage
// (moved outside the clip volume, so they cost no raster work); the blade texture's alpha
// shapes the blade through an alpha test plus its coverage of the pixel's samples under MSAA
// (_coverage.glsl).
#include "_lighting.glsl"
#include "_wind.glsl"
#include "_coverage.glsl"

#if defined VERTEX_SHADER

#define WIND_INCLUDED
#include "_blade_vertex.glsl"

#elif defined FRAGMENT_SHADER

uniform sampler2D u_blade;
uniform vec3 u_eye;
uniform float u_alpha_ref;     // medium alpha-test reference

centroid in vec3 v_world;
centroid in vec3 v_normal;
centroid in vec2 v_uv;
centroid in vec3 v_color;
centroid in vec4 v_map_color;
centroid in vec3 v_ambient;
centroid in vec3 v_diffuse;
flat in uint v_salt;
flat in float v_opacity;
flat in float v_density;
centroid in float v_height;
flat in vec2 v_lean;
flat in vec3 v_rest1;
flat in vec3 v_rest2;
flat in vec3 v_bent1;
flat in vec3 v_bent2;
flat in vec3 v_side;
uniform float u_subdivisions;

// The blade's normal at curve parameter t of the patch's full strip (_wind.glsl strip_normal)
// at the full strip's rows around t, interpolated between them as the full strip's triangles
// interpolate its vertices' normals; so a blade drawn with fewer segments is lit as it is with
// all of them. A draw of the full strips (WHOLE_STRIP) has those vertices: their normals
// interpolated are the same, without the flat curve inputs and the two normals a fragment.
vec3 row_normal(float t) {
    return strip_normal(v_side, v_rest1, v_rest2, v_bent1, v_bent2, t);
}

vec3 blade_normal(float t) {
#if defined WHOLE_STRIP
    return v_normal;
#else
    float s = max(u_subdivisions, 1.0);
    float row = min(floor(t * s), s - 1.0);
    return mix(row_normal(row / s), row_normal((row + 1.0) / s), t * s - row);
#endif
}

out vec4 f_color;

#if defined SHADOW
// The blades' shadows (core/shadows.py; Papavasiliou 3.6): the blade's outline moved onto the
// ground along the sun (_blade_vertex.glsl), in the ground's colour without the sun. A shadow
// covers the samples its blade's texel would (its alpha, of the blade's own samples: shadows
// of blades side by side within a pixel add up as the blades do) that lie in the pixel's
// u_shadow_strength share of samples, one share for every shadow (salt 0): where shadows
// overlap the ground loses that share once.
#include "_design.glsl"
#include "_soil.glsl"
uniform float u_shadow_strength;

void main() {
    vec4 tex = texture(u_blade, v_uv);
    float alpha = tex.a * v_opacity;
    if (alpha < u_alpha_ref) discard;
    if (gl_NumSamples <= 1) {  // no samples to choose from: the pixels themselves (screen door)
        uvec2 pixel = uvec2(gl_FragCoord.xy);
        float xi = float(coverage_hash(uvec3(pixel, v_salt)) & 0xFFFFu) / 65536.0;
        float eta = float(coverage_hash(uvec3(pixel, 0u)) & 0xFFFFu) / 65536.0;
        if (xi >= alpha || eta >= u_shadow_strength) discard;
    }
    f_color = vec4(soil(v_world, u_eye, 1.0, 0.0), 1.0);
    gl_SampleMask[0] = coverage_mask(alpha, v_salt) & coverage_mask(u_shadow_strength, 0u);
}
#else
void main() {
    vec4 tex = texture(u_blade, v_uv);
    tex.a *= v_opacity;  // blades crossing between LOD representations fade (eq. 5.26)
    if (tex.a < u_alpha_ref) discard;
    vec3 n = normalize(blade_normal(v_uv.y));
    if (dot(n, u_eye - v_world) < 0.0) n = -n;  // two-sided material
    vec3 albedo = mix(v_color * tex.rgb, v_map_color.rgb, v_map_color.a);  // eq. 6.8
    vec3 lit = shade(albedo, n, ao_blade(v_height, v_density), v_ambient, v_diffuse);
    f_color = vec4(technique(wind_view(lit, v_lean)), tex.a);
    gl_SampleMask[0] = coverage_mask(tex.a, v_salt);
}
#endif

#endif
