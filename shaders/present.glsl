#version 330 core
// Puts a frame over the whole target with every pixel opaque: a frame drawn at a lower
// resolution (the viewport's preview while the camera or the brush moves) linearly filtered,
// or, with RESOLVE n, a frame's n samples per pixel averaged (n = 1: a frame without them).
// Alpha-to-coverage and the alpha test leave the fragments' alpha in the frame; a window
// compositor (Qt draws the viewport's framebuffer over the window) would show the background
// through the grass.

#if defined VERTEX_SHADER

in vec2 in_corner;  // -1 … 1
out vec2 v_uv;

void main() {
    v_uv = in_corner * 0.5 + 0.5;
    gl_Position = vec4(in_corner, 0.0, 1.0);
}

#elif defined FRAGMENT_SHADER

out vec4 f_color;

#if defined RESOLVE
#if RESOLVE > 1
uniform sampler2DMS u_frame;
#else
uniform sampler2D u_frame;
#endif

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 sum = vec3(0.0);
    for (int s = 0; s < RESOLVE; ++s) sum += texelFetch(u_frame, texel, s).rgb;
    f_color = vec4(sum / float(RESOLVE), 1.0);
}

#else
uniform sampler2D u_frame;
in vec2 v_uv;

void main() { f_color = vec4(texture(u_frame, v_uv).rgb, 1.0); }
#endif

#endif
