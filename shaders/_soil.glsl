// The ground's colour (ground.glsl), shared with the blades' shadows (geometry.glsl, SHADOW),
// which paint the ground as it is without the sun's light: soil, darker and greener under the
// grass (the first grass type's density), lit by the ambient and diffuse light maps, fogged far away.
uniform vec3 u_soil_color;
uniform vec3 u_under_grass;   // soil colour under the grass
uniform vec3 u_fog_color;
uniform float u_fog_distance;
uniform vec4 u_grass_rect;    // xmin, zmin, xmax, zmax of the grassed cells

// the design maps span the grassed rectangle
vec2 soil_uv(vec2 p) {
    return (p - u_grass_rect.xy) / max(u_grass_rect.zw - u_grass_rect.xy, vec2(1e-6));
}

// `inside`: 1 over the grassed cells; `sun`: the share of the sun's light the point receives
vec3 soil(vec3 world, vec3 eye, float inside, float sun) {
    vec2 uv = soil_uv(world.xz);
    float grass = inside * textureLod(u_design, vec3(uv, 0.0), 0.0).x;  // the first type's
    vec3 albedo = mix(u_soil_color, u_under_grass, grass);
    vec3 ambient = mix(vec3(1.0), design_ambient(uv), inside);
    vec3 diffuse = mix(vec3(1.0), design_diffuse(uv), inside) * sun;
    vec3 color = shade(albedo, vec3(0.0, 1.0, 0.0), mix(1.0, 0.6, grass), ambient, diffuse);
    float fog = 1.0 - exp(-distance(eye, world) / u_fog_distance);
    return mix(color, u_fog_color, clamp(fog, 0.0, 1.0));
}
