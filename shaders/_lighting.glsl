// One lighting model for every representation (thesis 6.4.3, eq. 6.9):
// light = I_ambient · AO · ambient + I_diffuse · diffuse · max(0, N·L)
// Grass blades are thin: a little light passes through from behind (translucency).
uniform vec3 u_light_dir;      // towards the light, normalised, world space
uniform vec3 u_light_color;    // I_diffuse
uniform vec3 u_ambient_color;  // I_ambient
uniform float u_translucency;

vec3 shade(vec3 albedo, vec3 n, float ao) {
    float lambert = max(dot(n, u_light_dir), 0.0);
    float through = u_translucency * max(dot(-n, u_light_dir), 0.0);
    return albedo * (u_ambient_color * ao + u_light_color * (lambert + through) * mix(0.6, 1.0, ao));
}
