#version 330 core
// Props (boxes) standing in the grass, lit by the same sun and ambient light; drawn before the
// grass so the grass, which writes its own depth, hides their feet.
#include "_lighting.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;

in vec3 in_position;           // unit cube, centred
in vec3 in_normal;
in vec3 in_centre;             // per instance
in vec3 in_size;
in vec3 in_color;

out vec3 v_normal;
out vec3 v_color;

void main() {
    v_normal = in_normal;
    v_color = in_color;
    gl_Position = u_view_proj * vec4(in_centre + in_position * in_size, 1.0);
}

#elif defined FRAGMENT_SHADER

in vec3 v_normal;
in vec3 v_color;
out vec4 f_color;

void main() {
    f_color = vec4(shade(v_color, normalize(v_normal), 1.0, vec3(1.0), vec3(1.0)), 1.0);
}

#endif
