#version 330 core
// Props standing in the grass (boxes, and rocks: render/props.py), lit by the same sun and
// ambient light; drawn before the grass so the grass, which writes its own depth, hides their
// feet. A rock is turned about the vertical by its position, so one mesh makes every rock, and
// shaded with darker hollows and a fine grain.
#include "_lighting.glsl"

uniform float u_rock;          // 1 for rocks, 0 for boxes

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;

in vec3 in_position;           // the shape in the unit cube, centred
in vec3 in_normal;
in float in_cavity;            // 0 in a hollow … 1 on a bump (1 for boxes)
in vec3 in_centre;             // per instance
in vec3 in_size;
in vec3 in_color;

out vec3 v_normal;
out vec3 v_color;
out vec3 v_local;

float hash(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }

void main() {
    float a = u_rock * 6.2831853 * hash(in_centre.xz);
    mat3 turn = mat3(cos(a), 0.0, -sin(a), 0.0, 1.0, 0.0, sin(a), 0.0, cos(a));
    vec3 p = turn * in_position;
    // a stretched shape's normals: the inverse transpose of the scale
    v_normal = normalize((turn * in_normal) / in_size);
    v_color = in_color * mix(1.0, 0.55 + 0.45 * in_cavity, u_rock);
    v_local = in_position * 7.0 + in_centre;
    gl_Position = u_view_proj * vec4(in_centre + p * in_size, 1.0);
}

#elif defined FRAGMENT_SHADER

in vec3 v_normal;
in vec3 v_color;
in vec3 v_local;
out vec4 f_color;

// value noise for the rock's grain (a lattice of random values, smoothly interpolated)
float hash3(vec3 p) { return fract(sin(dot(p, vec3(127.1, 311.7, 74.7))) * 43758.5453); }
float noise(vec3 p) {
    vec3 i = floor(p), f = fract(p);
    f = f * f * (3.0 - 2.0 * f);
    float x00 = mix(hash3(i), hash3(i + vec3(1, 0, 0)), f.x);
    float x10 = mix(hash3(i + vec3(0, 1, 0)), hash3(i + vec3(1, 1, 0)), f.x);
    float x01 = mix(hash3(i + vec3(0, 0, 1)), hash3(i + vec3(1, 0, 1)), f.x);
    float x11 = mix(hash3(i + vec3(0, 1, 1)), hash3(i + vec3(1, 1, 1)), f.x);
    return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

void main() {
    float grain = 0.5 * noise(v_local) + 0.3 * noise(2.7 * v_local) + 0.2 * noise(7.3 * v_local);
    vec3 albedo = v_color * mix(1.0, 0.75 + 0.5 * grain, u_rock);
    f_color = vec4(shade(albedo, normalize(v_normal), 1.0, vec3(1.0), vec3(1.0)), 1.0);
}

#endif
