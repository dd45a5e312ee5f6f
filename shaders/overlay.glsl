#version 330 core
// Overlay lines drawn over the finished image (brush outline, LOD zone rings): world-space
// line strips in one colour each, no depth test, no lighting.

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
in vec3 in_position;

void main() { gl_Position = u_view_proj * vec4(in_position, 1.0); }

#elif defined FRAGMENT_SHADER

uniform vec4 u_color;
out vec4 f_color;

void main() { f_color = u_color; }

#endif
