#version 330 core
// Shows a frame drawn at a lower resolution (the viewport's preview while the camera or the
// brush moves) over the whole target, linearly filtered.

#if defined VERTEX_SHADER

in vec2 in_corner;  // -1 … 1
out vec2 v_uv;

void main() {
    v_uv = in_corner * 0.5 + 0.5;
    gl_Position = vec4(in_corner, 0.0, 1.0);
}

#elif defined FRAGMENT_SHADER

uniform sampler2D u_frame;
in vec2 v_uv;
out vec4 f_color;

void main() { f_color = vec4(texture(u_frame, v_uv).rgb, 1.0); }

#endif
