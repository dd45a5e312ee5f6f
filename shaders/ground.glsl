#version 330 core
// The ground under the grass: one large quad at y = 0, lit like the grass, darker where the
// grid of patches stands (the grass shades its own soil), fading into the sky far away.
#include "_lighting.glsl"
#include "_design.glsl"

#if defined VERTEX_SHADER

uniform mat4 u_view_proj;
uniform float u_extent;
uniform vec4 u_grass_rect;     // xmin, zmin, xmax, zmax of the grassed cells
uniform float u_mesh;          // 1: this is the grid over the grassed cells, following the heights
uniform float u_sink;          // how far the surrounding plane lies below y = 0
// per vertex of the grid, how far it sinks so that its triangles, chords of the height map's
// surface, lie on or under the ground the grass stands on (core/ground_mesh.py mesh_sink)
uniform sampler2D u_sink_map;
// how far a chunk's skirt hangs below its edge (render/ground.py): it closes the cracks between
// chunks drawn at different levels
uniform float u_skirt;

in vec2 in_corner;             // -1 … 1 (the plane) or 0 … 1 (the grid over the cells)
in float in_drop;              // 1 on a skirt's lower edge, else 0
out vec3 v_world;

void main() {
    if (u_mesh > 0.5) {
        vec2 p = mix(u_grass_rect.xy, u_grass_rect.zw, in_corner);
        ivec2 vertex = ivec2(round(in_corner * vec2(textureSize(u_sink_map, 0) - 1)));
        float sink = texelFetch(u_sink_map, vertex, 0).r;
        v_world = vec3(p.x, ground_height(in_corner) - u_height_scale * sink - in_drop * u_skirt, p.y);
    } else {
        v_world = vec3(in_corner.x * u_extent, -u_sink, in_corner.y * u_extent);
    }
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}

#elif defined FRAGMENT_SHADER

uniform vec3 u_soil_color;
uniform vec3 u_eye;
uniform vec3 u_fog_color;
uniform float u_fog_distance;
uniform vec4 u_grass_rect;    // xmin, zmin, xmax, zmax of the grassed cells
uniform float u_mesh;
uniform vec3 u_under_grass;   // soil colour under the grass

in vec3 v_world;
out vec4 f_color;

void main() {
    vec2 p = v_world.xz;
    float inside = max(u_mesh, step(u_grass_rect.x, p.x) * step(u_grass_rect.y, p.y)
                 * step(p.x, u_grass_rect.z) * step(p.y, u_grass_rect.w));
    // the design maps span the grassed rectangle: bare where the density map is, lit by the maps
    vec2 uv = (p - u_grass_rect.xy) / max(u_grass_rect.zw - u_grass_rect.xy, vec2(1e-6));
    float grass = inside * design_density(uv);
    vec3 albedo = mix(u_soil_color, u_under_grass, grass);
    vec3 ambient = mix(vec3(1.0), design_ambient(uv), inside);
    vec3 diffuse = mix(vec3(1.0), design_diffuse(uv), inside);
    vec3 color = shade(albedo, vec3(0.0, 1.0, 0.0), mix(1.0, 0.6, grass), ambient, diffuse);
    float fog = 1.0 - exp(-distance(u_eye, v_world) / u_fog_distance);
    f_color = vec4(mix(color, u_fog_color, clamp(fog, 0.0, 1.0)), 1.0);
}

#endif
