// Vertex stage shared by geometry.glsl and slice_capture.glsl: one patch instance per cell,
// blades above the local density or handed to the other LOD representation moved outside the
// clip volume.
#include "_lod.glsl"
uniform mat4 u_view_proj;
uniform float u_density;       // global density scale
uniform float u_cell_size;     // world units per patch

in vec3 in_position;
in vec3 in_normal;
in vec2 in_uv;
in vec3 in_color;
in vec2 in_root;
in float in_threshold;
in vec2 in_origin;             // per instance
in float in_cell_density;      // per instance
in vec2 in_lod;                // per instance: transition (w, side)

out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_color;
flat out float v_threshold;
flat out float v_opacity;

void main() {
    v_opacity = lod_opacity(in_threshold, u_density * in_cell_density, in_lod);
    if (v_opacity <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: the blade vanishes
        v_world = vec3(0.0); v_normal = vec3(0.0, 1.0, 0.0); v_uv = vec2(0.0); v_color = vec3(0.0);
        v_threshold = 1.0;
        return;
    }
    vec3 world = vec3(in_origin.x, 0.0, in_origin.y) * u_cell_size + in_position * u_cell_size;
    v_world = world;
    v_normal = in_normal;
    v_uv = in_uv;
    v_color = in_color;
    v_threshold = in_threshold;
    gl_Position = u_view_proj * vec4(world, 1.0);
}
