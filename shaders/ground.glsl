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
#include "_soil.glsl"

uniform vec3 u_eye;
uniform float u_mesh;

// Blade shadows where no blades cast them (core/shadows.py): per grass type (up to four), its
// density channel, the distances where its geometry level draws blades, (begin, end), and the
// transitions' (e1, e2) in and out (core/lod.py fades). The geometry there casts the shadows of
// the blades it keeps, those below w · density; the ground takes away the rest of what all the
// blades would, 1 − (1 − s·cover(x)) / (1 − s·cover(w·x)) of the sun. `cover` comes from the
// type's field: where in a cell its blades' shadows fall, per mirror state of the tiling, per
// length over level ground's (uneven terrain) and per density, layers of a texture array
// whose mip levels average it, down to the cell's mean (render/shadows.py).
#if defined SHADOWS
uniform int u_shadow_types;
uniform sampler2DArray u_shadow_field;
uniform int u_shadow_states;     // 4: a field per mirror state of the tiling; 1: not mirrored
uniform int u_shadow_stretches;  // 3: drawn at core/shadows.py STRETCHES; 1: level ground alone
uniform vec4 u_shadow_channel[4];  // one-hot: the type's density channel
uniform vec4 u_shadow_span[4];
uniform vec4 u_shadow_fade[4];
uniform float u_shadow_density;  // the document's global density
uniform float u_shadow_strength;
uniform float u_shadow_reach[4];  // core/shadows.py reach: where a type's shadows come from

float geometry_share(int type, float d) {
    vec4 span = u_shadow_span[type];
    vec4 fade = u_shadow_fade[type];
    if (d < span.x || d > span.y) return 0.0;
    float w = 1.0;
    if (fade.y > fade.x) w *= clamp((d - fade.x) / (fade.y - fade.x), 0.0, 1.0);
    if (fade.w > fade.z) w *= 1.0 - clamp((d - fade.z) / (fade.w - fade.z), 0.0, 1.0);
    return w;
}

// The share of the ground at `cell` (the point in cell units; the field repeats) in the
// shadows of the type's blades below density x, the shadows `k` times as long as on level
// ground. One read gives the shares at the densities (x · 16 rounded down, and up) and the two
// lengths the field was drawn at nearest k (render/shadows.py layers; 0.5, 1, 2 on uneven
// terrain), interpolated; beyond them as a union of shadows dropped at random grows,
// 1 − (1 − cover)^(k / length), the area of each shadow growing with its length. `implicit`:
// the mip level from the pixel quad's own derivatives, for a read outside any branch (the
// cheaper read on llvmpipe, which takes an explicit level per pixel), else `lod`.
float shadow_cover(int type, int state, vec2 cell, float lod, float x, float k, bool implicit) {
    float s = clamp(x, 0.0, 1.0) * 16.0;
    float j = min(floor(s), 15.0);
    int pairs = max(u_shadow_stretches - 1, 1);
    float e = 0.0, drawn_at = 1.0;
    if (u_shadow_stretches > 1) {
        e = clamp(log2(max(k, 1e-6)) + 1.0, 0.0, 2.0);  // 0.5, 1, 2 at 0, 1, 2
        drawn_at = clamp(k, 0.5, 2.0);
    }
    float pair = min(floor(e), float(pairs - 1));
    float layer = (float((type * u_shadow_states + state) * pairs) + pair) * 16.0 + j;
    vec4 t = implicit ? texture(u_shadow_field, vec3(cell, layer))
                      : textureLod(u_shadow_field, vec3(cell, layer), lod);
    float c = mix(mix(t.x, t.y, s - j), mix(t.z, t.w, s - j), e - pair);
    if (s <= 0.0) return 0.0;
    return 1.0 - pow(max(1.0 - c, 0.0), max(k / drawn_at, 1e-3));
}

// The share of the sun the ground keeps where the blades' shadows are not drawn: at density x
// all the blades' shadows, less those the geometry casts (the blades below w · x),
// (1 − s·cover(x)) / (1 − s·cover(w·x)); `k` as shadow_cover's; `cell` the point in cell units
// and `lod` the fields' mip level there (the first read comes before any branch). The density
// is the one where the shadows falling here stand: `reach` up the blades towards the sun
// (`towards`: the uv offset per unit of height), so the bare ground beside grass gets the
// grass's shadows.
float unshadowed(vec2 uv, float d, float k, vec2 towards, vec2 cell, float lod) {
    vec2 s = u_shadow_states > 1 ? cell_mirror(floor(cell), vec2(1.0)) : vec2(1.0);
    int state = (s.x < 0.0 ? 1 : 0) + (s.y < 0.0 ? 2 : 0);  // core/shadows.py MIRRORS
    float sun = 1.0;
    for (int t = 0; t < u_shadow_types; ++t) {
        float w = geometry_share(t, d);
        vec2 from = uv + towards * (k * u_shadow_reach[t]);
        vec4 density = textureLod(u_design, vec3(from, 0.0), 0.0) * u_shadow_density;
        float x = clamp(dot(density, u_shadow_channel[t]), 0.0, 1.0);
        float all_of_them = 1.0 - u_shadow_strength * shadow_cover(t, state, cell, lod, x, k,
                                                                   true);
        if (w >= 1.0) continue;  // the geometry casts every blade's shadow here
        float drawn = w > 0.0
            ? 1.0 - u_shadow_strength * shadow_cover(t, state, cell, lod, w * x, k, false) : 1.0;
        sun *= all_of_them / max(drawn, 1e-3);
    }
    return sun;
}

// The fields' mip level at a point `cell` (cell units): a texel of level 0 is 1 / 32 of a cell
// (core/shadows.py FIELD); from how the point moves across the pixel (outside any branch)
float field_lod(vec2 cell) {
    vec2 dx = dFdx(cell), dy = dFdy(cell);
    return log2(max(sqrt(max(dot(dx, dx), dot(dy, dy))) * 32.0, 1e-6));
}

// How much longer a blade's shadow falls on the ground's slope than on level ground: a blade
// stands upright and the geometry casts it along the sun (no lower than 5°) onto the ground's
// plane at its root (_blade_vertex.glsl, SHADOW); per unit of the blade's height the shadow
// reaches n_y / (sun · n) across the ground's plan, against 1 / sun_y level. n: the ground's
// triangle here, from how the position changes across the pixel (no height map reads)
float shadow_length(vec3 world) {
    if (u_height_scale <= 0.0) return 1.0;
    vec3 n = cross(dFdy(world), dFdx(world));
    n = n.y < 0.0 ? -n : n;
    n = dot(n, n) > 1e-20 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    vec3 sun = normalize(vec3(u_light_dir.x, max(u_light_dir.y, 0.0872), u_light_dir.z));
    return sun.y * n.y / max(dot(sun, n), 0.0872);
}

// towards the sun across the design maps, per unit of a blade's height: where the blades stand
// whose shadows fall at a point of level ground (the sun no lower than 5°, as they are cast)
vec2 shadow_source() {
    vec3 sun = normalize(vec3(u_light_dir.x, max(u_light_dir.y, 0.0872), u_light_dir.z));
    return sun.xz / sun.y / max(u_grass_rect.zw - u_grass_rect.xy, vec2(1e-6));
}
#else
float unshadowed(vec2 uv, float d, float k, vec2 towards, vec2 cell, float lod) { return 1.0; }
float shadow_length(vec3 world) { return 1.0; }
float field_lod(vec2 cell) { return 0.0; }
vec2 shadow_source() { return vec2(0.0); }
#endif

in vec3 v_world;
out vec4 f_color;

void main() {
    vec2 p = v_world.xz;
    float inside = max(u_mesh, step(u_grass_rect.x, p.x) * step(u_grass_rect.y, p.y)
                 * step(p.x, u_grass_rect.z) * step(p.y, u_grass_rect.w));
    vec2 uv = soil_uv(p);
    float d = distance(u_eye.xz, p);
    float k = shadow_length(v_world);  // derivatives: outside any branch
    float lod = field_lod(p);  // world units are cell units
    // the shadows are worked out everywhere and kept inside the grass: no branch around the
    // fields' first read
    float sun = mix(1.0, unshadowed(uv, d, k, shadow_source(), p, lod), inside);
    f_color = vec4(soil(v_world, u_eye, inside, sun), 1.0);
}

#endif
