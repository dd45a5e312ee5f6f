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

// Technique colour view (thesis Figs. 7.1-7.6): geometry red, volume yellow, image blue, keeping
// the shading's brightness so the structure stays readable. Off (0) unless a renderer sets it.
uniform vec3 u_technique_color;
uniform float u_technique_view;

vec3 technique(vec3 lit) {
    float luma = dot(lit, vec3(0.299, 0.587, 0.114));
    return mix(lit, u_technique_color * clamp(0.35 + 2.0 * luma, 0.0, 1.0), u_technique_view);
}
